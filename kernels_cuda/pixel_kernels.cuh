#pragma once
// Device-side pieces shared by the exact and the fast kernels. Inline device functions only:
// no __global__ here, so the two translation units (compiled with different float flags) never
// define the same kernel symbol.
#include <cuda_runtime.h>

namespace svgf::cuda::device {

__device__ __forceinline__ int pixel_x() {
  return static_cast<int>(blockIdx.x * blockDim.x + threadIdx.x);
}
__device__ __forceinline__ int pixel_y() {
  return static_cast<int>(blockIdx.y * blockDim.y + threadIdx.y);
}

// Adds the number of this block's threads with `flag` set to *count: a shared-memory integer
// tally, then one global atomic per block. Integer sums are order-free, so the total is the same
// for every schedule and block shape. Every thread of the block must call it (no early return).
__device__ __forceinline__ void count_block(bool flag, unsigned long long* count) {
  __shared__ unsigned int block_count;
  const bool first = threadIdx.x == 0 && threadIdx.y == 0;
  if (first) block_count = 0u;
  __syncthreads();
  if (flag) atomicAdd(&block_count, 1u);
  __syncthreads();
  if (first && block_count != 0u) atomicAdd(count, static_cast<unsigned long long>(block_count));
}

}  // namespace svgf::cuda::device

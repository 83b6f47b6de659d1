#pragma once
// Device-side pieces shared by the exact and the fast kernels. Inline device functions only:
// no __global__ here, so the two translation units (compiled with different float flags) never
// define the same kernel symbol.
#include <cstdint>

#include <cuda_runtime.h>

#include "core/tallies.h"

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

// Adds, for each bit b of `mask`, this block's threads with bit b set to counts[b] (shared
// tallies, then one global atomic per nonzero bit and block). Every thread must call it.
__device__ __forceinline__ void tally_block(uint32_t mask, unsigned long long* counts) {
  __shared__ unsigned int block_counts[kTallyBits];
  const int t = static_cast<int>(threadIdx.y * blockDim.x + threadIdx.x);
  const int threads = static_cast<int>(blockDim.x * blockDim.y);  // may be fewer than the bits
  for (int b = t; b < kTallyBits; b += threads) block_counts[b] = 0u;
  __syncthreads();
  for (int b = 0; mask != 0u && b < kTallyBits; ++b)
    if ((mask >> b) & 1u) atomicAdd(&block_counts[b], 1u);
  __syncthreads();
  for (int b = t; b < kTallyBits; b += threads)
    if (block_counts[b] != 0u) atomicAdd(&counts[b], static_cast<unsigned long long>(block_counts[b]));
}

}  // namespace svgf::cuda::device

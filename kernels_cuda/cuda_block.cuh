#pragma once
// CUDA's Block context for block kernels (core/block_reduce.h): one thread block of
// block::kThreads threads per block of rows, each thread taking rows t, t + 256, ... The
// scratch and the reduction's 256 partial sums live in dynamic shared memory. sum/min/max run
// the fixed tree of core/block_reduce.h (the CPU's reduce_rows evaluates the same one), so exact
// kernels give the CPU's bits. The methods are __host__ __device__ only so that a block kernel's
// SVGF_HD operator() compiles for both sides; they do their work in device code.
#include "core/block_reduce.h"
#include "core/hd.h"

namespace svgf::cuda {

class CudaBlock {
 public:
  SVGF_HD CudaBlock(float* scratch, float* partial) : scratch_(scratch), partial_(partial) {}

  template <class F>
  SVGF_HD void rows(const F& f) const {
#if defined(__CUDA_ARCH__)
    for (int k = 0; k < block::kRowsPerThread; ++k)
      f(static_cast<int>(threadIdx.x) + k * block::kThreads);
    __syncthreads();
#else
    (void)f;
#endif
  }
  template <class F>
  SVGF_HD float sum(const F& f) const { return reduce(f, block::SumOp{}); }
  template <class F>
  SVGF_HD float min(const F& f) const { return reduce(f, block::MinOp{}); }
  template <class F>
  SVGF_HD float max(const F& f) const { return reduce(f, block::MaxOp{}); }
  template <class F>
  SVGF_HD void once(const F& f) const {
#if defined(__CUDA_ARCH__)
    if (threadIdx.x == 0) f();
    __syncthreads();
#else
    (void)f;
#endif
  }
  SVGF_HD float* scratch() const { return scratch_; }

 private:
  template <class F, class Op>
  SVGF_HD float reduce(const F& f, Op op) const {
#if defined(__CUDA_ARCH__)
    const int t = static_cast<int>(threadIdx.x);
    partial_[t] = block::thread_partial(f, t, op);
    __syncthreads();
    for (int s = block::kThreads / 2; s > 0; s /= 2) {
      if (t < s) partial_[t] = op(partial_[t], partial_[t + s]);
      __syncthreads();
    }
    const float result = partial_[0];
    __syncthreads();  // nobody overwrites partial_ before every thread has read the result
    return result;
#else
    (void)f, (void)op;
    return 0.f;
#endif
  }
  float* scratch_;
  float* partial_;
};

template <class K>
__global__ void __launch_bounds__(block::kThreads) block_kernel(const K k) {
  extern __shared__ float shared[];
  const CudaBlock b(shared, shared + K::kScratchFloats);
  k(b, static_cast<int>(blockIdx.x));
}

}  // namespace svgf::cuda

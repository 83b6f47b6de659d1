#pragma once
// CUDA's Block context for block kernels (core/block_reduce.h): one thread block of
// block::kThreads threads per block of rows, each thread taking rows t, t + 256, ... The
// scratch and the reductions' warp totals (kReductionFloats) live in dynamic shared memory.
// Reductions run the fixed tree of core/block_reduce.h (the CPU's reduce_rows evaluates the same
// one), so exact kernels give the CPU's bits: each thread folds its rows, each warp folds its 32
// lanes by shuffles, lane 0 publishes the warp's total, one barrier, and every thread folds the
// 8 totals itself. The methods are __host__ __device__ only so that a block kernel's SVGF_HD
// operator() compiles for both sides; they do their work in device code.
#include "core/block_reduce.h"
#include "core/hd.h"

namespace svgf::cuda {

class CudaBlock {
 public:
  // Values one reduce() may carry, and the shared floats for their warp totals: two sets, used
  // in turn (below).
  static constexpr int kMaxValues = 16;
  static constexpr int kReductionFloats = 2 * kMaxValues * block::kWarps;

  SVGF_HD CudaBlock(float* scratch, float* totals) : scratch_(scratch), totals_(totals) {}

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
  SVGF_HD float sum(const F& f) const { return one(block::SumOp{}, f); }
  template <class F>
  SVGF_HD float min(const F& f) const { return one(block::MinOp{}, f); }
  template <class F>
  SVGF_HD float max(const F& f) const { return one(block::MaxOp{}, f); }

  // n <= N values of f(r, k) at once. The warp totals alternate between two sets: reduction
  // i + 2 overwrites set i's totals only after reduction i + 1's barrier, which every thread
  // reaches after it has read them, so one barrier a reduction is enough. (n is the same on
  // every thread: the shuffles run on full warps.)
  template <int N, class Op, class F>
  SVGF_HD void reduce(Op op, int n, const F& f, float* out) const {
#if defined(__CUDA_ARCH__)
    static_assert(N <= kMaxValues, "more values than the shared totals hold");
    const int t = static_cast<int>(threadIdx.x);
    const int lane = t % block::kWarpSize, warp = t / block::kWarpSize;
    float* const totals = totals_ + parity_ * kMaxValues * block::kWarps;
    parity_ ^= 1;
#pragma unroll
    for (int k = 0; k < N; ++k) {
      if (k >= n) break;
      float v = block::thread_partial([&](int r) { return f(r, k); }, t, op);
      for (int s = block::kWarpSize / 2; s > 0; s /= 2)
        v = op(v, __shfl_down_sync(0xffffffffu, v, s));
      if (lane == 0) totals[k * block::kWarps + warp] = v;
    }
    __syncthreads();
#pragma unroll
    for (int k = 0; k < N; ++k) {
      if (k >= n) break;
      float w[block::kWarps];
      for (int i = 0; i < block::kWarps; ++i) w[i] = totals[k * block::kWarps + i];
      out[k] = block::fold_warp_totals(w, op);
    }
#else
    (void)op, (void)n, (void)f, (void)out;
#endif
  }

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
  template <class Op, class F>
  SVGF_HD float one(Op op, const F& f) const {
    float r = 0.f;
    reduce<1>(op, 1, [&](int row, int) { return f(row); }, &r);
    return r;
  }
  float* scratch_;
  float* totals_;
  mutable int parity_ = 0;  // which set of totals the next reduction writes
};

template <class K>
__global__ void __launch_bounds__(block::kThreads) block_kernel(const K k) {
  extern __shared__ float shared[];
  const CudaBlock b(shared, shared + K::kScratchFloats);
  k(b, static_cast<int>(blockIdx.x));
}

}  // namespace svgf::cuda

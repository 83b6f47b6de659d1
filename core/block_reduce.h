#pragma once
// Block kernels: a kernel that works on a block of rows together (BMFR's per-block regression)
// rather than one pixel at a time. It is written once as an SVGF_HD template over a Block
// context; the CPU (kernels_cpu/cpu_block.h) and CUDA (kernels_cuda/cuda_block.cuh) provide it.
// What a Block offers:
//   rows(f)       f(r) for every row r in [0, kRows); every row is independent. Then a barrier.
//   sum(f)        the sum of f(r) over all rows, in the fixed order below, known to every thread
//   min(f), max(f) the same tree with min_f / max_f
//   reduce<N>(op, n, f, out)  n <= N values at once: out[k] = the tree of f(r, k) over all rows
//                 with op, for k < n; each value's tree is the one sum/min/max evaluate, so the
//                 bits are theirs, for the price of one reduction (one barrier on CUDA)
//   once(f)       f() by one thread (the only place a kernel writes shared state outside rows())
//   float* scratch()  kScratchFloats floats shared by the block (CUDA: shared memory)
// Code between these calls runs on every thread of a CUDA block with identical values (it may
// read results of the reductions and the scratch, and must not write shared state).
//
// The fixed order (determinism contract: one tree that both sides evaluate): a CUDA block has
// kThreads = 256 threads in kWarps = 8 warps of 32 and kRows = 1024 rows, four per thread.
//   1. thread t folds its rows t, t + 256, t + 512, t + 768 in that order, starting from the
//      first;
//   2. within each warp (threads 32 w + l): for s = 16, 8, 4, 2, 1, lane l < s takes
//      op(own, lane l + s's);
//   3. the 8 warp totals: for s = 4, 2, 1, total[w] = op(total[w], total[w + s]) for w < s.
// Steps 1-2 stay in registers on CUDA (shuffles), so a reduction costs one barrier. The CPU
// evaluates exactly this tree (reduce_rows), so results agree bit for bit.
#include "core/hd.h"
#include "core/vec.h"

namespace svgf::block {

constexpr int kThreads = 256;
constexpr int kRows = 1024;
constexpr int kRowsPerThread = kRows / kThreads;
constexpr int kWarpSize = 32;
constexpr int kWarps = kThreads / kWarpSize;

struct SumOp {
  SVGF_HD float operator()(float a, float b) const { return a + b; }
};
struct MinOp {
  SVGF_HD float operator()(float a, float b) const { return min_f(a, b); }
};
struct MaxOp {
  SVGF_HD float operator()(float a, float b) const { return max_f(a, b); }
};

// Step 1: thread t's share of a reduction, its four rows in order.
SVGF_HD_TEMPLATE
template <class Op, class F>
SVGF_HD float thread_partial(const F& f, int t, Op op) {
  float p = f(t);
  for (int k = 1; k < kRowsPerThread; ++k) p = op(p, f(t + k * kThreads));
  return p;
}

// Step 3 on the warp totals (total[0 .. kWarps)), in place; the result is total[0].
SVGF_HD_TEMPLATE
template <class Op>
SVGF_HD float fold_warp_totals(float* total, Op op) {
  for (int s = kWarps / 2; s > 0; s /= 2)
    for (int w = 0; w < s; ++w) total[w] = op(total[w], total[w + s]);
  return total[0];
}

// The whole tree on one thread (the CPU's Block, and tests).
template <class Op, class F>
float reduce_rows(const F& f, Op op) {
  float partial[kThreads];
  for (int t = 0; t < kThreads; ++t) partial[t] = thread_partial(f, t, op);
  float total[kWarps];
  for (int w = 0; w < kWarps; ++w) {
    float* lane = partial + w * kWarpSize;
    for (int s = kWarpSize / 2; s > 0; s /= 2)
      for (int l = 0; l < s; ++l) lane[l] = op(lane[l], lane[l + s]);
    total[w] = lane[0];
  }
  return fold_warp_totals(total, op);
}

}  // namespace svgf::block

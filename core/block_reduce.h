#pragma once
// Block kernels: a kernel that works on a block of rows together (BMFR's per-block regression)
// rather than one pixel at a time. It is written once as an SVGF_HD template over a Block
// context; the CPU (kernels_cpu/cpu_block.h) and CUDA (kernels_cuda/cuda_block.cuh) provide it.
// What a Block offers:
//   rows(f)       f(r) for every row r in [0, kRows); every row is independent. Then a barrier.
//   sum(f)        the sum of f(r) over all rows, in the fixed order below, known to every thread
//   min(f), max(f) the same tree with min_f / max_f
//   once(f)       f() by one thread (the only place a kernel writes shared state outside rows())
//   float* scratch()  kScratchFloats floats shared by the block (CUDA: shared memory)
// Code between these calls runs on every thread of a CUDA block with identical values (it may
// read results of sum()/min()/max() and the scratch, and must not write shared state).
//
// The fixed order (determinism contract: one tree that both sides evaluate): a CUDA block has
// kThreads = 256 threads and kRows = 1024 rows, four per thread. Thread t adds its rows
// t, t + 256, t + 512, t + 768 in that order, starting from the first; then the 256 partial
// sums are halved: for s = 128, 64, ..., 1, partial[t] = partial[t] + partial[t + s] for t < s.
// The CPU evaluates exactly this tree (reduce_rows), so sums agree bit for bit.
#include "core/hd.h"
#include "core/vec.h"

namespace svgf::block {

constexpr int kThreads = 256;
constexpr int kRows = 1024;
constexpr int kRowsPerThread = kRows / kThreads;

struct SumOp {
  SVGF_HD float operator()(float a, float b) const { return a + b; }
};
struct MinOp {
  SVGF_HD float operator()(float a, float b) const { return min_f(a, b); }
};
struct MaxOp {
  SVGF_HD float operator()(float a, float b) const { return max_f(a, b); }
};

// Thread t's share of a reduction: its four rows, in order.
SVGF_HD_TEMPLATE
template <class Op, class F>
SVGF_HD float thread_partial(const F& f, int t, Op op) {
  float p = f(t);
  for (int k = 1; k < kRowsPerThread; ++k) p = op(p, f(t + k * kThreads));
  return p;
}

// The whole tree on one thread (the CPU's Block, and tests).
template <class Op, class F>
float reduce_rows(const F& f, Op op) {
  float partial[kThreads];
  for (int t = 0; t < kThreads; ++t) partial[t] = thread_partial(f, t, op);
  for (int s = kThreads / 2; s > 0; s /= 2)
    for (int t = 0; t < s; ++t) partial[t] = op(partial[t], partial[t + s]);
  return partial[0];
}

}  // namespace svgf::block

#pragma once
// The CPU's Block context for block kernels (core/block_reduce.h): one block runs on one TBB
// task, its "threads" in sequence. rows() is a loop over the rows, sum/min/max evaluate the
// fixed tree, once() is a call, and the scratch is the task's own memory. Blocks run in
// parallel; a block's result depends only on its index, so any thread count gives the same bits.
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/block_reduce.h"
#include "kernels_cpu/ieee_guard.h"

namespace svgf::cpu {

class CpuBlock {
 public:
  explicit CpuBlock(float* scratch) : scratch_(scratch) {}
  template <class F>
  void rows(const F& f) const {
    for (int r = 0; r < block::kRows; ++r) f(r);
  }
  template <class F>
  float sum(const F& f) const { return block::reduce_rows(f, block::SumOp{}); }
  template <class F>
  float min(const F& f) const { return block::reduce_rows(f, block::MinOp{}); }
  template <class F>
  float max(const F& f) const { return block::reduce_rows(f, block::MaxOp{}); }
  template <int N, class Op, class F>
  void reduce(Op op, int n, const F& f, float* out) const {
    for (int k = 0; k < n; ++k) out[k] = block::reduce_rows([&](int r) { return f(r, k); }, op);
  }
  template <class F>
  void once(const F& f) const { f(); }
  float* scratch() const { return scratch_; }

 private:
  float* scratch_;
};

// Runs kernel(block, b) for b in [0, blocks); Kernel::kScratchFloats floats of scratch each.
template <class Kernel>
void for_each_block(int blocks, const Kernel& kernel) {
  tbb::parallel_for(tbb::blocked_range<int>(0, blocks, 1), [&](const tbb::blocked_range<int>& r) {
    ScopedIeeeFloat ieee;
    std::vector<float> scratch(Kernel::kScratchFloats);
    for (int b = r.begin(); b != r.end(); ++b) {
      CpuBlock block(scratch.data());
      kernel(block, b);
    }
  });
}

}  // namespace svgf::cpu

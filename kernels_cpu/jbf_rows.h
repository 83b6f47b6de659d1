#pragma once
// The joint bilateral filter's pass (both forms) on the CPU as vectorized rows (kernels_cpu/
// row_tools.h): the per-pixel kernel's terms (jbf_weight, methods/jbf/weight.h) in its tap
// order, so the same bits (tests/jbf_cpu_rows_test.cpp). Picked by the CPU engine in every mode
// (the JBF's CPU runs exact arithmetic).
#include "kernels_cpu/cpu_engine.h"
#include "methods/jbf/filter.h"

namespace svgf::cpu {

void run_jbf_rows(const JbfPass<ExactArith>& kernel, int width, int height);

template <>
struct PixelDriver<JbfPass<ExactArith>> {
  static void run(const JbfPass<ExactArith>& k, int w, int h) { run_jbf_rows(k, w, h); }
};

}  // namespace svgf::cpu

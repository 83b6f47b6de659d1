#pragma once
// The CIS 565 wavelet filter's a-trous pass on the CPU as vectorized rows (kernels_cpu/
// row_tools.h): the per-pixel kernel's terms (wavelet_weight, methods/wavelet/atrous.h) in its
// tap order, so the same bits (tests/wavelet_cpu_rows_test.cpp). Picked by the CPU engine for exact mode.
#include "kernels_cpu/cpu_engine.h"
#include "methods/wavelet/atrous.h"

namespace svgf::cpu {

using WaveletExactIteration = WaveletIteration<ExactArith, NormalPower<ExactArith>>;

void run_wavelet_rows(const WaveletExactIteration& kernel, int width, int height);

template <>
struct PixelDriver<WaveletExactIteration> {
  static void run(const WaveletExactIteration& k, int w, int h) { run_wavelet_rows(k, w, h); }
};

}  // namespace svgf::cpu

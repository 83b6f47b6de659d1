#pragma once
// SVGF's CPU drivers for the two wide-neighbourhood stages. The per-pixel kernels in
// methods/svgf/ loop over taps inside each pixel, which no compiler vectorizes; these loop over
// taps outside and over a row of pixels inside, so each inner loop is straight-line SIMD code.
// Every pixel still sums the same terms, computed by the same methods/svgf/ functions, in the
// same tap order: the result is bitwise the per-pixel kernel's (tests/svgf_cpu_rows_test.cpp
// checks it), and so the GPU's. The CPU engine picks them through PixelDriver.
#include "kernels_cpu/cpu_engine.h"
#include "methods/svgf/atrous.h"
#include "methods/svgf/variance.h"

namespace svgf::cpu {

void run_atrous_rows(const AtrousKernel& kernel, int width, int height);
void run_variance_rows(const VarianceKernel& kernel, int width, int height);

template <>
struct PixelDriver<AtrousKernel> {
  static void run(const AtrousKernel& k, int w, int h) { run_atrous_rows(k, w, h); }
};
template <>
struct PixelDriver<VarianceKernel> {
  static void run(const VarianceKernel& k, int w, int h) { run_variance_rows(k, w, h); }
};

}  // namespace svgf::cpu

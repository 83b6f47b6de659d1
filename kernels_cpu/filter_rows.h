#pragma once
// Vectorizable CPU drivers for the two wide-neighbourhood stages. The per-pixel kernels in core/
// loop over taps inside each pixel, which no compiler vectorizes; these loop over taps outside
// and over a row of pixels inside, so each inner loop is straight-line SIMD code. Every pixel
// still sums the same terms, computed by the same core/ functions, in the same tap order: the
// result is bitwise the per-pixel kernel's (tests/cpu_rows_test.cpp checks it), and so the GPU's.
#include "core/atrous.h"
#include "core/variance.h"

namespace svgf::cpu {

void run_atrous_rows(const AtrousKernel& kernel, int width, int height);
void run_variance_rows(const VarianceKernel& kernel, int width, int height);

}  // namespace svgf::cpu

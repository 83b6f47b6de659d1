#pragma once
// SVGF's CPU drivers for the two wide-neighbourhood stages and the reprojection. The per-pixel
// kernels in methods/svgf/ loop over taps inside each pixel, which no compiler vectorizes;
// these loop over taps outside and over a row of pixels inside, so each inner loop is
// straight-line SIMD code.
// Every pixel still sums the same terms, computed by the same methods/svgf/ functions, in the
// same tap order: the result is bitwise the per-pixel kernel's (tests/svgf_cpu_rows_test.cpp
// checks it), and so the GPU's. The CPU engine picks them through PixelDriver.
// The reprojection's row driver (svgf_reproject_rows.cpp) runs its per-pixel kernel's history
// reads (bilinear taps, 3x3 fallback) and its blend as vector code over a row; A-SVGF's
// gradient a-trous and lambda stages (svgf_gradient_rows.cpp) their interior strata.
#include "kernels_cpu/cpu_engine.h"
#include "methods/svgf/atrous.h"
#include "methods/svgf/gradient.h"
#include "methods/svgf/reproject.h"
#include "methods/svgf/variance.h"

namespace svgf::cpu {

void run_atrous_rows(const AtrousKernel& kernel, int width, int height);
void run_variance_rows(const VarianceKernel& kernel, int width, int height);
void run_reproject_rows(const ReprojectKernel& kernel, int width, int height);
void run_gradient_samples_rows(const GradientSamplesKernel& kernel, int strata_width,
                               int strata_height);
void run_gradient_atrous_rows(const GradientAtrousKernel& kernel, int strata_width,
                              int strata_height);
void run_gradient_lambda_rows(const GradientLambdaKernel& kernel, int strata_width,
                              int strata_height);

// The reprojection and variance rows stream the accumulation's variance plane, which the CPU
// denoiser always gives; a kernel without one (the variance then derived from the moments,
// methods/svgf/variance.h) runs per pixel.
template <>
struct PixelDriver<ReprojectKernel> {
  static void run(const ReprojectKernel& k, int w, int h) {
    if (k.accumulated.variance) run_reproject_rows(k, w, h);
    else for_each_pixel(w, h, k);
  }
};

template <>
struct PixelDriver<GradientSamplesKernel> {
  static void run(const GradientSamplesKernel& k, int w, int h) {
    run_gradient_samples_rows(k, w, h);
  }
};

template <>
struct PixelDriver<GradientAtrousKernel> {
  static void run(const GradientAtrousKernel& k, int w, int h) {
    run_gradient_atrous_rows(k, w, h);
  }
};

template <>
struct PixelDriver<GradientLambdaKernel> {
  static void run(const GradientLambdaKernel& k, int w, int h) {
    run_gradient_lambda_rows(k, w, h);
  }
};

// Exact mode's kernels with any normal-weight power (the rows pick theirs from phi_normal).
template <class Power>
struct PixelDriver<AtrousIteration<SvgfExact, Power, IllumVarView>> {
  static void run(const AtrousIteration<SvgfExact, Power, IllumVarView>& k, int w, int h) {
    run_atrous_rows(AtrousKernel{k.guides, k.in, k.out, k.step, k.params}, w, h);
  }
};
template <class Power>
struct PixelDriver<VarianceEstimate<SvgfExact, Power, IllumVarView>> {
  static void run(const VarianceEstimate<SvgfExact, Power, IllumVarView>& k, int w, int h) {
    if (!k.accumulated.variance) return for_each_pixel(w, h, k);
    run_variance_rows(
        VarianceKernel{k.guides, k.accumulated, k.moment1, k.moment2, k.history, k.out, k.params,
                       k.color_history},
        w, h);
  }
};

}  // namespace svgf::cpu

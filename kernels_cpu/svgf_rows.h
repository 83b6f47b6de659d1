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
#include "methods/svgf/sinks.h"
#include "methods/svgf/variance.h"

namespace svgf::cpu {

// Where an a-trous iteration's rows go when the pipeline fuses its outputs into the iterations
// (methods/svgf/flavors.h, kFusedOutputs): the last iteration remodulates its result instead of
// storing it (`remodulate`, then kernel.out is not written), the feedback tap's also copies its
// result's color into the color history. Each row through the same functions as the sinks.
struct AtrousRowOutputs {
  const RemodulateSink* remodulate = nullptr;
  RgbView color_history;  // none where r is null
};
void run_atrous_rows(const AtrousKernel& kernel, int width, int height,
                     const AtrousRowOutputs& outputs = {});
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

// Exact mode's kernels with any normal-weight power (the rows pick theirs from phi_normal), and
// the a-trous with any of the pipeline's outputs: the next iteration's buffer, the remodulation,
// either with the feedback tap's copy (methods/svgf/pipeline.h).
inline void run_atrous_into(const AtrousKernel& k, const IllumVarView& out, int w, int h,
                            AtrousRowOutputs o = {}) {
  run_atrous_rows(AtrousKernel{k.guides, k.in, out, k.step, k.params}, w, h, o);
}
inline void run_atrous_into(const AtrousKernel& k, const RemodulateSink& out, int w, int h,
                            AtrousRowOutputs o = {}) {
  o.remodulate = &out;
  run_atrous_rows(k, w, h, o);
}
template <class Out>
void run_atrous_into(const AtrousKernel& k, const FeedbackTee<Out>& out, int w, int h) {
  AtrousRowOutputs o;
  o.color_history = out.color_history;
  run_atrous_into(k, out.out, w, h, o);
}
template <class Power, class Out>
struct PixelDriver<AtrousIteration<SvgfExact, Power, Out>> {
  static void run(const AtrousIteration<SvgfExact, Power, Out>& k, int w, int h) {
    run_atrous_into(AtrousKernel{k.guides, k.in, IllumVarView(), k.step, k.params}, k.out, w, h);
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

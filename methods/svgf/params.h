#pragma once
// Every tunable of the SVGF pipeline, with its default, in one place. Defaults follow NVIDIA
// Falcor's SVGFPass (which follows Schied et al. 2017); docs/svgf.md lists where each comes from.
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/binomial.h"
#include "core/hd.h"

namespace svgf {

// What shortens a history the frame contradicts (issue 12, item 3; docs/svgf.md: Anti-lag).
enum class Antilag : int {
  Off,         // nothing (the paper, Falcor)
  Statistics,  // the history against this frame's neighbourhood statistics (reproject.h)
  Gradient,    // A-SVGF: the temporal gradients of the frame's re-shaded samples (gradient.h);
               // a frame without gradient samples falls back to Statistics
};

inline const char* to_string(Antilag a) {
  switch (a) {
    case Antilag::Off: return "off";
    case Antilag::Statistics: return "statistics";
    case Antilag::Gradient: return "gradient";
  }
  return "?";
}

// "off", "statistics" (alias "on", its name before the gradient mode existed), "gradient";
// std::invalid_argument naming the choices.
inline Antilag parse_antilag(const std::string& s) {
  if (s == "off") return Antilag::Off;
  if (s == "statistics" || s == "on") return Antilag::Statistics;
  if (s == "gradient") return Antilag::Gradient;
  throw std::invalid_argument("svgf: --antilag must be off, statistics (or on) or gradient, got '" +
                              s + "'");
}
// Whether direct and indirect illumination are filtered apart (SvgfParams::split).
enum class SplitMode { Auto, Off, On };

struct SvgfParams {
  // Demodulation: albedo below this is clamped, so black albedo does not divide by zero.
  float albedo_epsilon = 1e-3f;

  // Temporal accumulation (paper Sec. 4.1): exponential moving average with factor
  // max(alpha, 1/history) so the first frames are a plain mean. The paper blends with 0.2,
  // Falcor with 0.05 and a cap of 32; the longer average (0.03, 64) takes out the last
  // frame-to-frame drops on a static scene (docs/svgf.md: Static convergence).
  float alpha = 0.03f;
  float moments_alpha = 0.2f;
  int history_cap = 64;

  // Anti-lag from the history's disagreement with this frame (methods/svgf/reproject.h): a
  // history whose luminance lies more than antilag_low standard errors from the mean of its
  // (2 antilag_radius + 1)^2 neighbourhood loses a share of its length, all of it from
  // antilag_high on. antilag_relative (of the luminance, at least antilag_floor) widens the
  // tolerance for the bias reprojection and filtering leave. 5x5 and 4..8 fire far less on
  // still pixels than 3x3 and 3..6 (docs/svgf.md: Anti-lag). The default is A-SVGF's
  // gradients, with this rule on frames that carry none (docs/svgf.md: Defaults).
  Antilag antilag = Antilag::Gradient;
  int antilag_radius = 2;
  float antilag_low = 4.f;
  float antilag_high = 8.f;
  float antilag_relative = 0.05f;
  float antilag_floor = 1e-3f;

  // Temporal anti-aliasing after remodulation (core/taa.h; issue 12's seed, the jacquespillet
  // CUDA SVGF, blends 0.1): the output is blended with the previous TAA output, reprojected and
  // clamped to this frame's YCoCg neighbourhood. Off by default, as in Falcor's SVGFPass (TAA is
  // its own pass there).
  bool taa = false;
  float taa_alpha = 0.1f;

  // A-SVGF (Schied et al. 2018; methods/svgf/gradient.h, docs/svgf.md): the per-stratum
  // temporal gradients are filtered by gradient_iterations a-trous steps of 3x3 taps, 1, 2, 4,
  // ... strata apart (Schied's reference code: 3x3 box taps, 5 iterations), edge-stopped by
  // mesh id, depth and normal at each stratum's sample with SVGF's own tolerances (phi_depth 1,
  // phi_normal 128), then drive alpha' = (1 - lambda) alpha + lambda. One step: more average
  // a moving shadow's edge away (3 steps reach 21 pixels; docs/svgf.md: Defaults).
  int gradient_iterations = 1;
  float gradient_phi_depth = 1.f;
  float gradient_phi_normal = 128.f;
  // A pixel's lambda is the largest of the strata within gradient_lambda_radius of its own
  // (Schied's reference code and its ports: gGradientFilterRadius); 0 reads its own alone.
  int gradient_lambda_radius = 1;

  // Reprojection tap tests. A tap is kept when its mesh id matches, its world normals agree to
  // within reproject_normal_cos, and |z_then - z_prev| <= scale * fwidth(z) + relative * z.
  float reproject_depth_gradient_scale = 10.f;
  float reproject_depth_relative = 0.03f;
  float reproject_normal_cos = 0.9f;
  // z_prev is compared with the depth this pixel's point had in the previous frame's camera
  // (from the frames' cameras, core/previous_depth.h), not with z: under a fast turn or dolly
  // the depth of a still wall point changes by more than reproject_depth_relative from frame to
  // frame, and a fifth of the pixels lost their history every frame (docs/svgf.md). This
  // project's choice (NRD's 2.5D motion vectors carry the view-Z change for the same reason);
  // false: Falcor's and the paper's comparison with z itself.
  bool reproject_camera_depth = true;
  // Bilinear taps whose kept weights sum below this count as no reprojection (Falcor: 0.01).
  float reproject_min_weight = 0.01f;

  // Variance (paper Sec. 4.2): a 7x7 bilateral spatial estimate while history < this.
  int spatial_variance_history = 4;
  int spatial_variance_radius = 3;
  float spatial_variance_phi_depth = 3.f;  // depth tolerance of the spatial estimate (Falcor)
  // The filter's variance is that of the accumulated mean, the moments' sample variance / n for
  // about n = min(history, (2 - alpha) / alpha) accumulated samples (methods/svgf/variance.h),
  // so the luminance edge-stopping tightens as the history grows and the spatial filter steps
  // back on converged pixels. Off: the sample variance itself, as in the paper and Falcor.
  bool variance_of_mean = true;

  // Edge-stopping functions of the a-trous filter (paper Eq. 3-4).
  int iterations = 4;     // Falcor: 4; the paper uses 5
  // Iteration whose output is the next frame's color history; -1: none (the unfiltered
  // accumulation is fed back). The paper feeds back iteration 0, Falcor iteration 1; both
  // re-blur the history every frame, so a static scene loses detail frame after frame
  // (docs/svgf.md: Static convergence); ours feeds back the unfiltered accumulation.
  int feedback_tap = -1;
  float phi_color = 4.f;  // the paper's sigma_l; Falcor's is 10
  float phi_normal = 128.f;
  float phi_depth = 1.f;
  float variance_epsilon = 1e-4f;  // added under the square root of the luminance sigma
  float depth_gradient_floor = 1e-8f;

  // Separate direct and indirect filtering (issue 12, item 2; Lighthouse2's Optix7Filter, which
  // keeps luminance moments per signal and filters each with its own variance): when a frame
  // carries `direct` and `indirect`, each runs the whole frame above with its own history,
  // moments and variance (direct with the emission, indirect without), and the two remodulated
  // results are added (docs/svgf.md: Direct and indirect). Auto: split when the frame carries
  // both; On: a frame without them is an error; Off: `color` alone, as before.
  SplitMode split = SplitMode::Auto;
  // The indirect signal's a-trous iterations and luminance edge-stopping; -1: as iterations and
  // phi_color. (Lighthouse2 filters both signals alike; these let the noisier indirect have a
  // wider filter.)
  int indirect_iterations = -1;
  float indirect_phi_color = -1.f;

  // Whether an a-trous iteration's output is the history; otherwise the unfiltered
  // accumulation is, and the reprojection writes it there directly (methods/svgf/pipeline.h).
  bool feeds_back_iteration() const { return feedback_tap >= 0 && feedback_tap < iterations; }

  // The parameters the indirect signal is filtered with.
  SvgfParams indirect() const {
    SvgfParams q = *this;
    if (indirect_iterations >= 0) q.iterations = indirect_iterations;
    if (indirect_phi_color > 0.f) q.phi_color = indirect_phi_color;
    return q;
  }

  // std::invalid_argument naming the flag (or the member, for those without one) and its range.
  // Any value accepted here keeps every weight finite (tests/bad_input_test.cpp).
  void validate() const {
    auto fail = [](const std::string& what) { throw std::invalid_argument("svgf: " + what); };
    auto in_unit = [&](float v, const char* name) {  // (0, 1]
      if (!(v > 0.f && v <= 1.f)) fail(std::string(name) + " must be in (0, 1], got " + std::to_string(v));
    };
    auto at_least = [&](float v, float lo, const char* name) {
      if (!(std::isfinite(v) && v >= lo))
        fail(std::string(name) + " must be finite and >= " + std::to_string(lo) + ", got " +
             std::to_string(v));
    };
    if (iterations < 0 || iterations > 12)
      fail("--iterations must be in [0, 12], got " + std::to_string(iterations));
    // A tap at or past the last iteration feeds back the unfiltered accumulation, like -1.
    if (feedback_tap < -1 || feedback_tap > 11)
      fail("--feedback-tap must be in [-1, 11], got " + std::to_string(feedback_tap));
    in_unit(alpha, "--alpha");
    in_unit(moments_alpha, "--moments-alpha");
    in_unit(taa_alpha, "--svgf-taa-alpha");
    if (!(std::isfinite(phi_color) && phi_color > 0.f))
      fail("--phi-color must be finite and > 0, got " + std::to_string(phi_color));
    at_least(phi_normal, 0.f, "--phi-normal");
    at_least(phi_depth, 0.f, "--phi-depth");
    if (!(albedo_epsilon > 0.f && albedo_epsilon <= 1.f))
      fail("albedo_epsilon must be in (0, 1], got " + std::to_string(albedo_epsilon));
    if (history_cap < 1 || history_cap > 4096)
      fail("--history-cap must be in [1, 4096], got " + std::to_string(history_cap));
    if (antilag_radius < 1 || antilag_radius > 3)
      fail("--antilag-radius must be in [1, 3], got " + std::to_string(antilag_radius));
    at_least(antilag_low, 0.f, "--antilag-low");
    if (!(std::isfinite(antilag_high) && antilag_high > antilag_low))
      fail("--antilag-high must be finite and > --antilag-low (" + std::to_string(antilag_low) +
           "), got " + std::to_string(antilag_high));
    at_least(antilag_relative, 0.f, "--antilag-relative");
    if (gradient_iterations < 0 || gradient_iterations > 8)
      fail("--gradient-iterations must be in [0, 8], got " + std::to_string(gradient_iterations));
    at_least(gradient_phi_depth, 0.f, "--gradient-phi-depth");
    at_least(gradient_phi_normal, 0.f, "--gradient-phi-normal");
    if (gradient_lambda_radius < 0 || gradient_lambda_radius > 3)
      fail("--gradient-lambda-radius must be in [0, 3], got " +
           std::to_string(gradient_lambda_radius));
    if (!(std::isfinite(antilag_floor) && antilag_floor > 0.f))
      fail("antilag_floor must be finite and > 0, got " + std::to_string(antilag_floor));
    at_least(reproject_depth_gradient_scale, 0.f, "reproject_depth_gradient_scale");
    at_least(reproject_depth_relative, 0.f, "reproject_depth_relative");
    if (!(reproject_normal_cos >= -1.f && reproject_normal_cos <= 1.f))
      fail("reproject_normal_cos must be in [-1, 1], got " + std::to_string(reproject_normal_cos));
    at_least(reproject_min_weight, 0.f, "reproject_min_weight");
    if (spatial_variance_radius < 0 || spatial_variance_radius > 16)
      fail("spatial_variance_radius must be in [0, 16], got " +
           std::to_string(spatial_variance_radius));
    at_least(spatial_variance_phi_depth, 0.f, "spatial_variance_phi_depth");
    if (!(std::isfinite(variance_epsilon) && variance_epsilon > 0.f))
      fail("variance_epsilon must be finite and > 0, got " + std::to_string(variance_epsilon));
    if (!(std::isfinite(depth_gradient_floor) && depth_gradient_floor > 0.f))
      fail("depth_gradient_floor must be finite and > 0, got " +
           std::to_string(depth_gradient_floor));
    if (indirect_iterations < -1 || indirect_iterations > 12)
      fail("--indirect-iterations must be -1 (as --iterations) or in [0, 12], got " +
           std::to_string(indirect_iterations));
    if (!(indirect_phi_color == -1.f || (std::isfinite(indirect_phi_color) && indirect_phi_color > 0.f)))
      fail("--indirect-phi-color must be -1 (as --phi-color) or finite and > 0, got " +
           std::to_string(indirect_phi_color));
  }
};

// Named configurations (--svgf-preset):
//   "default"   the defaults above: "converge" with A-SVGF's anti-lag (docs/svgf.md: Defaults);
//   "falcor"    Falcor's SVGFPass: 4 iterations, feedback tap 1, phi_color 10, alpha 0.05,
//               history cap 32, the sample variance, no anti-lag (the defaults until issue 12);
//   "paper"     Schied et al. 2017: Falcor's with 5 iterations, tap 0, sigma_l 4, alpha 0.2;
//   "converge"  the defaults without the anti-lag: what makes a static scene converge
//               (docs/svgf.md: Static convergence), the unfiltered accumulation fed back (tap
//               -1), the variance of the mean, sigma_l 4, alpha 0.03, cap 64; alone it keeps a
//               one-frame outlier or a change of light in its history for many frames.
// Throws std::invalid_argument naming the choices.
inline SvgfParams svgf_preset(const std::string& name) {
  SvgfParams p;
  if (name == "default") return p;
  if (name == "converge") {
    p.antilag = Antilag::Off;
    return p;
  }
  p.feedback_tap = 1;
  p.variance_of_mean = false;
  p.phi_color = 10.f;
  p.alpha = 0.05f;
  p.history_cap = 32;
  p.antilag = Antilag::Off;
  p.gradient_iterations = 3;
  if (name == "falcor") return p;
  if (name == "paper") {
    p.iterations = 5;
    p.feedback_tap = 0;
    p.phi_color = 4.f;
    p.alpha = 0.2f;
    p.moments_alpha = 0.2f;
    return p;
  }
  throw std::invalid_argument("svgf: --svgf-preset must be default, falcor, paper or converge, got '" +
                              name + "'");
}

inline const char* to_string(SplitMode m) {
  switch (m) {
    case SplitMode::Auto: return "auto";
    case SplitMode::Off: return "off";
    case SplitMode::On: return "on";
  }
  return "?";
}
// Throws std::invalid_argument naming the choices.
inline SplitMode parse_split_mode(const std::string& s) {
  if (s == "auto") return SplitMode::Auto;
  if (s == "off") return SplitMode::Off;
  if (s == "on") return SplitMode::On;
  throw std::invalid_argument("svgf: --svgf-split must be auto, off or on, got '" + s + "'");
}

// Fixed numbers of the method, not tunables. Functions rather than constexpr arrays, because a
// namespace-scope array cannot be indexed from device code.

// B3-spline a-trous kernel (1/16, 1/4, 3/8, 1/4, 1/16) at offset |d| in 0..2; the 2-D weight is
// b3(|dx|) * b3(|dy|). Exact binary fractions: every weight and product is exact.
SVGF_HD float b3_weight(int d) { return binomial_weight(5, d); }
// 3x3 Gaussian (1/4, 1/2, 1/4) of the variance prefilter (paper Eq. 5), at offset |d| in 0..1.
SVGF_HD float gauss3_weight(int d) { return binomial_weight(3, d); }

}  // namespace svgf

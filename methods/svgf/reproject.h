#pragma once
// Stage 2: reproject and accumulate (paper Sec. 4.1, Falcor's SVGFReproject).
// Each pixel follows its motion vector into the previous frame, reads the color and luminance
// moments history through the 2x2 bilinear taps that pass the consistency tests (same mesh,
// similar depth and normal), falls back to the consistent pixels of the 3x3 neighbourhood, and
// blends the new sample in with alpha = max(alpha_min, 1 / history). No consistent tap: the
// history restarts at length 1 (disocclusion). An anti-lag (params.antilag) shortens a history
// the frame contradicts: the neighbourhood statistics below, or A-SVGF's lambda of the pixel's
// stratum (methods/svgf/gradient.h), alpha' = (1 - lambda) alpha + lambda.
#include <cmath>

#include "core/arith.h"
#include "core/bilinear_taps.h"
#include "core/hd.h"
#include "core/modulation.h"
#include "core/previous_depth.h"
#include "core/views.h"
#include "methods/svgf/demodulate.h"
#include "methods/svgf/gradient.h"
#include "methods/svgf/params.h"
#include "methods/svgf/variance.h"

namespace svgf {

// PrevGuides: how the previous frame's depth, normal and mesh id are stored: GuideView's
// planes, or PackedGuides (depth + normal as one 16-byte load a tap: the packed flavors, whose
// denoiser keeps the previous frame's packed guides as its history; methods/svgf/denoiser.h).
template <class PrevGuides>
struct ReprojectKernelT {
  GuideView guides;           // this frame
  PrevGuides prev_guides;     // the previous frame's depth, normal and mesh id
  // The depth this frame's points had in the previous frame's camera (the identity when the
  // camera did not move, or when params.reproject_camera_depth is off).
  PreviousViewDepth previous_depth;
  ConstRgbView illumination;  // this frame, demodulated
  // This frame's inputs, for the anti-lag's neighbourhood (demodulated again where it reads a
  // neighbour, so the stage needs nothing that another pixel of the same launch writes).
  ConstRgbView color;
  ConstRgbView albedo;
  ConstRgbView emission;  // optional
  // History, as the previous frame left it.
  ConstRgbView prev_color;    // the feedback tap of the previous frame's a-trous
  const float* prev_moment1 = nullptr;  // E[l]
  const float* prev_moment2 = nullptr;  // E[l^2]
  const float* prev_history = nullptr;  // frames accumulated (1 .. history_cap)
  bool has_history = false;   // false on the first frame and after reset()
  // A-SVGF's lambda per stratum (strata_along(width) a row), when the gradient stages ran this
  // frame; none: the statistics anti-lag stands in for it where params.antilag asks for one.
  const float* gradient_lambda = nullptr;
  // Outputs.
  // Blended color and the temporal variance E[l^2] - E[l]^2 (moment_variance; no variance
  // plane: the variance stage derives it from the moments, methods/svgf/variance.h).
  IllumVarView accumulated;
  float* moment1 = nullptr;
  float* moment2 = nullptr;
  float* history = nullptr;
  SvgfParams params;

  // What every previous-frame tap of pixel (x, y) (index i) is tested against, gathered once:
  // its mesh, the depth its point had in the previous camera, the depth tolerance, its normal.
  struct TapTest {
    uint32_t mesh;
    float depth_then;
    float tolerance;
    Vec3 normal;
  };
  SVGF_HD TapTest tap_test(int x, int y, int i) const {
    const float z = guides.depth[i];
    const float tolerance = params.reproject_depth_gradient_scale * guides.depth_fwidth(i) +
                            params.reproject_depth_relative * z;
    return {guides.mesh_id[i], previous_depth.at(x, y, z), tolerance, guides.normal.load(i)};
  }
  // May the previous frame's pixel (xp, yp) stand for the pixel of test t?
  SVGF_HD bool tap_consistent(const TapTest& t, int xp, int yp) const {
    return prev_guides.inside(xp, yp) && tap_matches(t, prev_guides.index(xp, yp));
  }
  // The same for a previous pixel j inside the image: same mesh, similar depth and normal.
  SVGF_HD bool tap_matches(const TapTest& t, int j) const { return tap_matches(t, tap_guides(j)); }

  // What the tests read of a previous pixel.
  struct TapGuides {
    uint32_t mesh;
    float depth;
    Vec3 normal;
  };
  SVGF_HD TapGuides tap_guides(int j) const {
    const DepthNormal g = prev_guides.depth_normal(j);
    return {prev_guides.mesh_id[j], g.depth, g.normal};
  }
  // All three tests are evaluated (no early exit), so a vectorized caller loads unconditionally.
  SVGF_HD bool tap_matches(const TapTest& t, const TapGuides& g) const {
    const bool same_mesh = t.mesh == g.mesh;
    const bool near_depth = abs_f(t.depth_then - g.depth) <= t.tolerance;  // NaN: no
    const bool near_normal = dot(t.normal, g.normal) >= params.reproject_normal_cos;
    return same_mesh & near_depth & near_normal;
  }

  struct History {
    Vec3 color;
    Vec2 moments;
    float length = 0.f;
    bool valid = false;
  };

  // The history the previous frame left at pixel j: one tap's values.
  SVGF_HD History tap_history(int j) const {
    History h;
    h.color = prev_color.load(j);
    h.moments = make_vec2(prev_moment1[j], prev_moment2[j]);
    h.length = prev_history[j];
    h.valid = true;
    return h;
  }

  // Where pixel (x, y) lies in the previous frame, (px, py); false when it has no history to
  // read there (no surface, or motion far outside or NaN: no float-to-int conversion out of
  // range follows). The tests are all evaluated (a vectorized caller loads unconditionally).
  SVGF_HD bool previous_position(int x, int y, int i, float& px, float& py) const {
    px = static_cast<float>(x) + guides.motion_x[i];
    py = static_cast<float>(y) + guides.motion_y[i];
    return guides.is_surface(i) & (abs_f(px) < 1e7f) & (abs_f(py) < 1e7f);
  }

  // Adds the previous frame's pixel j, weighted w, to the sums h and weight_sum.
  SVGF_HD void add_tap(History& h, float& weight_sum, int j, float w) const {
    add_tap(h, weight_sum, tap_history(j), w);
  }
  // The same with the tap's values read: `tap` (tap_history), weighted w.
  SVGF_HD static void add_tap(History& h, float& weight_sum, const History& tap, float w) {
    h.color += tap.color * w;
    h.moments += tap.moments * w;
    h.length = h.length + tap.length * w;
    weight_sum = weight_sum + w;
  }

  // The sums h divided by what they weigh: a history read.
  SVGF_HD static History normalized(History h, float weight) {
    h.color = h.color / weight;
    h.moments = h.moments / weight;
    h.length = h.length / weight;
    h.valid = true;
    return h;
  }

  SVGF_HD History read_history(int x, int y, int i) const {
    History h;
    float px = 0.f, py = 0.f;
    if (!has_history || !previous_position(x, y, i, px, py)) return h;
    const BilinearTaps taps = BilinearTaps::at(px, py);
    const TapTest test = tap_test(x, y, i);
    float weight_sum = 0.f;
    for (int k = 0; k < 4; ++k) {
      const int xk = taps.x(k);
      const int yk = taps.y(k);
      if (tap_consistent(test, xk, yk))
        add_tap(h, weight_sum, prev_guides.index(xk, yk), taps.weight(k));
    }
    if (weight_sum >= params.reproject_min_weight) return normalized(h, weight_sum);
    // Fallback: the consistent pixels of the 3x3 block around the nearest previous pixel, equally
    // weighted, in the hope of finding the surface somewhere near (Falcor).
    h = History();
    const int xn = nearest(px), yn = nearest(py);
    float count = 0.f;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx)
        if (tap_consistent(test, xn + dx, yn + dy))
          add_pixel(h, count, prev_guides.index(xn + dx, yn + dy));
    return count > 0.f ? normalized(h, count) : History();
  }

  // The pixel coordinate nearest to p: the centre of the fallback's 3x3 block.
  SVGF_HD static int nearest(float p) { return static_cast<int>(floor_small(p + 0.5f)); }

  // Adds the previous frame's pixel j, unweighted, to the fallback's sums h and count.
  SVGF_HD void add_pixel(History& h, float& count, int j) const {
    h.color += prev_color.load(j);
    h.moments += make_vec2(prev_moment1[j], prev_moment2[j]);
    h.length = h.length + prev_history[j];
    count = count + 1.f;
  }

  // Anti-lag without gradient samples (issue 12, item 3's fallback): how far the history's
  // luminance lies from this frame's neighbourhood on the same mesh (5x5 by default,
  // antilag_radius), in standard errors of
  // the difference of the two means (the neighbourhood's sample variance / count, and / length
  // for the history), plus antilag_relative of the larger luminance for the bias any
  // reprojection and filter leave. A still pixel whose history is right lies about 1 away; a
  // moved shadow, a light switched off or a history holding a one-frame outlier lies far out.
  SVGF_HD float history_discrepancy(int x, int y, int i, float l, const History& h) const {
    float n = 0.f, sum = 0.f, sum_sq = 0.f;
    const int r = params.antilag_radius;
    for (int dy = -r; dy <= r; ++dy)
      for (int dx = -r; dx <= r; ++dx) {
        const int xq = x + dx, yq = y + dy;
        if (!guides.inside(xq, yq)) continue;
        const int j = guides.index(xq, yq);
        if (guides.mesh_id[j] != guides.mesh_id[i] || !guides.is_surface(j)) continue;
        const float lq = j == i ? l
                                : luminance(demodulated(color.load(j), emission.load_or_zero(j),
                                                        albedo.load(j), params.albedo_epsilon));
        n = n + 1.f;
        sum = sum + lq;
        sum_sq = sum_sq + lq * lq;
      }
    const float mean = sum / n;
    // Unbiased sample variance (n - 1); one sample alone gives no spread, only the tolerance.
    const float spread = n > 1.f ? max_f(0.f, sum_sq - sum * mean) / (n - 1.f) : 0.f;
    const float l_history = luminance(h.color);
    // The history is a mean of `length` samples of the same spread. (Its own moments would
    // count an outlier it holds as spread, and hide it.)
    const float tolerance =
        ExactArith::sqrt(spread / n + spread / max_f(h.length, 1.f)) +
        params.antilag_relative * max_f(max_f(l_history, mean), params.antilag_floor);
    return abs_f(l_history - mean) / tolerance;
  }

  // Whether the statistics anti-lag runs (asked for, or standing in for a missing lambda).
  SVGF_HD bool statistics_antilag() const {
    return params.antilag == Antilag::Statistics ||
           (params.antilag == Antilag::Gradient && !gradient_lambda);
  }

  // The share of the history the anti-lag drops: 0 up to antilag_low, 1 from antilag_high.
  SVGF_HD float antilag_drop(int x, int y, int i, float l, const History& h) const {
    if (!statistics_antilag()) return 0.f;
    const float d = history_discrepancy(x, y, i, l, h);
    if (!(d > params.antilag_low)) return 0.f;
    return min_f(1.f, (d - params.antilag_low) / (params.antilag_high - params.antilag_low));
  }

  // A history the frame contradicts counts for fewer frames, so the new sample weighs more.
  // False when nothing of it is left, not even in rounding: the pixel restarts as after a
  // disocclusion.
  SVGF_HD static bool shorten(History& h, float drop) {
    h.length = h.length * (1.f - drop);
    return h.length > 0.f;
  }

  // The index of pixel (x, y)'s stratum in gradient_lambda.
  SVGF_HD int stratum(int x, int y) const {
    return (y / kGradientStratum) * strata_along(guides.width) + x / kGradientStratum;
  }

  SVGF_HD void operator()(int x, int y) const {
    const int i = guides.index(x, y);
    pixel(x, y, i, illumination.load(i));
  }
  // Pixel (x, y), index i, with its illumination c (DemodulateAndReproject passes it on).
  SVGF_HD void pixel(int x, int y, int i, Vec3 c) const {
    const float l = luminance(c);
    History h = read_history(x, y, i);
    const float drop = h.valid ? antilag_drop(x, y, i, l, h) : 0.f;
    const float lambda = gradient_lambda ? gradient_lambda[stratum(x, y)] : 0.f;
    const bool kept = history_kept(h, drop, lambda);
    blend(i, c, l, none_unless(kept, h), kept ? lambda : 0.f);
  }

  // Whether the history h is kept through the anti-lags: the statistics anti-lag's drop
  // shortens it, and dropped whole (nothing left, not even in rounding) or with A-SVGF's lambda
  // of its stratum (0 without the gradient stages) 1 or more, the pixel restarts as after a
  // disocclusion. No history is never kept.
  SVGF_HD static bool history_kept(History& h, float drop, float stratum_lambda) {
    return h.valid & shorten(h, drop) & (stratum_lambda < 1.f);
  }

  // h where keep (a valid h), else no history; selects, not branches (the CPU rows run it per
  // vector lane).
  SVGF_HD static History none_unless(bool keep, const History& h) {
    History r;
    r.color.x = keep ? h.color.x : 0.f;
    r.color.y = keep ? h.color.y : 0.f;
    r.color.z = keep ? h.color.z : 0.f;
    r.moments.x = keep ? h.moments.x : 0.f;
    r.moments.y = keep ? h.moments.y : 0.f;
    r.length = keep ? h.length : 0.f;
    r.valid = keep;
    return r;
  }

  // The new sample c (luminance l) blended into the history h (anti-lag applied, A-SVGF's
  // lambda not yet), and the outputs of pixel i.
  SVGF_HD void blend(int i, Vec3 c, float l, const History& h, float lambda) const {
    float length = h.valid ? min_f(h.length + 1.f, static_cast<float>(params.history_cap)) : 1.f;
    // With history h, alpha = 1/h makes the first frames an equal-weight mean.
    float alpha = h.valid ? max_f(params.alpha, 1.f / length) : 1.f;
    float alpha_m = h.valid ? max_f(params.moments_alpha, 1.f / length) : 1.f;
    if (h.valid && lambda > 0.f) {
      alpha = antilag_alpha(alpha, lambda);
      alpha_m = antilag_alpha(alpha_m, lambda);
      // The history now counts for 1 / alpha' frames, so the next frames go on from there
      // (Schied's reference code).
      length = min_f(length, 1.f / alpha);
    }
    const Vec3 color = h.color + (c - h.color) * alpha;
    const float m1 = h.moments.x + (l - h.moments.x) * alpha_m;
    const float m2 = h.moments.y + (l * l - h.moments.y) * alpha_m;
    accumulated.color.store(i, color);
    if (accumulated.variance) accumulated.variance[i] = moment_variance(m1, m2);
    moment1[i] = m1;
    moment2[i] = m2;
    history[i] = length;
  }
};

using ReprojectKernel = ReprojectKernelT<GuideView>;

// The demodulation and the reprojection of a pixel in one thread (the packed flavors' first
// kernel): the illumination passes on in registers, and is stored only where it is read back
// (`store_illumination`: the keep_scratch debug buffer); the same value either way.
template <class Reproject>
struct DemodulateAndReproject {
  DemodulateKernel demodulate;
  Reproject reproject;
  bool store_illumination = true;
  SVGF_HD void operator()(int x, int y) const {
    const int i = y * demodulate.width + x;
    const Vec3 c = demodulate.at(i);
    if (store_illumination) demodulate.illumination.store(i, c);
    reproject.pixel(x, y, i, c);
  }
};

}  // namespace svgf

#pragma once
// Stage 3: estimate variance (paper Sec. 4.2, Falcor's SVGFFilterMoments).
// With history >= spatial_variance_history the temporal variance from the moments passes
// through. A younger history has too few samples for it, so the luminance moments are instead
// gathered over a 7x7 bilateral neighbourhood (the color is filtered the same way) and the
// variance boosted by spatial_variance_history / history.
#include "methods/svgf/edge_stopping.h"
#include "methods/svgf/flavors.h"
#include "methods/svgf/params.h"
#include "core/rare_path.h"
#include "core/views.h"

namespace svgf {

// The variance of the accumulated color, from the per-sample luminance variance the moments
// estimate. The moments measure one sample's spread; the accumulated color averages about
// n = min(history, (2 - alpha) / alpha) samples (a mean of `history` frames, then an exponential
// average whose steady state has the variance of (2 - alpha) / alpha samples), so its variance
// is the sample variance / n. With variance_of_mean off it is the sample variance (the paper,
// Falcor): the filter then stays as strong on a 32-frame history as on a 1-frame one.
SVGF_HD float variance_of_mean_scale(const SvgfParams& p, float history) {
  if (!p.variance_of_mean) return 1.f;
  const float n = min_f(history, (2.f - p.alpha) / p.alpha);
  return n > 1.f ? 1.f / n : 1.f;
}

// The temporal variance E[l^2] - E[l]^2 of a pixel's luminance moments (paper Sec. 4.2): the
// reprojection stores it beside the accumulated color where the denoiser gives it a plane, and
// this stage derives it from the stored moments where not (the same floats, the same bits).
SVGF_HD float moment_variance(float m1, float m2) { return max_f(0.f, m2 - m1 * m1); }

// The variance a pixel of `history` frames passes on, from its temporal estimate.
SVGF_HD float temporal_variance(const SvgfParams& p, float variance, float history) {
  return variance * variance_of_mean_scale(p, history);
}

// The variance from the 7x7 spatial moments m1, m2 of a young history, boosted by
// spatial_variance_history / history because so few frames back it (Falcor).
SVGF_HD float spatial_variance(const SvgfParams& p, float m1, float m2, float history) {
  return max_f(0.f, m2 - m1 * m1) * (static_cast<float>(p.spatial_variance_history) / history) *
         variance_of_mean_scale(p, history);
}

template <class Flavor, class Power = NormalPower<typename Flavor::Arith>,
          class Out = typename Flavor::Signal>
struct VarianceEstimate {
  using Arith = typename Flavor::Arith;
  typename Flavor::Guides guides;
  // From the reprojection (separate planes in every flavor); its variance plane is optional:
  // without one the temporal variance comes from the moments (moment_variance).
  ConstIllumVarView accumulated;
  const float* moment1 = nullptr;
  const float* moment2 = nullptr;
  const float* history = nullptr;
  Out out;
  SvgfParams params;
  // Where set, every pixel's accumulated color is copied here too: the color history's one
  // slot, which the reprojection read until this stage (methods/svgf/pipeline.h).
  RgbView color_history = {};

  SVGF_HD void operator()(int x, int y) const {
    if (!common_path(x, y)) rare_path(x, y);
  }

  // A history old enough (or no surface): the temporal variance passes through. The GPU runs the
  // rare path below on compacted threads (core/rare_path.h).
  SVGF_HD bool common_path(int x, int y) const {
    const int i = guides.index(x, y);
    const float h = history[i];
    if (h < static_cast<float>(params.spatial_variance_history) &&
        guides.depth_normal(i).depth > 0.f)
      return false;
    const Vec3 color = accumulated.color.load(i);
    if (color_history.r) color_history.store(i, color);
    const float variance =
        accumulated.variance ? accumulated.variance[i] : moment_variance(moment1[i], moment2[i]);
    out.store(i, make_color_var(color, temporal_variance(params, variance, h)));
    return true;
  }

  // A young history on a surface: the 7x7 bilateral estimate.
  SVGF_HD void rare_path(int x, int y) const {
    const int i = guides.index(x, y);
    const float h = history[i];
    const Vec3 center_color = accumulated.color.load(i);
    if (color_history.r) color_history.store(i, center_color);
    const DepthNormal gc = guides.depth_normal(i);
    const EdgeSample c{gc.depth, gc.normal, luminance_with<Arith>(center_color)};
    const float inv_phi_z = inv_depth_tolerance<Arith>(
        params.spatial_variance_phi_depth, guides.depth_fwidth(i), params.depth_gradient_floor);
    const float inv_phi_l = Arith::recip(params.phi_color);
    const Power normal_power = Power::of(params.phi_normal);
    const int r = params.spatial_variance_radius;
    Sums s;
    // Where the flavor asks for it, the default radius as a compile-time loop (each tap's
    // depth scale a constant times the pixel's 1 / phi_z, not an IEEE square root and
    // division), and (fast mode) without the bounds tests where the footprint is inside: the
    // same taps in the same order. (Exact mode's kernel with the interior split got no faster
    // on the H200: 0.219 ms against 0.200 at 1080p camera-pan, docs/benchmarks.md.)
    if (Flavor::kSplitInteriorVariance && r == kDefaultRadius) {
      if (x >= r && y >= r && x < guides.width - r && y < guides.height - r)
        taps<kDefaultRadius, false>(x, y, r, c, inv_phi_z, inv_phi_l, normal_power, s);
      else
        taps<kDefaultRadius, true>(x, y, r, c, inv_phi_z, inv_phi_l, normal_power, s);
    } else if (Flavor::kUnrollVariance && r == kDefaultRadius) {
      taps<kDefaultRadius, true>(x, y, r, c, inv_phi_z, inv_phi_l, normal_power, s);
    } else {
      taps<0, true>(x, y, r, c, inv_phi_z, inv_phi_l, normal_power, s);
    }
    const auto by_weight = Arith::divide_by(max_f(s.weight, 1e-6f));
    const Vec2 m = by_weight(s.moments);
    out.store(i, make_color_var(by_weight(s.color), spatial_variance(params, m.x, m.y, h)));
  }

 private:
  static constexpr int kDefaultRadius = SvgfParams{}.spatial_variance_radius;
  struct Sums {
    float weight = 0.f;
    Vec3 color;
    Vec2 moments;
  };

  // The (2r + 1)^2 taps, row by row; kRadius > 0: r known at compile time.
  template <int kRadius, bool kCheck>
  SVGF_HD void taps(int x, int y, int r, const EdgeSample& c, float inv_phi_z, float inv_phi_l,
                    const Power& normal_power, Sums& s) const {
    const int reach = kRadius > 0 ? kRadius : r;
#if defined(__CUDA_ARCH__)
#pragma unroll
#endif
    for (int dy = -reach; dy <= reach; ++dy) {
#if defined(__CUDA_ARCH__)
#pragma unroll
#endif
      for (int dx = -reach; dx <= reach; ++dx) {
        const int xq = x + dx;
        const int yq = y + dy;
        if (kCheck && !guides.inside(xq, yq)) continue;
        const int j = guides.index(xq, yq);
        const Vec3 cq = accumulated.color.load(j);
        const DepthNormal gq = guides.depth_normal(j);
        const EdgeSample q{gq.depth, gq.normal, luminance_with<Arith>(cq)};
        const float w =
            edge_stopping_weight<Arith>(c, q, Arith::tap_depth_scale(inv_phi_z, dx, dy, 1),
                                        normal_power, inv_phi_l);
        s.weight = s.weight + w;
        s.color = Arith::mad(cq, w, s.color);
        s.moments = Arith::mad(make_vec2(moment1[j], moment2[j]), w, s.moments);
      }
    }
  }
};

// Exact mode's estimate over separate planes (the CPU row drivers are proven equal to it).
using VarianceKernel = VarianceEstimate<SvgfExact>;

}  // namespace svgf

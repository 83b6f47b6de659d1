#pragma once
// Stage 4: one iteration of the edge-avoiding a-trous wavelet filter (paper Sec. 4.3, Eq. 1-5;
// Falcor's SVGFAtrous). 5x5 B3-spline taps spaced `step` = 2^iteration pixels apart, each
// weighted by the edge-stopping function; the luminance sigma comes from the 3x3-Gaussian
// prefiltered variance. The variance is filtered with squared weights (Eq. 5), so it stays the
// variance of the filtered color.
#include "core/sink.h"
#include "core/views.h"
#include "methods/svgf/edge_stopping.h"
#include "methods/svgf/flavors.h"
#include "methods/svgf/params.h"

namespace svgf {

// The variance of pixel j in any storage layout (or a bare variance plane).
SVGF_HD float variance_of(const float* variance, int j) { return variance[j]; }
template <class T>
SVGF_HD float variance_of(const IllumVar<T>& s, int j) { return s.variance[j]; }
// Packed: only the variance's 4 bytes are loaded, not the pixel's 16.
template <class T>
SVGF_HD float variance_of(const PackedIllumVar<T>& s, int j) { return s.data[j].w; }

// 3x3 Gaussian of the variance around an interior pixel i (all taps inside). The weights are
// exact binary fractions summing to exactly 1, but the division is kept so the result has the
// same bits as the border version below.
template <class Arith = ExactArith, class Var>
SVGF_HD float prefiltered_variance_interior(const Var& variance, int width, int i) {
  float sum = 0.f;
  float weight_sum = 0.f;
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      const float k = gauss3_weight(dx < 0 ? -dx : dx) * gauss3_weight(dy < 0 ? -dy : dy);
      sum = Arith::mad(variance_of(variance, i + dy * width + dx), k, sum);
      weight_sum = weight_sum + k;
    }
  }
  return Arith::divide_by(weight_sum)(sum);
}

// 3x3 Gaussian of the variance around (x, y). Out-of-image taps are skipped and the weights
// renormalized (the project's border rule).
template <class Arith = ExactArith, class Guides, class Var>
SVGF_HD float prefiltered_variance(const Guides& g, const Var& variance, int x, int y) {
  if (x > 0 && y > 0 && x < g.width - 1 && y < g.height - 1)
    return prefiltered_variance_interior<Arith>(variance, g.width, g.index(x, y));
  float sum = 0.f;
  float weight_sum = 0.f;
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      if (!g.inside(x + dx, y + dy)) continue;
      const float k = gauss3_weight(dx < 0 ? -dx : dx) * gauss3_weight(dy < 0 ? -dy : dy);
      sum = Arith::mad(variance_of(variance, g.index(x + dx, y + dy)), k, sum);
      weight_sum = weight_sum + k;
    }
  }
  return Arith::divide_by(weight_sum)(sum);
}

// 1 / phi_l of a pixel: phi_color * sqrt(max(0, epsilon + prefiltered variance)) (Eq. 4).
template <class Arith = ExactArith>
SVGF_HD float atrous_inv_phi_luminance(const SvgfParams& p, float prefiltered) {
  return Arith::inv_scaled_sqrt(p.phi_color, max_f(0.f, p.variance_epsilon + prefiltered));
}

// One a-trous iteration. Flavor: arithmetic and storage (methods/svgf/flavors.h); Power: the
// normal weight's power; Out: where the result goes, anything with store(i, ColorVar) (the
// next iteration's buffer, or a fused sink of methods/svgf/sinks.h).
template <class Flavor, class Power = NormalPower<typename Flavor::Arith>,
          class Out = typename Flavor::Signal>
struct AtrousIteration {
  using Arith = typename Flavor::Arith;
  // The flavor's register cap for a GPU launch (kernels_cuda/cuda_launch.cuh), 0 for none.
  static constexpr int kMaxRegisters = Flavor::kAtrousMaxRegisters;
  typename Flavor::Guides guides;
  typename Flavor::ConstSignal in;
  Out out;
  int step = 1;  // 2^iteration
  SvgfParams params;

  SVGF_HD void operator()(int x, int y) const {
    const int i = guides.index(x, y);
    const ColorVar center = in.load(i);
    const DepthNormal gc = guides.depth_normal(i);
    const auto out_inputs = sink_inputs(out, i);  // a remodulating sink's albedo, fetched early
    if (!(gc.depth > 0.f)) {  // background: nothing to filter against
      store_with(out, out_inputs, i, center);
      return;
    }
    // The depth tolerance first: its loads then overlap the prefilter's (after the prefilter's
    // interior/border branch the GPU issued them late and waited: +9% on the H100's last
    // fast iteration).
    const float inv_phi_z = inv_depth_tolerance<Arith>(
        params.phi_depth, guides.depth_fwidth(i), params.depth_gradient_floor);
    const float inv_phi_l =
        atrous_inv_phi_luminance<Arith>(params, prefiltered_variance<Arith>(guides, in, x, y));
    const EdgeSample c{gc.depth, gc.normal, luminance_with<Arith>(center.color)};
    const Power normal_power = Power::of(params.phi_normal);

    // The centre enters with its kernel weight and no edge-stopping term, so the sum is never 0.
    const float center_k = b3_weight(0) * b3_weight(0);
    Sums s;
    s.weight = center_k;
    s.color = center.color * center_k;
    s.variance = center.variance * (center_k * center_k);
    // Pixels whose whole footprint is inside may skip the 24 bounds tests (same sums, same
    // order), where the flavor asks for it.
    const int reach = 2 * step;
    const bool interior = Flavor::kSplitInterior && x >= reach && y >= reach &&
                          x < guides.width - reach && y < guides.height - reach;
    Arith::with_depth_scale(inv_phi_z, step, [&](const auto& depth_scale) {
      if (interior)
        taps<false>(x, y, c, depth_scale, inv_phi_l, normal_power, s);
      else
        taps<true>(x, y, c, depth_scale, inv_phi_l, normal_power, s);
    });
    const auto by_weight = Arith::divide_by(s.weight);
    store_with(out, out_inputs, i,
               make_color_var(by_weight(s.color),
                              Arith::divide_by(s.weight * s.weight)(s.variance)));
  }

 private:
  struct Sums {
    float weight;
    Vec3 color;
    float variance;
  };

  // depth_scale: the pixel's 1 / phi_z in Arith::with_depth_scale's form (tap(dx, dy) scales
  // it by the tap's distance).
  template <bool kCheck, class DepthScale>
  SVGF_HD void taps(int x, int y, const EdgeSample& c, const DepthScale& depth_scale,
                    float inv_phi_l, const Power& normal_power, Sums& s) const {
#if defined(__CUDA_ARCH__)
#pragma unroll
#endif
    for (int dy = -2; dy <= 2; ++dy) {
#if defined(__CUDA_ARCH__)
#pragma unroll
#endif
      for (int dx = -2; dx <= 2; ++dx) {
        if (dx == 0 && dy == 0) continue;
        const int xq = x + dx * step;
        const int yq = y + dy * step;
        if (kCheck && !guides.inside(xq, yq)) continue;
        const int j = guides.index(xq, yq);
        const ColorVar q = in.load(j);
        const DepthNormal gq = guides.depth_normal(j);
        const EdgeSample sq{gq.depth, gq.normal, luminance_with<Arith>(q.color)};
        const float k = b3_weight(dx < 0 ? -dx : dx) * b3_weight(dy < 0 ? -dy : dy);
        const float tap_scale = depth_scale.tap(dx, dy);
        const float w =
            edge_stopping_weight<Arith>(c, sq, tap_scale, normal_power, inv_phi_l) * k;
        s.weight = s.weight + w;
        s.color = Arith::mad(q.color, w, s.color);
        s.variance = Arith::mad(q.variance, w * w, s.variance);
      }
    }
  }
};

// Exact mode's a-trous iteration over separate planes: what the CPU engine and the CUDA exact
// engine run, and what the CPU row drivers are proven equal to.
using AtrousKernel = AtrousIteration<SvgfExact>;

}  // namespace svgf

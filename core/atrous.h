#pragma once
// Stage 4: one iteration of the edge-avoiding a-trous wavelet filter (paper Sec. 4.3, Eq. 1-5;
// Falcor's SVGFAtrous). 5x5 B3-spline taps spaced `step` = 2^iteration pixels apart, each
// weighted by the edge-stopping function; the luminance sigma comes from the 3x3-Gaussian
// prefiltered variance. The variance is filtered with squared weights (Eq. 5), so it stays the
// variance of the filtered color.
#include "core/edge_stopping.h"
#include "core/params.h"
#include "core/views.h"

namespace svgf {

// 3x3 Gaussian of the variance around an interior pixel i (all taps inside). The weights are
// exact binary fractions summing to exactly 1, but the division is kept so the result has the
// same bits as the border version below.
SVGF_HD float prefiltered_variance_interior(const float* variance, int width, int i) {
  float sum = 0.f;
  float weight_sum = 0.f;
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      const float k = gauss3_weight(dx < 0 ? -dx : dx) * gauss3_weight(dy < 0 ? -dy : dy);
      sum = sum + variance[i + dy * width + dx] * k;
      weight_sum = weight_sum + k;
    }
  }
  return sum / weight_sum;
}

// 3x3 Gaussian of the variance around (x, y). Out-of-image taps are skipped and the weights
// renormalized (the project's border rule).
SVGF_HD float prefiltered_variance(const GuideView& g, const float* variance, int x, int y) {
  if (x > 0 && y > 0 && x < g.width - 1 && y < g.height - 1)
    return prefiltered_variance_interior(variance, g.width, g.index(x, y));
  float sum = 0.f;
  float weight_sum = 0.f;
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      if (!g.inside(x + dx, y + dy)) continue;
      const float k = gauss3_weight(dx < 0 ? -dx : dx) * gauss3_weight(dy < 0 ? -dy : dy);
      sum = sum + variance[g.index(x + dx, y + dy)] * k;
      weight_sum = weight_sum + k;
    }
  }
  return sum / weight_sum;
}

struct AtrousKernel {
  GuideView guides;
  ConstIllumVarView in;
  IllumVarView out;
  int step = 1;  // 2^iteration
  SvgfParams params;

  SVGF_HD void operator()(int x, int y) const {
    const int i = guides.index(x, y);
    const Vec3 center_color = in.color.load(i);
    const float center_variance = in.variance[i];
    if (!guides.is_surface(i)) {  // background: nothing to filter against
      out.color.store(i, center_color);
      out.variance[i] = center_variance;
      return;
    }
    const float variance = prefiltered_variance(guides, in.variance, x, y);
    const float inv_phi_l =
        1.f / (params.phi_color * sqrtf(max_f(0.f, params.variance_epsilon + variance)));
    const float inv_phi_z =
        1.f / (params.phi_depth * max_f(guides.depth_fwidth(i), params.depth_gradient_floor));
    const EdgeSample c{guides.depth[i], guides.normal.load(i), luminance(center_color)};
    const NormalPower normal_power = NormalPower::of(params.phi_normal);

    // The centre enters with its kernel weight and no edge-stopping term, so the sum is never 0.
    const float center_k = b3_weight(0) * b3_weight(0);
    float weight_sum = center_k;
    Vec3 color_sum = center_color * center_k;
    float variance_sum = center_variance * (center_k * center_k);
    for (int dy = -2; dy <= 2; ++dy) {
      for (int dx = -2; dx <= 2; ++dx) {
        if (dx == 0 && dy == 0) continue;
        const int xq = x + dx * step;
        const int yq = y + dy * step;
        if (!guides.inside(xq, yq)) continue;
        const int j = guides.index(xq, yq);
        const Vec3 cq = in.color.load(j);
        const EdgeSample q{guides.depth[j], guides.normal.load(j), luminance(cq)};
        const float k = b3_weight(dx < 0 ? -dx : dx) * b3_weight(dy < 0 ? -dy : dy);
        const float w = edge_stopping_weight(c, q, inv_phi_z * inv_tap_distance(dx, dy, step),
                                             normal_power, inv_phi_l) * k;
        weight_sum = weight_sum + w;
        color_sum += cq * w;
        variance_sum = variance_sum + in.variance[j] * (w * w);
      }
    }
    out.color.store(i, color_sum / weight_sum);
    out.variance[i] = variance_sum / (weight_sum * weight_sum);
  }
};

}  // namespace svgf

#pragma once
// Stage 3: estimate variance (paper Sec. 4.2, Falcor's SVGFFilterMoments).
// With history >= spatial_variance_history the temporal variance from the moments passes
// through. A younger history has too few samples for it, so the luminance moments are instead
// gathered over a 7x7 bilateral neighbourhood (the color is filtered the same way) and the
// variance boosted by spatial_variance_history / history.
#include "core/edge_stopping.h"
#include "core/params.h"
#include "core/views.h"

namespace svgf {

struct VarianceKernel {
  GuideView guides;
  ConstIllumVarView accumulated;  // from reproject
  const float* moment1 = nullptr;
  const float* moment2 = nullptr;
  const float* history = nullptr;
  IllumVarView out;
  SvgfParams params;

  SVGF_HD void operator()(int x, int y) const {
    const int i = guides.index(x, y);
    const float h = history[i];
    const Vec3 center_color = accumulated.color.load(i);
    if (!(h < static_cast<float>(params.spatial_variance_history)) || !guides.is_surface(i)) {
      out.color.store(i, center_color);
      out.variance[i] = accumulated.variance[i];
      return;
    }
    const EdgeSample c{guides.depth[i], guides.normal.load(i), luminance(center_color)};
    const float inv_phi_z = 1.f / (params.spatial_variance_phi_depth *
                                   max_f(guides.depth_fwidth(i), params.depth_gradient_floor));
    const float inv_phi_l = 1.f / params.phi_color;
    const NormalPower normal_power = NormalPower::of(params.phi_normal);
    const int r = params.spatial_variance_radius;
    float weight_sum = 0.f;
    Vec3 color_sum;
    Vec2 moments_sum;
    for (int dy = -r; dy <= r; ++dy) {
      for (int dx = -r; dx <= r; ++dx) {
        const int xq = x + dx;
        const int yq = y + dy;
        if (!guides.inside(xq, yq)) continue;
        const int j = guides.index(xq, yq);
        const Vec3 cq = accumulated.color.load(j);
        const EdgeSample q{guides.depth[j], guides.normal.load(j), luminance(cq)};
        const float w = edge_stopping_weight(c, q, inv_phi_z * inv_tap_distance(dx, dy, 1),
                                             normal_power, inv_phi_l);
        weight_sum = weight_sum + w;
        color_sum += cq * w;
        moments_sum += make_vec2(moment1[j], moment2[j]) * w;
      }
    }
    weight_sum = max_f(weight_sum, 1e-6f);
    const Vec2 m = moments_sum / weight_sum;
    out.color.store(i, color_sum / weight_sum);
    out.variance[i] = max_f(0.f, m.y - m.x * m.x) *
                      (static_cast<float>(params.spatial_variance_history) / h);
  }
};

}  // namespace svgf

#pragma once
// The joint edge-stopping weight of SVGF (Schied et al. 2017, Eq. 3-4; Falcor's computeWeight):
//   w = exp(-|l_p - l_q| / phi_l  -  |z_p - z_q| / phi_z) * max(0, n_p . n_q)^phi_n
// shared by the 7x7 spatial variance estimate and the a-trous iterations.
#include "core/det_math.h"
#include "core/vec.h"

namespace svgf {

// What a pixel contributes to edge-stopping tests, gathered once per centre or tap.
struct EdgeSample {
  float depth;
  Vec3 normal;
  float luminance;
};

// phi_z is the depth tolerance for this tap (already scaled by gradient and distance); 0 means
// "centre tap": no depth term. A NaN anywhere (bad guide data) yields weight 0, never NaN.
SVGF_HD float edge_stopping_weight(const EdgeSample& c, const EdgeSample& q, float phi_z,
                                   float phi_normal, float phi_l) {
  const float w_normal = det_pow(max_f(0.f, dot(c.normal, q.normal)), phi_normal);
  const float e_depth = phi_z == 0.f ? 0.f : abs_f(c.depth - q.depth) / phi_z;
  const float e_lum = abs_f(c.luminance - q.luminance) / phi_l;
  const float w = det_exp((0.f - max_f(e_lum, 0.f)) - max_f(e_depth, 0.f)) * w_normal;
  return w > 0.f ? w : 0.f;
}

// Distance in pixels of the tap (dx, dy) * step; sqrt is IEEE-exact on both sides.
SVGF_HD float tap_distance(int dx, int dy, int step) {
  const float fx = static_cast<float>(dx * step);
  const float fy = static_cast<float>(dy * step);
  return sqrtf(fx * fx + fy * fy);
}

}  // namespace svgf

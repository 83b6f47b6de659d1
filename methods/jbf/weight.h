#pragma once
// The joint bilateral weight of GAMES202 homework 5 (assignment Sec. 2.1):
//   J(i, j) = exp(-|p_i - p_j|^2 / (2 s_coord^2) - |c_i - c_j|^2 / (2 s_color^2)
//                 - D_normal^2 / (2 s_normal^2) - D_plane^2 / (2 s_plane^2))
// p the pixel coordinates, c the color, D_normal = acos(clamp(n_i . n_j, -1, 1)) the angle
// between the normals, D_plane = n_i . (x_j - x_i) / |x_j - x_i| (0 where the positions
// coincide) with x the world positions. Exact mode: the project's own acos and exp, IEEE sqrt and
// division, the same bits on every backend; fast mode: FastArith's (core/arith.h).
#include "core/arith.h"
#include "core/det_math.h"
#include "core/vec.h"
#include "methods/jbf/params.h"

namespace svgf {

// 1 / (2 sigma^2) of each term, computed once per frame.
struct JbfScales {
  float coord, color, normal, plane;
  static JbfScales of(const JbfParams& p) {
    auto f = [](float s) { return 1.f / (2.f * s * s); };
    return {f(p.sigma_coord), f(p.sigma_color), f(p.sigma_normal), f(p.sigma_plane)};
  }
};

// What a pixel brings to the weight: its color, normal and world position.
struct JbfSample {
  Vec3 color, normal, position;
};

// The weight's exponent without the coordinate term, >= 0 (NaN for NaN guide data).
template <class Arith>
SVGF_HD float jbf_guide_exponent(const JbfSample& i, const JbfSample& j, const JbfScales& s) {
  const Vec3 dc = i.color - j.color;
  const float e_color = Arith::dot(dc, dc) * s.color;
  const float cosine = Arith::min(1.f, Arith::max(-1.f, Arith::dot(i.normal, j.normal)));
  const float angle = Arith::acos(cosine);
  const float e_normal = angle * angle * s.normal;
  const Vec3 dx = j.position - i.position;
  const float len = Arith::sqrt(Arith::dot(dx, dx));
  const float ratio = Arith::divide_by(len)(Arith::dot(i.normal, dx));  // both sides computed:
  const float d_plane = len > 0.f ? ratio : 0.f;  // a select, so the CPU rows vectorize it
  const float e_plane = d_plane * d_plane * s.plane;
  return (e_color + e_normal) + e_plane;
}

// J(i, j) for a tap at squared pixel distance d2; 0 where a guide is NaN.
template <class Arith>
SVGF_HD float jbf_weight(const JbfSample& i, const JbfSample& j, float d2, const JbfScales& s) {
  // e is >= 0 (squares times positive scales) or NaN. The max takes fast mode's NaN to 0 (exact
  // mode's exp already gives 0); a select on e instead would stop the CPU rows vectorizing.
  const float e = d2 * s.coord + jbf_guide_exponent<Arith>(i, j, s);
  return Arith::max(Arith::exp_nonpositive(0.f - e), 0.f);
}

}  // namespace svgf

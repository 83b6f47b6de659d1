#pragma once
// The joint edge-stopping weight of SVGF (Schied et al. 2017, Eq. 3-4; Falcor's computeWeight):
//   w = exp(-|l_p - l_q| / phi_l  -  |z_p - z_q| / phi_z) * saturate(n_p . n_q)^phi_n
// evaluated with the reciprocals 1/phi_l and 1/phi_z, shared by the 7x7 spatial variance
// estimate and the a-trous iterations, on every backend and in every mode (Arith).
#include "core/arith.h"
#include "core/normal_weight.h"
#include "core/det_math.h"
#include "core/vec.h"

namespace svgf {

// What a pixel contributes to edge-stopping tests, gathered once per centre or tap.
struct EdgeSample {
  float depth;
  Vec3 normal;
  float luminance;
};

// The normal term saturate(n_p . n_q)^phi_n. Symmetric to the bit: n_q . n_p multiplies the
// same components and adds the products in the same order, so w(p, q) and w(q, p) are the same
// value, NaN aside (a NaN term zeroes the weight either way); the CPU a-trous rows compute it
// once for both pixels of a pair (kernels_cpu/svgf_rows.cpp).
template <class Arith = ExactArith, class Power>
SVGF_HD_INLINE float edge_normal_weight(Vec3 n_p, Vec3 n_q, const Power& normal_power) {
  return normal_power(normal_cosine<Arith>(n_p, n_q));
}

// The weight given its normal term w_normal = edge_normal_weight(c.normal, q.normal) (q's
// normal is not read). inv_phi_z and inv_phi_l are the reciprocals of the depth and luminance
// tolerances for this tap (computed once per pixel and tap, so the tap loop has no division).
// At the centre tap inv_phi_z is Inf and the depth difference 0: 0 * Inf is NaN, which max_f
// drops, so the centre has no depth term (Falcor's phiDepth == 0 case) without a branch,
// keeping the CPU row loops vectorizable. inv_phi_z = 0 (phi_depth = 0) drops the depth term
// everywhere. Bad guide data (NaN) drops the term it is in or zeroes the weight; the weight is
// never NaN.
template <class Arith = ExactArith>
SVGF_HD_INLINE float edge_stopping_weight_given_normal(const EdgeSample& c, const EdgeSample& q,
                                                       float inv_phi_z, float w_normal,
                                                       float inv_phi_l) {
  const float e_depth = Arith::abs_before_clamp(c.depth - q.depth) * inv_phi_z;
  const float e_lum = Arith::abs_before_clamp(c.luminance - q.luminance) * inv_phi_l;
  // The argument is <= 0 (or -0): both terms are clamped to >= 0 first (which also takes -0 and
  // NaN to 0, whatever their sign, hence abs_before_clamp).
  const float w = Arith::exp_neg_sum(Arith::max(e_lum, 0.f), Arith::max(e_depth, 0.f)) * w_normal;
  return Arith::positive_part(w);
}

template <class Arith = ExactArith, class Power>
SVGF_HD_INLINE float edge_stopping_weight(const EdgeSample& c, const EdgeSample& q,
                                          float inv_phi_z, const Power& normal_power,
                                          float inv_phi_l) {
  return edge_stopping_weight_given_normal<Arith>(
      c, q, inv_phi_z, edge_normal_weight<Arith>(c.normal, q.normal, normal_power), inv_phi_l);
}

SVGF_HD float edge_stopping_weight(const EdgeSample& c, const EdgeSample& q, float inv_phi_z,
                                   float phi_normal, float inv_phi_l) {
  return edge_stopping_weight<ExactArith>(c, q, inv_phi_z, NormalPower<>::of(phi_normal),
                                          inv_phi_l);
}

// 1 / distance in pixels of the tap (dx, dy) * step (Inf at the centre); sqrt and division
// are IEEE-exact on both sides.
SVGF_HD float inv_tap_distance(int dx, int dy, int step) {
  return ExactArith::tap_depth_scale(1.f, dx, dy, step);
}

// 1 / phi_z for a pixel: the depth tolerance phi_depth * max(fwidth(z), floor) (paper Eq. 3's
// sigma_z |grad z|). phi_depth = 0 means no depth term (Falcor's convention): 0, not Inf.
template <class Arith = ExactArith>
SVGF_HD float inv_depth_tolerance(float phi_depth, float depth_fwidth, float floor) {
  return phi_depth == 0.f ? 0.f : Arith::recip(phi_depth * max_f(depth_fwidth, floor));
}

}  // namespace svgf

#pragma once
// The normal term every edge-stopping weight of the suite uses: saturate(n_p . n_q)^phi
// (SVGF's phi_normal, the CIS 565 wavelet's sigma_N), on every backend and in every mode
// (Arith, core/arith.h).
#include "core/arith.h"
#include "core/det_math.h"
#include "core/vec.h"

namespace svgf {

// max(0, n.n')^phi_n. For phi_n = 2^m (the default 128 = 2^7, m <= 16) it is m squarings in
// float: cheap, and the same bits whether m is known at run time (this struct, used by the
// per-pixel kernels) or at compile time (NormalPowerFixed, used by the vectorized CPU rows).
// Any other phi_n goes through det_pow.
template <class Arith = ExactArith>
struct NormalPower {
  float phi = 128.f;
  int squarings = -1;  // m when phi = 2^m, else -1
  SVGF_HD static NormalPower of(float phi_normal) {
    NormalPower p;
    p.phi = phi_normal;
    float v = 1.f;
    for (int m = 0; m <= 16; ++m, v = v * 2.f)
      if (phi_normal == v) p.squarings = m;
    return p;
  }
  SVGF_HD float operator()(float d) const {
    if (squarings < 0) return Arith::pow(d, phi);
    for (int i = 0; i < squarings; ++i) d = d * d;
    return d;
  }
};

template <int M>
struct NormalPowerFixed {
  SVGF_HD static NormalPowerFixed of(float) { return NormalPowerFixed(); }
  SVGF_HD float operator()(float d) const {
    for (int i = 0; i < M; ++i) d = d * d;
    return d;
  }
};

// Runs body(power) with the normal weight's power: the default 128 = 2^7 as seven squarings
// known at compile time, any other exponent in its run-time form (the same bits either way:
// NormalPower). On the GPU the taps then run no squaring loop.
SVGF_HD_TEMPLATE
template <class Arith, class Body>
SVGF_HD void with_normal_power_of(float phi_normal, const Body& body) {
  const NormalPower<Arith> p = NormalPower<Arith>::of(phi_normal);
  if (p.squarings == 7) body(NormalPowerFixed<7>());
  else body(p);
}

// The normal term's base: n_p . n_q clamped to [0, 1] (Falcor's saturate). Unit normals give
// at most 1, but normals stored as half floats reach |n|^2 = 1.0003, and uncapped, a same-face
// neighbour would weigh up to 1.04 times the centre. A NaN normal zeroes the weight: exact mode
// keeps the NaN (min_f/max_f) for the final select, fast mode's saturate makes it 0.
template <class Arith>
SVGF_HD float normal_cosine(Vec3 a, Vec3 b) {
  return Arith::saturate(Arith::dot(a, b));
}

}  // namespace svgf

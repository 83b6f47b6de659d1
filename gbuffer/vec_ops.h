#pragma once
// Float vector helpers for the path tracer, on top of core/vec.h. Every expression is written
// out in a fixed order and the build has FMA contraction off, so results are the same bits on
// any x86-64 compiler that honours IEEE float.
#include <cmath>

#include "core/vec.h"

namespace svgf::gbuffer {

inline Vec3 vec3(float s) { return make_vec3(s, s, s); }
inline Vec3 cross(Vec3 a, Vec3 b) {
  return make_vec3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
inline float length(Vec3 a) { return std::sqrt(dot(a, a)); }  // sqrt is correctly rounded
inline Vec3 normalize(Vec3 a) { return a / length(a); }
inline Vec3 neg(Vec3 a) { return make_vec3(-a.x, -a.y, -a.z); }
inline float max_component(Vec3 a) { return max_f(max_f(a.x, a.y), a.z); }
inline float max_abs_component(Vec3 a) { return max_f(max_f(abs_f(a.x), abs_f(a.y)), abs_f(a.z)); }

// Orthonormal basis around unit n (Duff et al. 2017, "Building an Orthonormal Basis, Revisited").
inline void orthonormal_basis(Vec3 n, Vec3& t, Vec3& b) {
  const float sign = n.z >= 0.f ? 1.f : -1.f;
  const float a = -1.f / (sign + n.z);
  const float c = n.x * n.y * a;
  t = make_vec3(1.f + sign * n.x * n.x * a, sign * c, -sign * n.x);
  b = make_vec3(c, sign + n.y * n.y * a, -n.y);
}

}  // namespace svgf::gbuffer

#pragma once
// Small value types for per-pixel math. Every operation is written out in a fixed order so the
// compiler has no freedom to reassociate: the CPU and GPU evaluate the same expression tree.
#include "core/hd.h"

namespace svgf {

struct Vec2 {
  float x = 0.f, y = 0.f;
};

struct Vec3 {
  float x = 0.f, y = 0.f, z = 0.f;
};

SVGF_HD Vec3 make_vec3(float x, float y, float z) { Vec3 v; v.x = x; v.y = y; v.z = z; return v; }
SVGF_HD Vec2 make_vec2(float x, float y) { Vec2 v; v.x = x; v.y = y; return v; }

SVGF_HD Vec3 operator+(Vec3 a, Vec3 b) { return make_vec3(a.x + b.x, a.y + b.y, a.z + b.z); }
SVGF_HD Vec3 operator-(Vec3 a, Vec3 b) { return make_vec3(a.x - b.x, a.y - b.y, a.z - b.z); }
SVGF_HD Vec3 operator*(Vec3 a, Vec3 b) { return make_vec3(a.x * b.x, a.y * b.y, a.z * b.z); }
SVGF_HD Vec3 operator/(Vec3 a, Vec3 b) { return make_vec3(a.x / b.x, a.y / b.y, a.z / b.z); }
SVGF_HD Vec3 operator*(Vec3 a, float s) { return make_vec3(a.x * s, a.y * s, a.z * s); }
SVGF_HD Vec3 operator*(float s, Vec3 a) { return make_vec3(s * a.x, s * a.y, s * a.z); }
SVGF_HD Vec3 operator/(Vec3 a, float s) { return make_vec3(a.x / s, a.y / s, a.z / s); }
SVGF_HD Vec3& operator+=(Vec3& a, Vec3 b) { a = a + b; return a; }

SVGF_HD Vec2 operator+(Vec2 a, Vec2 b) { return make_vec2(a.x + b.x, a.y + b.y); }
SVGF_HD Vec2 operator-(Vec2 a, Vec2 b) { return make_vec2(a.x - b.x, a.y - b.y); }
SVGF_HD Vec2 operator*(Vec2 a, float s) { return make_vec2(a.x * s, a.y * s); }
SVGF_HD Vec2 operator/(Vec2 a, float s) { return make_vec2(a.x / s, a.y / s); }
SVGF_HD Vec2& operator+=(Vec2& a, Vec2 b) { a = a + b; return a; }

// ((a.x*b.x + a.y*b.y) + a.z*b.z), left to right.
SVGF_HD float dot(Vec3 a, Vec3 b) { return (a.x * b.x + a.y * b.y) + a.z * b.z; }

SVGF_HD float min_f(float a, float b) { return a < b ? a : b; }
// max_f(NaN, b) is b: a NaN never wins a max, which the callers rely on to drop bad values.
SVGF_HD float max_f(float a, float b) { return a > b ? a : b; }
// A constant as a select against it sees it: the value itself. The CPU row drivers pass
// theirs through an opaque factor of 1 instead (kernels_cpu/row_tools.h, OpaqueConstant): GCC 12
// compiles max_f and min_f against a literal as a compare and a blend, but against a value it
// cannot see as one vmaxps/vminps, whose IEEE rule (a > b ? a : b) is max_f's exactly.
struct LiteralConstant {
  SVGF_HD static float of(float c) { return c; }
};
SVGF_HD float abs_f(float a) { return a < 0.f ? -a : a; }
SVGF_HD Vec3 max_v(Vec3 a, float s) { return make_vec3(max_f(a.x, s), max_f(a.y, s), max_f(a.z, s)); }
SVGF_HD Vec3 min_v(Vec3 a, Vec3 b) {
  return make_vec3(min_f(a.x, b.x), min_f(a.y, b.y), min_f(a.z, b.z));
}
SVGF_HD Vec3 max_v(Vec3 a, Vec3 b) {
  return make_vec3(max_f(a.x, b.x), max_f(a.y, b.y), max_f(a.z, b.z));
}

// floor for |x| < 2^31 through truncation, exact like floorf. Unlike floorf it vectorizes under
// GCC's default -ftrapping-math (which keeps libm's floorf a call) and needs no libm on device.
SVGF_HD int floor_small_int(float x) {
  const int t = static_cast<int>(x);  // toward zero
  return t - (static_cast<float>(t) > x ? 1 : 0);
}
SVGF_HD float floor_small(float x) { return static_cast<float>(floor_small_int(x)); }

// x - x is 0 for finite x and NaN for NaN and +-Inf, with no library call (isfinite is not
// reliably available on both sides without including <cmath> into device code).
SVGF_HD bool is_finite(float x) { return (x - x) == 0.f; }
SVGF_HD bool is_finite(Vec3 v) { return is_finite(v.x) && is_finite(v.y) && is_finite(v.z); }

// Rec. 709 luminance, as in Falcor's SVGF.
SVGF_HD Vec3 rec709_weights() { return make_vec3(0.2126f, 0.7152f, 0.0722f); }
SVGF_HD float luminance(Vec3 c) { return dot(rec709_weights(), c); }

}  // namespace svgf

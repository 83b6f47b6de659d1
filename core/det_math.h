#pragma once
// Deterministic transcendental functions built only from IEEE + - * / , floor and integer bit
// manipulation. The CUDA math library's expf/powf and glibc's differ in their last bits, so the
// exact mode cannot use either: these give the same bits on every compiler and device as long
// as contraction (FMA) is off and subnormals are kept. Accuracy, tested in tests/det_math_test:
//   det_exp  (float)         : within 2 ulp of the correctly rounded exp over all floats
//   det_pow  (float, float)  : within 1 ulp of the correctly rounded pow (computed in double)
#include <cstdint>
#include <cstring>
#include <cmath>

#include "core/hd.h"
#include "core/vec.h"

namespace svgf {

SVGF_HD uint32_t float_bits(float f) { uint32_t u; memcpy(&u, &f, sizeof u); return u; }
SVGF_HD float bits_float(uint32_t u) { float f; memcpy(&f, &u, sizeof f); return f; }
SVGF_HD uint64_t double_bits(double d) { uint64_t u; memcpy(&u, &d, sizeof u); return u; }
SVGF_HD double bits_double(uint64_t u) { double d; memcpy(&d, &u, sizeof d); return d; }

// y 2^k for y in [0.7, 1.42] (e^r above) and k in [-150, 128], rounded once: as two exact
// power-of-two factors, both normal floats, so that a subnormal result is rounded only once.
// The split is at floor(k/2) (an arithmetic shift, one instruction); any split whose two
// halves stay in [-126, 127] gives the same bits, since y 2^k1 is exact and the product's one
// rounding is of y 2^k either way (tests/det_math_test.cpp checks it against the split at k/2
// for every k). Both halves lie in [-75, 64].
SVGF_HD float det_scale_pow2(float y, int k) {
  static_assert((-3 >> 1) == -2, "det_scale_pow2 needs an arithmetic right shift");
  const int k1 = k >> 1;
  const int k2 = k - k1;
  const float s1 = bits_float(static_cast<uint32_t>(k1 + 127) << 23);
  const float s2 = bits_float(static_cast<uint32_t>(k2 + 127) << 23);
  return (y * s1) * s2;  // y*s1 is exact; the only rounding is the last product
}

// y 2^k for y in [0.7, 1.42] and an integral k in [-150, 0] (det_exp_nonpositive's range), with
// the same one rounding as det_scale_pow2 in fewer instructions and no float-to-int conversion:
// y 2^(k+64) is exact and normal (k + 64 in [-86, 64]), and the product by 2^-64 rounds it once.
// 2^(k+64)'s bits come from k's float: k + (1.5 2^23 + 191) is exact and holds the integer
// k + 191 in [41, 191] in its low mantissa bits (its bits are 0x4B400000 + k + 191); shifted
// left by 23, everything above those bits falls out and k + 191 becomes the exponent field.
// tests/det_math_test.cpp checks it against det_scale_pow2 for every k and many y.
SVGF_HD_INLINE float det_scale_pow2_nonpositive(float y, float k) {
  const uint32_t field = float_bits(k + 12583103.f) << 23;  // 12583103 = 1.5 2^23 + 191
  return (y * bits_float(field)) * 5.42101086242752217e-20f;  // 2^-64
}

// c - a * b for a product a * b that is exact in float (the caller proves it): one fused
// multiply-add where there is one (the GPU; the CPU kernels built for x86-64-v3 and v4), whose
// one rounding is then the rounding of the separate difference, so the bits are the same
// everywhere (tests/det_math_test.cpp). Not a contraction: a product that rounds must not come
// here.
SVGF_HD_INLINE float sub_exact_product(float c, float a, float b) {
#if defined(__CUDA_ARCH__)
  return __fmaf_rn(-a, b, c);
#elif defined(__FMA__)
  return __builtin_fmaf(-a, b, c);
#else
  return c - a * b;
#endif
}

// e^r for |r| <= ln2/2 (and a little beyond): 1 + r + r^2 P(r), P a degree-4 near-minimax
// (Chebyshev) fit of (e^r - 1 - r) / r^2 on [-0.35, 0.35], coefficients rounded to float. Its
// own error is below 1e-8 relatively (0.1 ulp); the float evaluation leaves det_exp within
// 1.03 ulp of the exact exp over every float (Cephes' degree-5 P gave 0.99 for two operations
// more; the same 2-ulp bound, tests/det_math_test.cpp). The exact a-trous takes one exp a tap,
// so those two operations are two of a tap's instructions (82 on the GPU before).
SVGF_HD_INLINE float det_exp_poly(float r) {
  const float r2 = r * r;
  float p = 1.3926926767e-03f;
  p = p * r + 8.3637740463e-03f;
  p = p * r + 4.1666548699e-02f;
  p = p * r + 1.6666573286e-01f;
  p = p * r + 0.5f;
  return (p * r2 + r) + 1.f;
}

// e^x = y 2^k for x clamped to [-104, 89]: Cody-Waite reduction x = k ln2 + r with |r| <= ln2/2
// (ln2 split so k*ln2_hi is exact for |k| <= 255: ln2_hi has 15 significant bits, k 8, so the
// GPU and the x86-64-v3/v4 kernels take x - k*ln2_hi as one FMA) and det_exp_poly for y = e^r.
// Straight-line code, so the CPU loops vectorize it.
struct ExpReduced {
  float y;  // e^r, in [0.7, 1.42]
  float k;  // integral, |k| <= 150
};
SVGF_HD_INLINE ExpReduced det_exp_reduce(float xc) {
  // k = floor(x log2e + 1/2): floorf is one rounding instruction (roundps, vrndscaleps: the CPU
  // kernels are built with -fno-trapping-math; FRND on the GPU).
  const float k = floorf(xc * 1.44269504088896341f + 0.5f);
  const float r = sub_exact_product(xc, k, 0.693145751953125f) - k * 1.428606765330187e-06f;
  return ExpReduced{det_exp_poly(r), k};
}

// exp(x) in float for x already clamped to [-104, 89]: 2^k applied as two exact power-of-two
// factors so that a subnormal result is rounded only once. k converts to the integer exactly
// (|k| <= 150).
SVGF_HD float det_exp_clamped(float xc) {
  const ExpReduced e = det_exp_reduce(xc);
  return det_scale_pow2(e.y, static_cast<int>(e.k));
}

// exp(x) in float, any x: below -104 the result is 0, above 89 +Inf, NaN stays NaN.
SVGF_HD float det_exp(float x) {
  const float out = det_exp_clamped(min_f(max_f(x, -104.f), 89.f));  // NaN lands on -104
  return x == x ? out : x;
}

// exp(x) for x <= 0 or NaN (NaN gives 0): the edge-stopping weights' case. The same bits as
// det_exp for every x <= 0 (and for 0 < x < 43, which no caller passes; beyond, k + 191 leaves
// the exponent field); with one clamp instead of two, GCC 12 if-converts (vectorizes) it.
// x clamped to [-104, 0] makes k <= 0, so 2^k goes through det_scale_pow2_nonpositive (same
// bits). K: how the clamp sees its constant (core/vec.h, LiteralConstant).
template <class K = LiteralConstant>
SVGF_HD_INLINE float det_exp_nonpositive(float x) {
  const ExpReduced e = det_exp_reduce(max_f(x, K::of(-104.f)));
  return det_scale_pow2_nonpositive(e.y, e.k);
}

// exp(x) in double, same scheme with a degree-13 Taylor polynomial (error < 1e-16 on |r|<=ln2/2).
// Used only inside det_pow, where a float result needs a few more bits than float carries.
SVGF_HD double det_exp_d(double x) {
  if (!(x == x)) return x;
  const double xc = x < -746.0 ? -746.0 : (x > 710.0 ? 710.0 : x);
  const double k = floor(xc * 1.4426950408889634 + 0.5);
  const double r = (xc - k * 6.93147180369123816490e-01) - k * 1.90821492927058770002e-10;
  double p = 1.6059043836821613e-10;
  p = p * r + 2.08767569878681e-09;
  p = p * r + 2.505210838544172e-08;
  p = p * r + 2.755731922398589e-07;
  p = p * r + 2.7557319223985893e-06;
  p = p * r + 2.48015873015873e-05;
  p = p * r + 0.0001984126984126984;
  p = p * r + 0.001388888888888889;
  p = p * r + 0.008333333333333333;
  p = p * r + 0.041666666666666664;
  p = p * r + 0.16666666666666666;
  p = p * r + 0.5;
  p = p * r + 1.0;
  p = p * r + 1.0;
  const int ki = static_cast<int>(k);
  const int k1 = ki / 2;
  const int k2 = ki - k1;
  const double s1 = bits_double(static_cast<uint64_t>(k1 + 1023) << 52);
  const double s2 = bits_double(static_cast<uint64_t>(k2 + 1023) << 52);
  return (p * s1) * s2;
}

// log(x) in double for finite x > 0: x = m 2^e with m in [sqrt(1/2), sqrt(2)), then
// log m = 2 atanh(s), s = (m-1)/(m+1), |s| <= 0.1716, summed to s^23.
SVGF_HD double det_log_d(double x) {
  uint64_t b = double_bits(x);
  int e = 0;
  if (((b >> 52) & 0x7ff) == 0) {  // subnormal: scale into the normal range first
    x = x * 18014398509481984.0;  // 2^54
    b = double_bits(x);
    e = -54;
  }
  e += static_cast<int>((b >> 52) & 0x7ff) - 1023;
  double m = bits_double((b & 0x000fffffffffffffULL) | 0x3ff0000000000000ULL);
  if (m > 1.4142135623730951) {
    m = m * 0.5;
    e += 1;
  }
  const double s = (m - 1.0) / (m + 1.0);
  const double s2 = s * s;
  double p = 0.043478260869565216;  // 1/23
  p = p * s2 + 0.047619047619047616;
  p = p * s2 + 0.05263157894736842;
  p = p * s2 + 0.058823529411764705;
  p = p * s2 + 0.06666666666666667;
  p = p * s2 + 0.07692307692307693;
  p = p * s2 + 0.09090909090909091;
  p = p * s2 + 0.1111111111111111;
  p = p * s2 + 0.14285714285714285;
  p = p * s2 + 0.2;
  p = p * s2 + 0.3333333333333333;
  p = p * s2 + 1.0;
  const double ed = static_cast<double>(e);
  return ed * 6.93147180369123816490e-01 + (ed * 1.90821492927058770002e-10 + 2.0 * s * p);
}

// pow(x, y) in float. An integer exponent (the normal weight's 128, say) is exponentiation by
// repeated squaring in double; any other goes through exp(y log x) in double. Both leave at
// most one float rounding that matters, hence the 1-ulp bound.
SVGF_HD float det_pow(float x, float y) {
  if (y == 0.f || x == 1.f) return 1.f;
  if (!(x == x) || !(y == y)) return x + y;
  const bool y_integer = floorf(y) == y;
  if (y_integer && abs_f(y) <= 16777216.f) {
    uint32_t n = static_cast<uint32_t>(abs_f(y));
    double base = static_cast<double>(x);
    double r = 1.0;
    while (n != 0u) {
      if (n & 1u) r = r * base;
      n >>= 1;
      if (n != 0u) base = base * base;
    }
    if (y < 0.f) r = 1.0 / r;
    return static_cast<float>(r);
  }
  float ax = x;
  if (x < 0.f) {
    if (!y_integer) return bits_float(0x7fc00000u);  // NaN: negative base, fractional power
    ax = -x;  // |y| > 2^24 is an even integer
  }
  const float inf = bits_float(0x7f800000u);
  if (ax == 0.f) return y > 0.f ? 0.f : inf;
  if (ax == inf) return y > 0.f ? inf : 0.f;
  return static_cast<float>(det_exp_d(static_cast<double>(y) * det_log_d(static_cast<double>(ax))));
}

// asin(x) for |x| <= 1/2: x + x^3 P(x^2), Cephes' asinf polynomial (relative error about
// 2.5e-7 there), in a fixed order of float operations.
SVGF_HD float det_asin_small(float x) {
  const float z = x * x;
  const float p =
      (((4.2163199048e-2f * z + 2.4181311049e-2f) * z + 4.5470025998e-2f) * z + 7.4953002686e-2f) *
          z +
      1.6666752422e-1f;
  return x + x * (z * p);
}

// IEEE square root: the same bits on both sides.
struct IeeeSqrt {
  SVGF_HD float operator()(float x) const { return sqrtf(x); }
};

// acos(x) for x in [-1, 1] (Cephes' acosf): near +-1 through asin of sqrt((1 -+ x) / 2), so the
// small angles keep their relative accuracy. With IEEE sqrt (det_acos) the same bits on both
// sides, absolute error below 4e-7 (tests/det_math_test.cpp); fast mode passes an approximate
// square root (FastArith::acos). NaN stays NaN.
// Written with selects instead of branches so the CPU rows vectorize it; the values are those
// of picking the branch first (for x < -1/2, 0.5 - 0.5 |x| is 0.5 + 0.5 x exactly).
template <class Sqrt>
SVGF_HD float acos_cephes(float x, Sqrt sqrt_of) {
  const float ax = abs_f(x);
  const float s = det_asin_small(ax > 0.5f ? sqrt_of(0.5f - 0.5f * ax) : x);
  return x > 0.5f ? 2.f * s : (x < -0.5f ? 3.14159274f - 2.f * s : 1.57079637f - s);
}

SVGF_HD float det_acos(float x) { return acos_cephes(x, IeeeSqrt()); }

}  // namespace svgf

// The project's exp and pow against the C library evaluated in double and rounded to float
// (correctly rounded but for astronomically rare cases), over their whole input range.
#include <cmath>
#include <algorithm>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <vector>

#include <catch2/catch.hpp>

#include "core/arith.h"
#include "core/det_math.h"

using namespace svgf;

namespace {

// Distance in units in the last place between two floats of the same sign (or zero).
int64_t ulp_distance(float a, float b) {
  if (std::isnan(a) || std::isnan(b)) return (std::isnan(a) && std::isnan(b)) ? 0 : INT64_MAX;
  auto ordered = [](float f) {
    const int32_t i = static_cast<int32_t>(float_bits(f));
    return i < 0 ? int64_t(INT32_MIN) - i : int64_t(i);  // monotonic map of the bit patterns
  };
  const int64_t d = ordered(a) - ordered(b);
  return d < 0 ? -d : d;
}

float ref_exp(float x) { return static_cast<float>(std::exp(static_cast<double>(x))); }
float ref_pow(float x, float y) {
  return static_cast<float>(std::pow(static_cast<double>(x), static_cast<double>(y)));
}

}  // namespace

TEST_CASE("det_exp is within 2 ulp of exp over every 61st float in [-104, 89]", "[det_math]") {
  int64_t worst = 0;
  float worst_x = 0;
  uint64_t n = 0;
  // All negative floats down to -104 and all positive floats up to 89, stepping through the bit
  // patterns (every binade is visited at the same density; 61 is prime to avoid aliasing).
  for (int sign = 0; sign < 2; ++sign) {
    const uint32_t end = float_bits(sign ? 104.f : 89.f);
    for (uint32_t b = 0; b <= end; b += 61) {
      const float x = sign ? -bits_float(b) : bits_float(b);
      const int64_t d = ulp_distance(det_exp(x), ref_exp(x));
      if (d > worst) { worst = d; worst_x = x; }
      ++n;
    }
  }
  INFO("worst " << worst << " ulp at x = " << worst_x << " over " << n << " inputs");
  CHECK(n > 30000000u);
  REQUIRE(worst <= 2);
}

TEST_CASE("det_exp special values", "[det_math]") {
  const float inf = std::numeric_limits<float>::infinity();
  CHECK(det_exp(0.f) == 1.f);
  CHECK(det_exp(-inf) == 0.f);
  CHECK(det_exp(inf) == inf);
  CHECK(det_exp(89.f) == inf);
  CHECK(det_exp(-104.f) == 0.f);
  CHECK(std::isnan(det_exp(std::numeric_limits<float>::quiet_NaN())));
  // Subnormal results are kept, not flushed: exp(-100) = 3.72e-44.
  CHECK(det_exp(-100.f) > 0.f);
  CHECK(det_exp(-100.f) < std::numeric_limits<float>::min());
  CHECK(ulp_distance(det_exp(-100.f), ref_exp(-100.f)) <= 1);
}

TEST_CASE("det_pow with integer exponents is within 1 ulp of pow", "[det_math]") {
  int64_t worst = 0;
  const float exponents[] = {1, 2, 3, 7, 16, 64, 128, 129, 255, -1, -2, -5, -128, 1000};
  for (float y : exponents) {
    // x over all positive floats (every 4099th bit pattern), and some negative bases.
    for (uint32_t b = 1; b < 0x7f800000u; b += 4099) {
      const float x = bits_float(b);
      worst = std::max(worst, ulp_distance(det_pow(x, y), ref_pow(x, y)));
      worst = std::max(worst, ulp_distance(det_pow(-x, y), ref_pow(-x, y)));
    }
  }
  INFO("worst " << worst << " ulp");
  REQUIRE(worst <= 1);
}

TEST_CASE("det_pow with fractional exponents is within 1 ulp of pow", "[det_math]") {
  int64_t worst = 0;
  float worst_x = 0, worst_y = 0;
  const float exponents[] = {0.5f, 1.f / 2.4f, 2.4f, 0.1f, -0.5f, -1.7f, 3.3f, 10.5f, 127.5f};
  for (float y : exponents) {
    for (uint32_t b = 1; b < 0x7f800000u; b += 1021) {
      const float x = bits_float(b);
      const int64_t d = ulp_distance(det_pow(x, y), ref_pow(x, y));
      if (d > worst) { worst = d; worst_x = x; worst_y = y; }
    }
  }
  INFO("worst " << worst << " ulp at pow(" << worst_x << ", " << worst_y << ")");
  REQUIRE(worst <= 1);
}

TEST_CASE("det_pow special values", "[det_math]") {
  const float inf = std::numeric_limits<float>::infinity();
  CHECK(det_pow(0.f, 0.f) == 1.f);
  CHECK(det_pow(0.f, 128.f) == 0.f);
  CHECK(det_pow(0.f, 0.5f) == 0.f);
  CHECK(det_pow(0.f, -0.5f) == inf);
  CHECK(det_pow(inf, 0.5f) == inf);
  CHECK(det_pow(-2.f, 3.f) == -8.f);
  CHECK(std::isnan(det_pow(-2.f, 0.5f)));
  CHECK(std::isnan(det_pow(std::numeric_limits<float>::quiet_NaN(), 2.f)));
  // 0.5^140 = 2^-140 is subnormal in float and must come out exactly.
  CHECK(det_pow(0.5f, 140.f) == std::ldexp(1.f, -140));
}

namespace {

// det_exp_clamped's last step, y 2^k, before it split k at floor(k/2): the split at k/2
// (truncated). Both round y 2^k once, so they must agree bit for bit.
float scale_pow2_split_at_half(float y, int k) {
  const int k1 = k / 2;
  const int k2 = k - k1;
  return (y * bits_float(static_cast<uint32_t>(k1 + 127) << 23)) *
         bits_float(static_cast<uint32_t>(k2 + 127) << 23);
}

// det_exp_clamped as it was before floorf and det_scale_pow2: k through truncation
// (floor_small_int), 2^k split at k/2 (the same polynomial).
float det_exp_clamped_before(float xc) {
  const int ki = floor_small_int(xc * 1.44269504088896341f + 0.5f);
  const float k = static_cast<float>(ki);
  const float r = (xc - k * 0.693145751953125f) - k * 1.428606765330187e-06f;
  return scale_pow2_split_at_half(det_exp_poly(r), ki);
}

}  // namespace

TEST_CASE("det_exp_clamped gives the bits of its earlier form on [-104, 89]", "[det_math]") {
  // Every 31st float of the clamped range, both signs, and the ends: floorf against floor
  // through truncation, the split of 2^k at floor(k/2) against k/2 (exact-mode bits must not
  // move). det_scale_pow2's test below covers every k with more y.
  uint64_t differing = 0, n = 0;
  const auto check = [&](float x) {
    differing += float_bits(det_exp_clamped(x)) != float_bits(det_exp_clamped_before(x));
    ++n;
  };
  for (uint32_t b = 0; b <= float_bits(104.f); b += 31) check(-bits_float(b));
  for (uint32_t b = 0; b <= float_bits(89.f); b += 31) check(bits_float(b));
  for (float x : {-104.f, 89.f, -0.f, 0.f, -103.97f, -0.3465736f, 0.3465736f}) check(x);
  CHECK(n > 70000000u);
  REQUIRE(differing == 0);
}

namespace {

// Two ways of y 2^k over k = k_first..k_last and y over e^r's range and a little beyond (every
// stride-th float of it and its last): how many values were compared, how many differ and how
// many of `got`'s are subnormal.
struct ScaleComparison {
  uint64_t n = 0, differing = 0, subnormal = 0;
};
template <class Got, class Want>
ScaleComparison compare_scales(int k_first, int k_last, uint32_t stride, const Got& got,
                               const Want& want) {
  const uint32_t first = float_bits(0.69f), last = float_bits(1.43f);
  ScaleComparison c;
  for (int k = k_first; k <= k_last; ++k) {
    const auto check = [&](uint32_t b) {
      const float y = bits_float(b), g = got(y, k);
      c.differing += float_bits(g) != float_bits(want(y, k));
      c.subnormal += std::fpclassify(g) == FP_SUBNORMAL;
      ++c.n;
    };
    for (uint32_t b = first; b < last; b += stride) check(b);
    check(last);
  }
  return c;
}

}  // namespace

TEST_CASE("det_scale_pow2 gives the bits of the split at k/2 for every k of det_exp",
          "[det_math]") {
  // Every k det_exp_clamped makes (x in [-104, 89]), every 61st y, subnormal results (k below
  // -126) included.
  const ScaleComparison c = compare_scales(
      -150, 128, 61, [](float y, int k) { return det_scale_pow2(y, k); },
      [](float y, int k) { return scale_pow2_split_at_half(y, k); });
  CHECK(c.n > 20000000u);
  CHECK(c.subnormal > 1000000u);
  REQUIRE(c.differing == 0);
  REQUIRE(det_scale_pow2(1.f, -149) == std::ldexp(1.f, -149));  // the smallest subnormal
  REQUIRE(det_scale_pow2(1.f, 127) == std::ldexp(1.f, 127));
}

TEST_CASE("det_scale_pow2_nonpositive gives det_scale_pow2's bits for every k <= 0 of det_exp",
          "[det_math]") {
  // Every k det_exp_nonpositive makes (x in [-104, 0]), every 13th y, subnormal results
  // included.
  const ScaleComparison c = compare_scales(
      -150, 0, 13,
      [](float y, int k) { return det_scale_pow2_nonpositive(y, static_cast<float>(k)); },
      [](float y, int k) { return det_scale_pow2(y, k); });
  CHECK(c.n > 50000000u);
  CHECK(c.subnormal > 10000000u);
  REQUIRE(c.differing == 0);
  REQUIRE(det_scale_pow2_nonpositive(1.f, -149.f) == std::ldexp(1.f, -149));
  REQUIRE(det_scale_pow2_nonpositive(1.f, -150.f) == 0.f);  // 2^-150 rounds to even: 0
  REQUIRE(det_scale_pow2_nonpositive(1.4f, 0.f) == 1.4f);
}

// The GPU and the x86-64-v3/v4 CPU kernels evaluate the reduction's x - k ln2_hi as one FMA
// (sub_exact_product; this binary takes the separate form, the variant tests the fused one):
// the same bits only because k ln2_hi is exact for every k the reduction makes (|k| <= 150; the
// claim holds to 255). Here the product's exactness for every such k, and the fused form
// (std::fma, one rounding) against the separate one at the k of every 61st float in
// [-104, 89].
TEST_CASE("x - k ln2_hi in one FMA gives the separate form's bits", "[det_math]") {
  const float ln2_hi = 0.693145751953125f;
  for (int k = -255; k <= 255; ++k) {
    const float kf = static_cast<float>(k);
    REQUIRE(static_cast<double>(kf * ln2_hi) ==
            static_cast<double>(kf) * static_cast<double>(ln2_hi));
  }
  uint64_t differing = 0, n = 0;
  for (const float sign : {1.f, -1.f}) {
    const uint32_t end = float_bits(sign > 0 ? 89.f : 104.f);
    for (uint32_t b = 0; b <= end; b += 61, ++n) {
      const float x = sign * bits_float(b);
      const float k = std::floor(x * 1.44269504088896341f + 0.5f);
      differing += float_bits(std::fma(-k, ln2_hi, x)) != float_bits(x - k * ln2_hi);
      differing += float_bits(sub_exact_product(x, k, ln2_hi)) != float_bits(x - k * ln2_hi);
    }
  }
  CHECK(n > 30000000u);
  REQUIRE(differing == 0);
}

TEST_CASE("det_exp_nonpositive gives det_exp's bits for every x <= 0", "[det_math]") {
  const uint32_t end = float_bits(110.f);
  uint64_t differing = 0, n = 0;
  for (uint32_t b = 0; b <= end; b += 7, ++n) {
    const float x = -bits_float(b);
    differing += float_bits(det_exp_nonpositive(x)) != float_bits(det_exp(x));
  }
  CHECK(n > 100000000u);
  REQUIRE(differing == 0);
  REQUIRE(det_exp_nonpositive(-std::numeric_limits<float>::infinity()) == 0.f);
  REQUIRE(det_exp_nonpositive(std::numeric_limits<float>::quiet_NaN()) == 0.f);
}

TEST_CASE("det_acos is within 4e-7 of acos on [-1, 1], exact at the ends", "[det_math]") {
  double worst = 0;
  int count = 0;
  for (int k = -200000; k <= 200000; ++k) {
    const float x = static_cast<float>(k) / 200000.f;
    const double err = std::fabs(double(det_acos(x)) - std::acos(double(x)));
    worst = std::max(worst, err);
    ++count;
  }
  // The small angles near 1 keep their relative accuracy (the JBF's normal term squares them).
  for (float t : {1e-3f, 1e-2f, 0.1f}) {
    const float x = std::cos(t);
    INFO("angle " << t);
    REQUIRE(std::fabs(double(det_acos(x)) - std::acos(double(x))) <= 3e-7 * std::acos(double(x)) + 1e-7);
  }
  INFO(count << " values, worst error " << worst);
  REQUIRE(worst <= 4e-7);
  REQUIRE(det_acos(1.f) == 0.f);
  REQUIRE(std::fabs(det_acos(-1.f) - 3.14159265f) <= 3e-7f);
  REQUIRE(std::isnan(det_acos(std::numeric_limits<float>::quiet_NaN())));
}

// det_acos is written with selects so that it vectorizes; its comment promises the values of
// picking the branch first. Checked against that form on every 61st float of [-1, 1].
TEST_CASE("det_acos gives the bits of its branching form", "[det_math]") {
  const auto branching = [](float x) {
    if (x > 0.5f) return 2.f * det_asin_small(sqrtf(0.5f - 0.5f * x));
    if (x < -0.5f) return 3.14159274f - 2.f * det_asin_small(sqrtf(0.5f + 0.5f * x));
    return 1.57079637f - det_asin_small(x);
  };
  const uint32_t one = float_bits(1.f);
  size_t checked = 0, differing = 0;
  for (uint32_t sign : {0u, 0x80000000u})
    for (uint32_t u = 0; u <= one; u += (u + 61 > one && u != one) ? one - u : 61) {
      const float x = bits_float(u | sign);
      differing += float_bits(det_acos(x)) != float_bits(branching(x));
      ++checked;
    }
  INFO(checked << " values");
  REQUIRE(checked > 30000000);
  REQUIRE(differing == 0);
}

// The edge-stopping weight takes |x| as a sign-bit clear (abs_before_clamp) where a max(., 0)
// clamp follows: that must give abs_f's bits after the clamp, -0 and NaN of either sign included.
TEST_CASE("abs_before_clamp then max(., 0) gives abs's bits", "[det_math]") {
  const float inf = std::numeric_limits<float>::infinity();
  const float scales[] = {0.f, -0.f, 1.f, 3.7f, -2.f, 1e-30f, 1e30f, inf, -inf,
                          std::numeric_limits<float>::quiet_NaN()};
  uint64_t differing = 0, n = 0;
  for (uint64_t b = 0; b <= 0xffffffffull; b += 4099, ++n) {
    for (const uint32_t sign : {0u, 0x80000000u}) {  // both signs of each magnitude (and NaN)
      const float x = bits_float(static_cast<uint32_t>(b) ^ sign);
      for (const float s : scales)
        differing += float_bits(max_f(ExactArith::abs_before_clamp(x) * s, 0.f)) !=
                     float_bits(max_f(abs_f(x) * s, 0.f));
    }
  }
  CHECK(n > 1000000u);
  REQUIRE(differing == 0);
}

// The edge-stopping weights' exp(-(a + b)) (ExactArith::exp_neg_sum) evaluates exp((-a) - b);
// it must give the bits of exp((0 - a) - b), its form before, for every a, b >= 0 the weights
// pass (their terms clamped by max(., 0): +0 .. +Inf, and -0 and NaN for good measure).
TEST_CASE("exp_neg_sum gives the bits of exp((0 - a) - b)", "[det_math]") {
  std::vector<float> terms = {0.f, -0.f, std::numeric_limits<float>::infinity(),
                              std::numeric_limits<float>::quiet_NaN(),
                              std::numeric_limits<float>::denorm_min(), 1e-30f, 103.97f, 200.f};
  for (uint32_t b = 0; b < 0x7f800000u; b += 0x7f800000u / 4099) terms.push_back(bits_float(b));
  uint64_t differing = 0, n = 0;
  for (const float a : terms)
    for (const float b : terms) {
      ++n;
      differing += float_bits(ExactArith::exp_neg_sum(a, b)) !=
                   float_bits(det_exp_nonpositive((0.f - a) - b));
    }
  CHECK(n > 16000000u);
  REQUIRE(differing == 0);
}

// The unrolled a-trous taps scale 1 / phi_z by a factored tap distance (ExactArith::
// with_depth_scale, then the scale's tap(dx, dy)): for every tap of the 5x5 footprint, every
// power-of-two step up to 2^12 and 1 / phi_z across the floats (signed zeros, subnormals, Inf,
// NaN), it must give the full expression's bits. A step that is not a power of two takes the
// full expression.
TEST_CASE("with_depth_scale's taps give tap_depth_scale's bits", "[det_math]") {
  uint64_t differing = 0, n = 0, factored = 0;
  for (int step : {1, 2, 4, 8, 16, 32, 64, 128, 256, 512, 1024, 2048, 4096, 3, 6, 12})
    for (uint64_t b = 0; b <= 0xffffffffull; b += 65537) {
      const float s = bits_float(static_cast<uint32_t>(b));
      ExactArith::with_depth_scale(s, step, [&](const auto& scale) {
        factored += std::is_same<std::decay_t<decltype(scale)>,
                                 ExactArith::PowerOfTwoStepScale>::value;
        for (int dy = -2; dy <= 2; ++dy)
          for (int dx = -2; dx <= 2; ++dx) {
            ++n;
            differing += float_bits(scale.tap(dx, dy)) !=
                         float_bits(ExactArith::tap_depth_scale(s, dx, dy, step));
          }
      });
    }
  CHECK(n > 20000000u);
  CHECK(factored == 13u * (0xffffffffull / 65537 + 1));  // the 13 powers of two, every value
  REQUIRE(differing == 0);
}

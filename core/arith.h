#pragma once
// Arithmetic policies: the per-pixel functors are written once and take one of these as a
// template parameter, so exact and fast mode differ in how a formula is evaluated, never in
// which formula it is (docs/architecture.md, "Fast mode without a second copy").
//
//  ExactArith: IEEE + - * / and sqrt, the project's det_exp/det_pow, every sum rounded in the
//              written order. Compiled without contraction on both sides: the CPU and the GPU
//              give the same bits.
//  FastArith:  GPU intrinsics where they pay: ex2.approx.ftz for exp, approximate reciprocals
//              and rsqrt, FMA for the running sums and dot products, fmaxf/fminf and the .SAT
//              clamp. Device code only; its tolerance against exact mode, per stage and per
//              frame, is written in docs/cuda.md and checked by the GPU tests.
#include <cmath>

#include "core/det_math.h"
#include "core/hd.h"
#include "core/vec.h"

namespace svgf {

struct ExactArith {
  // max/min/abs with the project's NaN rules (core/vec.h: max_f(NaN, b) is b, max_f(a, NaN) is
  // NaN), which the edge-stopping weights rely on; the same select on both sides.
  SVGF_HD static float max(float a, float b) { return max_f(a, b); }
  SVGF_HD static float min(float a, float b) { return min_f(a, b); }
  SVGF_HD static float abs(float a) { return abs_f(a); }
  // |a| by clearing the sign bit (one vector AND; abs is a compare and a select). It differs from
  // abs only in the sign of -0 and of NaN, for terms that a max(., 0) clamps next, which erases
  // both: the same bits there.
  SVGF_HD static float abs_before_clamp(float a) { return fabsf(a); }
  // The selects against constants below take K, how they see their constants (core/vec.h,
  // LiteralConstant; the CPU rows' RowExactArith passes its OpaqueConstant): the same values.
  // Clamped to [0, 1]; NaN stays NaN (it zeroes the weight it enters).
  template <class K = LiteralConstant>
  SVGF_HD static float saturate(float a) { return min_f(K::of(1.f), max_f(K::of(0.f), a)); }
  template <class K = LiteralConstant>
  SVGF_HD_INLINE static float exp_nonpositive(float x) { return det_exp_nonpositive<K>(x); }
  // exp(-(a + b)) for a, b >= 0, evaluated as exp((-a) - b). It was exp((0 - a) - b): the two
  // differ only in the sign of a zero argument (a = b = +0), whose exp is 1 either way, so the
  // bits are the same (tests/det_math_test.cpp), and on the GPU the negation is an operand's
  // modifier, one add a tap fewer.
  template <class K = LiteralConstant>
  SVGF_HD_INLINE static float exp_neg_sum(float a, float b) {
    return det_exp_nonpositive<K>(-a - b);
  }
  SVGF_HD static float pow(float x, float y) { return det_pow(x, y); }
  SVGF_HD static float dot(Vec3 a, Vec3 b) { return svgf::dot(a, b); }
  // c + a * b, rounded twice (no FMA).
  SVGF_HD static float mad(float a, float b, float c) { return c + a * b; }
  SVGF_HD static Vec3 mad(Vec3 a, float b, Vec3 c) { return c + a * b; }
  SVGF_HD static Vec2 mad(Vec2 a, float b, Vec2 c) { return c + a * b; }
  SVGF_HD static float recip(float x) { return 1.f / x; }
  SVGF_HD static float sqrt(float x) { return sqrtf(x); }
  SVGF_HD static float acos(float x) { return det_acos(x); }
  // 1 / (scale * sqrt(x)).
  SVGF_HD static float inv_scaled_sqrt(float scale, float x) { return 1.f / (scale * sqrtf(x)); }
  // Division by one value, several times: IEEE division each time.
  struct Divider {
    float d;
    SVGF_HD float operator()(float x) const { return x / d; }
    SVGF_HD Vec3 operator()(Vec3 v) const { return v / d; }
    SVGF_HD Vec2 operator()(Vec2 v) const { return v / d; }
  };
  SVGF_HD static Divider divide_by(float d) { return Divider{d}; }
  // w where w > 0, else 0 (NaN too).
  template <class K = LiteralConstant>
  SVGF_HD static float positive_part(float w) { return max_f(w, K::of(0.f)); }
  // inv_phi_z scaled by 1 / distance in pixels of the tap (dx, dy) * step; at the centre the
  // distance is 0 and the scale Inf (see edge_stopping_weight for why that drops the term).
  SVGF_HD static float tap_depth_scale(float inv_phi_z, int dx, int dy, int step) {
    const float fx = static_cast<float>(dx * step);
    const float fy = static_cast<float>(dy * step);
    return inv_phi_z * (1.f / sqrtf(fx * fx + fy * fy));
  }
  // The same in a fully unrolled 5x5 tap loop (dx, dy known at compile time), in two parts:
  // once per pixel (with_depth_scale picks the scale's form), then per tap (its tap(dx, dy)).
  // For a power-of-two step (every a-trous step) the scale above is exactly
  // inv_phi_z * ((1 / sqrt(dx^2 + dy^2)) * (1 / step)): the step multiplies the sum by a power
  // of four, the root by a power of two and the reciprocal by its inverse, and IEEE rounding
  // commutes with such scalings (no overflow or underflow at these sizes). Constant dx, dy make
  // the first factor a compile-time constant and 1 / step is the pixel's, so a tap costs two
  // multiplies instead of an IEEE square root and division (tests/det_math_test.cpp checks the
  // bits for every tap and step). Other steps keep the full expression.
  struct PowerOfTwoStepScale {
    float inv_phi_z;
    float inv_step;  // 1 / step, IEEE
    SVGF_HD float tap(int dx, int dy) const {
      const float inv_distance = 1.f / sqrtf(static_cast<float>(dx * dx + dy * dy));
      return inv_phi_z * (inv_distance * inv_step);
    }
  };
  struct AnyStepScale {
    float inv_phi_z;
    int step;
    SVGF_HD float tap(int dx, int dy) const { return tap_depth_scale(inv_phi_z, dx, dy, step); }
  };
  // body(scale) with the pixel's scale; the step's test and its reciprocal once a pixel, not
  // once a tap (on the GPU each tap paid them, about 13 SASS instructions: nvcc did not hoist
  // the IEEE reciprocal out of the tap's branch; docs/benchmarks.md has what it saved).
  template <class Body>
  SVGF_HD static void with_depth_scale(float inv_phi_z, int step, const Body& body) {
    if ((step & (step - 1)) == 0)
      body(PowerOfTwoStepScale{inv_phi_z, 1.f / static_cast<float>(step)});
    else
      body(AnyStepScale{inv_phi_z, step});
  }
};

// 1 / sqrt(dx^2 + dy^2) for the taps of a 5x5 footprint as constants (an unrolled tap loop
// folds them); -1 at the centre and outside the footprint.
SVGF_HD constexpr float inv_distance_small(int dx, int dy) {
  const int d2 = dx * dx + dy * dy;
  return d2 == 1   ? 1.f
         : d2 == 2 ? 0.70710678f
         : d2 == 4 ? 0.5f
         : d2 == 5 ? 0.44721360f
         : d2 == 8 ? 0.35355339f
                   : -1.f;
}

// Rec. 709 luminance (core/vec.h) evaluated with an arithmetic policy.
template <class Arith>
SVGF_HD float luminance_with(Vec3 c) { return Arith::dot(rec709_weights(), c); }

#if defined(__CUDACC__)
struct FastArith {
  // One instruction each (FMNMX, FADD |x|). fmaxf/fminf return the non-NaN operand: where the
  // exact rules keep a NaN to zero a weight, these drop it instead; the callers' results agree
  // (edge_stopping_weight: a NaN normal gives cos 0, hence weight 0, either way).
  __device__ __forceinline__ static float max(float a, float b) { return fmaxf(a, b); }
  __device__ __forceinline__ static float min(float a, float b) { return fminf(a, b); }
  __device__ __forceinline__ static float abs(float a) { return fabsf(a); }
  __device__ __forceinline__ static float abs_before_clamp(float a) { return fabsf(a); }
  // Clamped to [0, 1] by the .SAT modifier of the instruction that computes `a` (free); NaN
  // gives 0.
  __device__ __forceinline__ static float saturate(float a) { return __saturatef(a); }
  // 2^(x log2 e) on the special-function unit, subnormal results flushed to 0 (.ftz: without
  // it the compiler adds range fix-ups around every exp; the weights lose nothing they use).
  __device__ __forceinline__ static float exp2_ftz(float x) {
    float r;
    asm("ex2.approx.ftz.f32 %0, %1;" : "=f"(r) : "f"(x));
    return r;
  }
  __device__ __forceinline__ static float exp_nonpositive(float x) {
    return exp2_ftz(x * 1.44269504f);
  }
  __device__ __forceinline__ static float exp_neg_sum(float a, float b) {
    return exp2_ftz((a + b) * -1.44269504f);
  }
  __device__ __forceinline__ static float pow(float x, float y) {
    return x > 0.f ? __powf(x, y) : (y > 0.f ? 0.f : 1.f);
  }
  __device__ __forceinline__ static float dot(Vec3 a, Vec3 b) {
    return __fmaf_rn(a.z, b.z, __fmaf_rn(a.y, b.y, a.x * b.x));
  }
  __device__ __forceinline__ static float mad(float a, float b, float c) {
    return __fmaf_rn(a, b, c);
  }
  __device__ __forceinline__ static Vec3 mad(Vec3 a, float b, Vec3 c) {
    return make_vec3(__fmaf_rn(a.x, b, c.x), __fmaf_rn(a.y, b, c.y), __fmaf_rn(a.z, b, c.z));
  }
  __device__ __forceinline__ static Vec2 mad(Vec2 a, float b, Vec2 c) {
    return make_vec2(__fmaf_rn(a.x, b, c.x), __fmaf_rn(a.y, b, c.y));
  }
  __device__ __forceinline__ static float recip(float x) { return __fdividef(1.f, x); }
  // One special-function instruction (relative error about 2^-22); 0 stays 0.
  __device__ __forceinline__ static float sqrt(float x) {
    float r;
    asm("sqrt.approx.ftz.f32 %0, %1;" : "=f"(r) : "f"(x));
    return r;
  }
  struct ApproxSqrt {
    __device__ __forceinline__ float operator()(float x) const { return FastArith::sqrt(x); }
  };
  // Exact mode's polynomial (core/det_math.h) around the approximate square root.
  __device__ __forceinline__ static float acos(float x) { return acos_cephes(x, ApproxSqrt()); }
  __device__ __forceinline__ static float inv_scaled_sqrt(float scale, float x) {
    return rsqrtf(x) * __fdividef(1.f, scale);
  }
  // One approximate reciprocal, then products.
  struct Divider {
    float r;
    __device__ __forceinline__ float operator()(float x) const { return x * r; }
    __device__ __forceinline__ Vec3 operator()(Vec3 v) const { return v * r; }
    __device__ __forceinline__ Vec2 operator()(Vec2 v) const { return v * r; }
  };
  __device__ __forceinline__ static Divider divide_by(float d) {
    return Divider{__fdividef(1.f, d)};
  }
  // The weight's last select is not needed: the exponent's terms went through fmaxf (no NaN)
  // and both factors lie in [0, 1], so the product is a number >= 0.
  __device__ __forceinline__ static float positive_part(float w) { return w; }
  // Any tap: one rsqrt (the centre gives Inf, as in exact mode).
  __device__ __forceinline__ static float tap_depth_scale(float inv_phi_z, int dx, int dy,
                                                          int step) {
    return (inv_phi_z * __fdividef(1.f, static_cast<float>(step))) *
           rsqrtf(static_cast<float>(dx * dx + dy * dy));
  }
  // In an unrolled 5x5 loop: inv_phi_z / step once per pixel, then one multiply by a constant
  // per tap (ExactArith::with_depth_scale's form).
  struct PixelDepthScale {
    float per_step;  // inv_phi_z / step
    __device__ __forceinline__ float tap(int dx, int dy) const {
      const float c = inv_distance_small(dx, dy);
      return per_step * (c >= 0.f ? c : __int_as_float(0x7f800000));  // centre: Inf
    }
  };
  template <class Body>
  __device__ __forceinline__ static void with_depth_scale(float inv_phi_z, int step,
                                                          const Body& body) {
    body(PixelDepthScale{inv_phi_z * __fdividef(1.f, static_cast<float>(step))});
  }
};
#endif

}  // namespace svgf

#pragma once
// What the vectorized CPU row drivers share (svgf_rows, wavelet_rows, jbf_rows): they loop over
// a kernel's taps outside and over a row of pixels inside, so each inner loop is straight-line
// SIMD code, and every pixel still sums the same terms in the per-pixel kernel's order (same
// bits as the per-pixel kernel, hence as the GPU).
#include <memory>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/arith.h"
#include "core/normal_weight.h"
#include "core/views.h"
#include "kernels_cpu/ieee_guard.h"
#include "kernels_cpu/parallel_for.h"

namespace svgf::cpu {

// GCC vectorizes the tap loops only as functions of their own whose arrays are all restrict
// arguments: inlined into the row, the restrict promise is lost and the loop stays scalar.
#define SVGF_TAP_LOOP __attribute__((noinline))

// 1, where the optimizer cannot see it: noipa hides the body from every caller, const lets the
// loop-invariant call move out of the row loops (one call a loop, not a pixel). Other compilers
// see a plain 1 (the same values; only the instruction choice below is lost).
#if defined(__GNUC__) && !defined(__clang__)
__attribute__((noipa, const)) inline float opaque_one() { return 1.f; }
#else
inline float opaque_one() { return 1.f; }
#endif

// A select's constant multiplied by that 1: the same value for every constant (c * 1 is c,
// -0, subnormals and Inf included), but one GCC cannot fold into the select. Against a literal,
// GCC 12 vectorizes max_f(x, 0.f) as a compare and a zero-masked move and the saturate as
// compares, mask logic and blends; against this, as one vmaxps or vminps, whose rule
// (a > b ? a : b) is max_f's exactly. The a-trous tap row's loop on x86-64-v4: 586 -> 445
// instructions, no mask register left in it. A value that is not a compile-time constant
// passes as it is (no multiply).
struct OpaqueConstant {
#if defined(__GNUC__)
  static float of(float c) { return __builtin_constant_p(c) ? c * opaque_one() : c; }
#else
  static float of(float c) { return c; }
#endif
};

// Exact mode's arithmetic with its selects against constants written for the vectorizer: the
// same functions as ExactArith and the same bits (the rows tests hold them: tests/
// svgf_cpu_rows_test.cpp, wavelet_cpu_rows_test.cpp, jbf_cpu_rows_test.cpp).
struct RowExactArith : ExactArith {
  static float max(float a, float b) { return max_f(OpaqueConstant::of(a), OpaqueConstant::of(b)); }
  static float min(float a, float b) { return min_f(OpaqueConstant::of(a), OpaqueConstant::of(b)); }
  static float saturate(float a) { return ExactArith::saturate<OpaqueConstant>(a); }
  static float exp_nonpositive(float x) { return ExactArith::exp_nonpositive<OpaqueConstant>(x); }
  static float exp_neg_sum(float a, float b) {
    return ExactArith::exp_neg_sum<OpaqueConstant>(a, b);
  }
  static float positive_part(float w) { return ExactArith::positive_part<OpaqueConstant>(w); }
};

// Runs body(power) with the normal-weight power as a compile-time policy for the usual
// exponents 2^0 .. 2^10, else the run-time one. Same bits either way (NormalPower).
template <class Body>
void with_normal_power(float phi_normal, const Body& body) {
  const NormalPower<> p = NormalPower<>::of(phi_normal);
  switch (p.squarings) {
    case 0: return body(NormalPowerFixed<0>());
    case 1: return body(NormalPowerFixed<1>());
    case 2: return body(NormalPowerFixed<2>());
    case 3: return body(NormalPowerFixed<3>());
    case 4: return body(NormalPowerFixed<4>());
    case 5: return body(NormalPowerFixed<5>());
    case 6: return body(NormalPowerFixed<6>());
    case 7: return body(NormalPowerFixed<7>());
    case 8: return body(NormalPowerFixed<8>());
    case 9: return body(NormalPowerFixed<9>());
    case 10: return body(NormalPowerFixed<10>());
    default: return body(p);
  }
}

// A float vector's lanes on the widest instruction set the rows are built for (x86-64-v4):
// GCC 12 has no masked loop tails on x86, so a loop of fewer pixels, or its last partial
// vector, runs one pixel at a time; short loops are widened to whole vectors of these.
inline constexpr int kVectorLanes = 16;

// rows(y0, y1) over the image's rows with TBB, in the IEEE mode the kernels need.
template <class Rows>
void parallel_rows(int height, const Rows& rows) {
  tbb::parallel_for(tbb::blocked_range<int>(0, height, kRowsPerTask),
                    [&](const tbb::blocked_range<int>& r) {
                      ScopedIeeeFloat ieee;
                      rows(r.begin(), r.end());
                    });
}

// Per-task scratch: `planes` rows of `width` floats (a row's centre terms and running sums).
// n values of a trivial type T, left uninitialized: for a plane a parallel loop then writes
// whole. A std::vector would first zero it on the calling thread (a 720p plane is 3.7 MB, and
// the luminance alone is five planes a frame).
template <class T>
class UninitializedPlane {
 public:
  explicit UninitializedPlane(size_t n) : values_(new T[n]) {}
  T* data() { return values_.get(); }
  const T* data() const { return values_.get(); }

 private:
  std::unique_ptr<T[]> values_;
};

struct RowScratch {
  std::vector<std::vector<float>> plane;
  RowScratch(int planes, int width) : plane(static_cast<size_t>(planes), std::vector<float>(width)) {}
  float* operator[](int k) { return plane[static_cast<size_t>(k)].data(); }
};

// The weighted color sums of a row of a filter pass whose centre weighs `centre_weight`:
// started with the centre's own term, finished as sum / weight on surfaces (depth > 0), the
// input passed through elsewhere: the per-pixel kernels' first and last lines.
struct ColorSums {
  float* weight;
  float* r;
  float* g;
  float* b;
  ColorSums(RowScratch& s, int first)
      : weight(s[first]), r(s[first + 1]), g(s[first + 2]), b(s[first + 3]) {}

  void start(ConstRgbView in, int row, int width, float centre_weight) const {
    for (int x = 0; x < width; ++x) {
      const int i = row + x;
      weight[x] = centre_weight;
      r[x] = in.r[i] * centre_weight;
      g[x] = in.g[i] * centre_weight;
      b[x] = in.b[i] * centre_weight;
    }
  }
  void finish(const float* depth, ConstRgbView in, RgbView out, int row, int width) const {
    for (int x = 0; x < width; ++x) {
      const int i = row + x;
      out.store(i, depth[i] > 0.f
                       ? ExactArith::divide_by(weight[x])(make_vec3(r[x], g[x], b[x]))
                       : in.load(i));
    }
  }
};

}  // namespace svgf::cpu

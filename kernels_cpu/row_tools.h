#pragma once
// What the vectorized CPU row drivers share (svgf_rows, wavelet_rows, jbf_rows): they loop over
// a kernel's taps outside and over a row of pixels inside, so each inner loop is straight-line
// SIMD code, and every pixel still sums the same terms in the per-pixel kernel's order (same
// bits as the per-pixel kernel, hence as the GPU).
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/normal_weight.h"
#include "kernels_cpu/ieee_guard.h"
#include "kernels_cpu/parallel_for.h"

namespace svgf::cpu {

// GCC vectorizes the tap loops only as functions of their own whose arrays are all restrict
// arguments: inlined into the row, the restrict promise is lost and the loop stays scalar.
#define SVGF_TAP_LOOP __attribute__((noinline))

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
struct RowScratch {
  std::vector<std::vector<float>> plane;
  RowScratch(int planes, int width) : plane(static_cast<size_t>(planes), std::vector<float>(width)) {}
  float* operator[](int k) { return plane[static_cast<size_t>(k)].data(); }
};

}  // namespace svgf::cpu

// The sanitize stage (core/sanitize.h) on the CPU, a span of a row at a time. Per pixel the
// kernel loads eleven to seventeen planes and branches on what it finds; almost every pixel of
// a frame is clean, and a clean pixel is neither written nor counted. So a span is first
// scanned by one vector loop that runs the kernel's own rule, sanitize_pixel (and
// sanitize_radiance for the split of color), on registers and keeps only whether any pixel
// would be repaired; a span that has one runs the per-pixel kernel, which writes and counts
// exactly what it always does. Same planes and tallies as the kernel
// (tests/sanitize_rows_test.cpp).
#include "kernels_cpu/sanitize_rows.h"

#include <algorithm>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include "kernels_cpu/ieee_guard.h"
#include "kernels_cpu/parallel_for.h"
#include "kernels_cpu/row_tools.h"

namespace svgf::cpu {
namespace {

// Pixels a scan covers: a pixel to repair sends this many to the per-pixel kernel.
constexpr int kSpan = 64;

// Whether any pixel of [i0, i1) needs a repair: the kernel's rule with its stores left out.
// The optional planes are template arguments, so every load in the loop is unconditional.
template <bool kEmission, bool kPosition, bool kSplit>
SVGF_TAP_LOOP bool span_needs_repair(const InputPlanes& planes, int i0, int i1) {
  const InputPlanes in = planes;  // a local copy: its plane pointers stay in registers
  unsigned needs = 0u;
  for (int i = i0; i < i1; ++i) {
    InputPixel p;
    p.color = in.color.load(i);
    p.albedo = in.albedo.load(i);
    p.emission = kEmission ? in.emission.load(i) : Vec3();
    p.normal = in.normal.load(i);
    p.position = kPosition ? in.position.load(i) : Vec3();
    p.depth = in.depth[i];
    p.depth_dx = in.depth_dx[i];
    p.depth_dy = in.depth_dy[i];
    p.motion_x = in.motion_x[i];
    p.motion_y = in.motion_y[i];
    uint32_t repairs = sanitize_pixel(p, kEmission, kPosition);
    if (kSplit)  // as the kernel: the split of color follows color's rule
      repairs |= radiance_ok(in.direct.load(i)) & radiance_ok(in.indirect.load(i)) ? 0u
                                                                                   : kRepairColor;
    needs |= repairs;
  }
  return needs != 0u;
}

using SpanScan = bool (*)(const InputPlanes&, int, int);

template <bool kEmission, bool kPosition>
SpanScan scan_for(bool split) {
  return split ? span_needs_repair<kEmission, kPosition, true>
               : span_needs_repair<kEmission, kPosition, false>;
}
SpanScan scan_for(const InputPlanes& in) {
  const bool emission = in.emission.r != nullptr, position = in.position.r != nullptr;
  const bool split = in.direct.r != nullptr;
  if (emission) return position ? scan_for<true, true>(split) : scan_for<true, false>(split);
  return position ? scan_for<false, true>(split) : scan_for<false, false>(split);
}

}  // namespace

Tallies run_sanitize_rows(const SanitizeInputs& kernel, int width, int height) {
  const SpanScan needs_repair = scan_for(kernel.in);
  return tbb::parallel_reduce(
      tbb::blocked_range<int>(0, height, kRowsPerTask), Tallies{},
      [&](const tbb::blocked_range<int>& rows, Tallies t) {
        ScopedIeeeFloat ieee;
        for (int y = rows.begin(); y != rows.end(); ++y)
          for (int x0 = 0; x0 < width; x0 += kSpan) {
            const int x1 = std::min(x0 + kSpan, width);
            if (!needs_repair(kernel.in, y * width + x0, y * width + x1)) continue;
            for (int x = x0; x < x1; ++x) {  // tally_pixels' loop, on this span
              const uint32_t mask = kernel(x, y);
              if (mask != 0u) t.add_mask(mask);
            }
          }
        return t;
      },
      [](Tallies a, const Tallies& b) { return a += b; });
}

}  // namespace svgf::cpu

// SVGF's reprojection on the CPU, a row at a time. The per-pixel kernel branches on every tap
// (inside? consistent?) and stays scalar. Most pixels take its common case: a history read
// through the consistent ones of the four bilinear taps, no statistics anti-lag. A row runs
// that case for every pixel as straight-line vector code, built from the kernel's own pieces
// (methods/svgf/reproject.h: the same operations in the same order), and the per-pixel kernel
// redoes the pixels that took another path (no surface, far motion, the 3x3 fallback, a
// history dropped whole). Same bits as the per-pixel kernel
// (tests/svgf_cpu_reproject_rows_test.cpp).
#include <vector>

#include "kernels_cpu/row_tools.h"
#include "kernels_cpu/svgf_rows.h"

namespace svgf::cpu {
namespace {

// v clamped into 0..last (by value: std::min and std::max take references, which keep GCC 12
// from vectorizing the loop).
inline int clamp_index(int v, int last) { return v < 0 ? 0 : (v > last ? last : v); }

// Pixels 0..w-1 of row y as the common case: outputs written for every pixel, and common[x]
// set where pixel x is one (its outputs are the per-pixel kernel's); elsewhere the outputs are
// meaningless and the caller overwrites them. A tap is loaded clamped into the image (every
// load in bounds) and added where read_history adds it (inside and consistent): a select
// instead of a branch, the same sums.
template <bool kLambda>  // whether gradient_lambda is given
SVGF_TAP_LOOP void reproject_common(const ReprojectKernel& kernel, int y,
                                    int* __restrict common) {
  using History = ReprojectKernel::History;
  const ReprojectKernel k = kernel;  // a local copy: its plane pointers stay in registers
  const int w = k.guides.width;
  const int last_x = k.prev_guides.width - 1, last_y = k.prev_guides.height - 1;
  const float min_weight = k.params.reproject_min_weight;
#pragma GCC ivdep
  for (int x = 0; x < w; ++x) {
    const int i = k.guides.index(x, y);
    float px = 0.f, py = 0.f;
    bool ok = k.previous_position(x, y, i, px, py);
    const BilinearTaps taps = BilinearTaps::at(ok ? px : 0.f, ok ? py : 0.f);
    History h;
    float weight_sum = 0.f;
#pragma GCC unroll 4
    for (int t = 0; t < 4; ++t) {
      const int xt = taps.x(t), yt = taps.y(t);
      const int j = k.prev_guides.index(clamp_index(xt, last_x), clamp_index(yt, last_y));
      History with = h;
      float with_sum = weight_sum;
      k.add_tap(with, with_sum, j, taps.weight(t));
      const bool consistent = k.prev_guides.inside(xt, yt) & k.tap_matches(i, j);
      h.color.x = consistent ? with.color.x : h.color.x;
      h.color.y = consistent ? with.color.y : h.color.y;
      h.color.z = consistent ? with.color.z : h.color.z;
      h.moments.x = consistent ? with.moments.x : h.moments.x;
      h.moments.y = consistent ? with.moments.y : h.moments.y;
      h.length = consistent ? with.length : h.length;
      weight_sum = consistent ? with_sum : weight_sum;
    }
    ok = ok & (weight_sum >= min_weight);  // else read_history's fallback: not common
    h = ReprojectKernel::normalized(h, weight_sum);
    ok = ok & ReprojectKernel::shorten(h, 0.f);  // no statistics anti-lag: nothing dropped
    const float lambda = kLambda ? k.gradient_lambda[k.stratum(x, y)] : 0.f;
    ok = ok & (lambda < 1.f);
    const Vec3 c = k.illumination.load(i);
    k.blend(i, c, luminance(c), h, lambda);
    common[x] = ok;
  }
}

}  // namespace

void run_reproject_rows(const ReprojectKernel& kernel, int width, int height) {
  // No common case: no history (every pixel restarts), or the statistics anti-lag (a 5x5
  // neighbourhood per pixel).
  if (!kernel.has_history || kernel.statistics_antilag()) {
    for_each_pixel(width, height, kernel);
    return;
  }
  parallel_rows(height, [&](int y0, int y1) {
    std::vector<int> common(static_cast<size_t>(width));
    for (int y = y0; y < y1; ++y) {
      if (kernel.gradient_lambda)
        reproject_common<true>(kernel, y, common.data());
      else
        reproject_common<false>(kernel, y, common.data());
      for (int x = 0; x < width; ++x)
        if (!common[x]) kernel(x, y);
    }
  });
}

}  // namespace svgf::cpu

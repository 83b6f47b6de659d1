// SVGF's reprojection on the CPU, a row at a time. The per-pixel kernel branches on every tap
// (inside? consistent?) and stays scalar; most pixels of a moving camera take its common case:
// all four bilinear taps inside and consistent, no statistics anti-lag. A row runs that case
// for every pixel as straight-line vector code, built from the kernel's own pieces
// (methods/svgf/reproject.h: the same operations in the same order), and the per-pixel kernel
// redoes the pixels that took another path. Same bits as the per-pixel kernel
// (tests/svgf_cpu_rows_test.cpp).
#include <algorithm>
#include <vector>

#include "kernels_cpu/row_tools.h"
#include "kernels_cpu/svgf_rows.h"

namespace svgf::cpu {
namespace {

// Pixels 0..w-1 of row y as the common case: outputs written for every pixel, and common[x]
// set where pixel x is one (its outputs are the per-pixel kernel's); elsewhere the outputs are
// meaningless and the caller overwrites them. Taps outside the image are read clamped inside
// (the pixel is not common then), so every load is in bounds.
template <bool kLambda>  // whether gradient_lambda is given
SVGF_TAP_LOOP void reproject_common(const ReprojectKernel& kernel, int y,
                                    int* __restrict common) {
  const ReprojectKernel k = kernel;  // a local copy: its plane pointers stay in registers
  const int w = k.guides.width;
  const int last_x = k.prev_guides.width - 2, last_y = k.prev_guides.height - 2;
  const float min_weight = k.params.reproject_min_weight;
#pragma GCC ivdep
  for (int x = 0; x < w; ++x) {
    const int i = k.guides.index(x, y);
    float px = 0.f, py = 0.f;
    bool ok = k.previous_position(x, y, i, px, py);
    BilinearTaps taps = BilinearTaps::at(ok ? px : 0.f, ok ? py : 0.f);
    const int x0 = std::min(std::max(taps.x0, 0), last_x);
    const int y0 = std::min(std::max(taps.y0, 0), last_y);
    ok = ok & (x0 == taps.x0) & (y0 == taps.y0);
    taps.x0 = x0;
    taps.y0 = y0;
    ReprojectKernel::History h;
    float weight_sum = 0.f;
#pragma GCC unroll 4
    for (int t = 0; t < 4; ++t) {
      const int j = k.prev_guides.index(taps.x(t), taps.y(t));
      ok = ok & k.tap_matches(i, j);
      k.add_tap(h, weight_sum, j, taps.weight(t));
    }
    ok = ok & (weight_sum >= min_weight);
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
  // No common case: no history (every pixel restarts), the statistics anti-lag (a 5x5
  // neighbourhood per pixel), or no 2x2 block of taps in the image.
  if (!kernel.has_history || kernel.statistics_antilag() || width < 2 || height < 2) {
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

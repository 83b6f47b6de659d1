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

// What the vector passes made of a pixel.
enum PixelPath : int {
  kPerPixel = 0,  // to be run by the per-pixel kernel
  kDone = 1,      // its outputs are the per-pixel kernel's
  kFallback = 2,  // a surface whose bilinear taps weigh too little: read_history's 3x3 block
};

// h and weight become with and with_weight where take: a tap added by a select, not a branch.
inline void take_if(bool take, const ReprojectKernel::History& with, float with_weight,
                    ReprojectKernel::History& h, float& weight) {
  h.color.x = take ? with.color.x : h.color.x;
  h.color.y = take ? with.color.y : h.color.y;
  h.color.z = take ? with.color.z : h.color.z;
  h.moments.x = take ? with.moments.x : h.moments.x;
  h.moments.y = take ? with.moments.y : h.moments.y;
  h.length = take ? with.length : h.length;
  weight = take ? with_weight : weight;
}

// Pixels 0..w-1 of row y through the bilinear taps: outputs written for every pixel, path[x]
// kDone where they are the per-pixel kernel's; elsewhere they are meaningless and a later pass
// overwrites them. A tap is loaded clamped into the image (every load in bounds) and added
// where read_history adds it (inside and consistent), the same sums.
template <bool kLambda>  // whether gradient_lambda is given
SVGF_TAP_LOOP void reproject_bilinear(const ReprojectKernel& kernel, int y,
                                      int* __restrict path) {
  using History = ReprojectKernel::History;
  const ReprojectKernel k = kernel;  // a local copy: its plane pointers stay in registers
  const int w = k.guides.width;
  const int last_x = k.prev_guides.width - 1, last_y = k.prev_guides.height - 1;
  const float min_weight = k.params.reproject_min_weight;
#pragma GCC ivdep
  for (int x = 0; x < w; ++x) {
    const int i = k.guides.index(x, y);
    float px = 0.f, py = 0.f;
    const bool moved = k.previous_position(x, y, i, px, py);
    const BilinearTaps taps = BilinearTaps::at(moved ? px : 0.f, moved ? py : 0.f);
    History h;
    float weight_sum = 0.f;
#pragma GCC unroll 4
    for (int t = 0; t < 4; ++t) {
      const int xt = taps.x(t), yt = taps.y(t);
      const int j = k.prev_guides.index(clamp_index(xt, last_x), clamp_index(yt, last_y));
      History with = h;
      float with_sum = weight_sum;
      k.add_tap(with, with_sum, j, taps.weight(t));
      take_if(k.prev_guides.inside(xt, yt) & k.tap_matches(i, j), with, with_sum, h, weight_sum);
    }
    const bool bilinear = weight_sum >= min_weight;
    h = ReprojectKernel::normalized(h, weight_sum);
    bool ok = moved & bilinear;
    ok = ok & ReprojectKernel::shorten(h, 0.f);  // no statistics anti-lag: nothing dropped
    const float lambda = kLambda ? k.gradient_lambda[k.stratum(x, y)] : 0.f;
    ok = ok & (lambda < 1.f);
    const Vec3 c = k.illumination.load(i);
    k.blend(i, c, luminance(c), h, lambda);
    path[x] = ok ? kDone : (moved & !bilinear ? kFallback : kPerPixel);
  }
}

// read_history's fallback for the pixels x = pending[0..n) of row y, one a lane, the same
// way: `compact` is the kernel with its outputs in row scratch, where pixel pending[m] writes
// at m; done[m] says where they are the per-pixel kernel's.
template <bool kLambda>
SVGF_TAP_LOOP void reproject_fallback(const ReprojectKernel& compact, int y,
                                      const int* __restrict pending, int n,
                                      int* __restrict done) {
  using History = ReprojectKernel::History;
  const ReprojectKernel k = compact;
  const int last_x = k.prev_guides.width - 1, last_y = k.prev_guides.height - 1;
#pragma GCC ivdep
  for (int m = 0; m < n; ++m) {
    const int x = pending[m];
    const int i = k.guides.index(x, y);
    float px = 0.f, py = 0.f;
    k.previous_position(x, y, i, px, py);  // true: the first pass found it moved
    const int xn = ReprojectKernel::nearest(px), yn = ReprojectKernel::nearest(py);
    History h;
    float count = 0.f;
#pragma GCC unroll 9
    for (int t = 0; t < 9; ++t) {  // dy outer, dx inner, as read_history
      const int xt = xn + t % 3 - 1, yt = yn + t / 3 - 1;
      const int j = k.prev_guides.index(clamp_index(xt, last_x), clamp_index(yt, last_y));
      History with = h;
      float with_count = count;
      k.add_pixel(with, with_count, j);
      take_if(k.prev_guides.inside(xt, yt) & k.tap_matches(i, j), with, with_count, h, count);
    }
    bool ok = count > 0.f;
    h = ReprojectKernel::normalized(h, count);
    ok = ok & ReprojectKernel::shorten(h, 0.f);
    const float lambda = kLambda ? k.gradient_lambda[k.stratum(x, y)] : 0.f;
    ok = ok & (lambda < 1.f);
    const Vec3 c = k.illumination.load(i);
    k.blend(m, c, luminance(c), h, lambda);
    done[m] = ok;
  }
}

// Row y: the two vector passes, then the per-pixel kernel for what they left.
template <bool kLambda>
void reproject_row(const ReprojectKernel& kernel, const ReprojectKernel& compact, int y,
                   int* path, int* pending, int* done) {
  const int w = kernel.guides.width;
  reproject_bilinear<kLambda>(kernel, y, path);
  int n = 0;
  for (int x = 0; x < w; ++x)
    if (path[x] == kFallback) pending[n++] = x;
  if (n > 0) reproject_fallback<kLambda>(compact, y, pending, n, done);
  for (int m = 0; m < n; ++m) {
    const int x = pending[m], i = kernel.guides.index(x, y);
    if (!done[m]) {
      path[x] = kPerPixel;
      continue;
    }
    kernel.accumulated.color.store(i, compact.accumulated.color.load(m));
    kernel.accumulated.variance[i] = compact.accumulated.variance[m];
    kernel.moment1[i] = compact.moment1[m];
    kernel.moment2[i] = compact.moment2[m];
    kernel.history[i] = compact.history[m];
  }
  for (int x = 0; x < w; ++x)
    if (path[x] == kPerPixel) kernel(x, y);
}

}  // namespace

void run_reproject_rows(const ReprojectKernel& kernel, int width, int height) {
  // No vector pass: no history (every pixel restarts), or the statistics anti-lag (a 5x5
  // neighbourhood per pixel).
  if (!kernel.has_history || kernel.statistics_antilag()) {
    for_each_pixel(width, height, kernel);
    return;
  }
  parallel_rows(height, [&](int y0, int y1) {
    std::vector<int> path(static_cast<size_t>(width)), pending(path.size()), done(path.size());
    RowScratch out(7, width);
    ReprojectKernel compact = kernel;
    compact.accumulated = {RgbView(out[0], out[1], out[2]), out[3]};
    compact.moment1 = out[4];
    compact.moment2 = out[5];
    compact.history = out[6];
    for (int y = y0; y < y1; ++y) {
      if (kernel.gradient_lambda)
        reproject_row<true>(kernel, compact, y, path.data(), pending.data(), done.data());
      else
        reproject_row<false>(kernel, compact, y, path.data(), pending.data(), done.data());
    }
  });
}

}  // namespace svgf::cpu

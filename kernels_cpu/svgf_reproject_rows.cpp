// SVGF's reprojection on the CPU, a row at a time. The per-pixel kernel branches on every tap
// (inside? consistent?) and stays scalar. A row runs its two history reads as vector loops,
// built from the kernel's own pieces (methods/svgf/reproject.h: the same operations in the
// same order): every pixel through its bilinear taps, then the pixels whose taps weigh too
// little through the 3x3 fallback. The per-pixel kernel runs the stage under the statistics
// anti-lag and without history. Same bits as the per-pixel kernel
// (tests/svgf_cpu_reproject_rows_test.cpp).
#include <vector>

#include "kernels_cpu/row_tools.h"
#include "kernels_cpu/svgf_rows.h"

namespace svgf::cpu {
namespace {

// v clamped into 0..last (by value: std::min and std::max take references, which keep GCC 12
// from vectorizing the loop).
inline int clamp_index(int v, int last) { return v < 0 ? 0 : (v > last ? last : v); }

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

// The end of the per-pixel kernel for a history read h (valid) that counts where `read`:
// the anti-lags (no statistics anti-lag here: it drops nothing), then the blend of pixel i,
// whose outputs `k` stores at `at`.
template <bool kLambda>  // whether gradient_lambda is given
inline void blend_read(const ReprojectKernel& k, int x, int y, int i, int at, bool read,
                       ReprojectKernel::History h) {
  const Vec3 c = k.illumination.load(i);
  const float lambda = kLambda ? k.gradient_lambda[k.stratum(x, y)] : 0.f;
  const bool kept = read & ReprojectKernel::history_kept(h, 0.f, lambda);
  k.blend(at, c, luminance(c), ReprojectKernel::none_unless(kept, h), kept ? lambda : 0.f);
}

// Pixels 0..w-1 of row y through their bilinear taps, as read_history reads them: outputs
// written for every pixel, and fallback[x] set where pixel x needs read_history's 3x3 block
// instead (its outputs are meaningless then; the next pass overwrites them). A tap is loaded
// clamped into the image (every load in bounds) and added where read_history adds it (inside
// and consistent), the same sums.
template <bool kLambda>
SVGF_TAP_LOOP void reproject_bilinear(const ReprojectKernel& kernel, int y,
                                      int* __restrict fallback) {
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
    const ReprojectKernel::TapTest test = k.tap_test(x, y, i);
    History h;
    float weight_sum = 0.f;
#pragma GCC unroll 4
    for (int t = 0; t < 4; ++t) {
      const int xt = taps.x(t), yt = taps.y(t);
      const int j = k.prev_guides.index(clamp_index(xt, last_x), clamp_index(yt, last_y));
      History with = h;
      float with_sum = weight_sum;
      k.add_tap(with, with_sum, j, taps.weight(t));
      take_if(k.prev_guides.inside(xt, yt) & k.tap_matches(test, j), with, with_sum, h, weight_sum);
    }
    const bool bilinear = weight_sum >= min_weight;
    blend_read<kLambda>(k, x, y, i, i, moved & bilinear,
                        ReprojectKernel::normalized(h, weight_sum));
    fallback[x] = moved & !bilinear;
  }
}

// read_history's fallback for the pixels x = pending[0..n) of row y, one a lane, the same
// way: `compact` is the kernel with its outputs in row scratch, where pixel pending[m] writes
// at m.
template <bool kLambda>
SVGF_TAP_LOOP void reproject_fallback(const ReprojectKernel& compact, int y,
                                      const int* __restrict pending, int n) {
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
    const ReprojectKernel::TapTest test = k.tap_test(x, y, i);
    History h;
    float count = 0.f;
#pragma GCC unroll 9
    for (int t = 0; t < 9; ++t) {  // dy outer, dx inner, as read_history
      const int xt = xn + t % 3 - 1, yt = yn + t / 3 - 1;
      const int j = k.prev_guides.index(clamp_index(xt, last_x), clamp_index(yt, last_y));
      History with = h;
      float with_count = count;
      k.add_pixel(with, with_count, j);
      take_if(k.prev_guides.inside(xt, yt) & k.tap_matches(test, j), with, with_count, h,
              count);
    }
    blend_read<kLambda>(k, x, y, i, m, count > 0.f, ReprojectKernel::normalized(h, count));
  }
}

// Row y: every pixel through its bilinear taps, then those that need it through the 3x3
// fallback, their outputs copied into place.
template <bool kLambda>
void reproject_row(const ReprojectKernel& kernel, const ReprojectKernel& compact, int y,
                   int* fallback, int* pending) {
  const int w = kernel.guides.width;
  reproject_bilinear<kLambda>(kernel, y, fallback);
  int n = 0;
  for (int x = 0; x < w; ++x)
    if (fallback[x]) pending[n++] = x;
  if (n == 0) return;
  reproject_fallback<kLambda>(compact, y, pending, n);
  for (int m = 0; m < n; ++m) {
    const int i = kernel.guides.index(pending[m], y);
    kernel.accumulated.color.store(i, compact.accumulated.color.load(m));
    kernel.accumulated.variance[i] = compact.accumulated.variance[m];
    kernel.moment1[i] = compact.moment1[m];
    kernel.moment2[i] = compact.moment2[m];
    kernel.history[i] = compact.history[m];
  }
}

}  // namespace

void run_reproject_rows(const ReprojectKernel& kernel, int width, int height) {
  // The per-pixel kernel: no history (every pixel restarts), or the statistics anti-lag (a
  // 5x5 neighbourhood per pixel).
  if (!kernel.has_history || kernel.statistics_antilag()) {
    for_each_pixel(width, height, kernel);
    return;
  }
  parallel_rows(height, [&](int y0, int y1) {
    std::vector<int> fallback(static_cast<size_t>(width)), pending(fallback.size());
    RowScratch out(7, width);
    ReprojectKernel compact = kernel;
    compact.accumulated = {RgbView(out[0], out[1], out[2]), out[3]};
    compact.moment1 = out[4];
    compact.moment2 = out[5];
    compact.history = out[6];
    for (int y = y0; y < y1; ++y) {
      if (kernel.gradient_lambda)
        reproject_row<true>(kernel, compact, y, fallback.data(), pending.data());
      else
        reproject_row<false>(kernel, compact, y, fallback.data(), pending.data());
    }
  });
}

}  // namespace svgf::cpu

// SVGF's reprojection on the CPU, a row at a time. The per-pixel kernel branches on every tap
// (inside? consistent?) and stays scalar. A row runs its two history reads as vector loops,
// built from the kernel's own pieces (methods/svgf/reproject.h: the same operations in the
// same order): every pixel through its bilinear taps, then the pixels whose taps weigh too
// little through the 3x3 fallback. A camera's motion field is smooth, so the taps of 16
// neighbouring pixels mostly lie at one of a few shifts from them (up to 3 columns and 2 rows
// apart): such a chunk reads its taps by contiguous loads and selects (same values), the
// others through gathers. The per-pixel kernel runs the stage under the statistics anti-lag
// and without history. Same bits as the per-pixel kernel
// (tests/svgf_cpu_reproject_rows_test.cpp).
#include <algorithm>
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
// the anti-lags (no statistics anti-lag here: it drops nothing; `lambda`, the pixel's
// stratum's, from the row's lambdas), then the blend of pixel i, whose outputs `k` stores at
// `at`.
inline void blend_read(const ReprojectKernel& k, int i, int at, bool read, float lambda,
                       ReprojectKernel::History h) {
  const Vec3 c = k.illumination.load(i);
  const bool kept = read & ReprojectKernel::history_kept(h, 0.f, lambda);
  k.blend(at, c, luminance(c), ReprojectKernel::none_unless(kept, h), kept ? lambda : 0.f);
}

// Pixels x0..x1-1 of row y through their bilinear taps, as read_history reads them: outputs
// written for every pixel, and fallback[x] set where pixel x needs read_history's 3x3 block
// instead (its outputs are meaningless then; the next pass overwrites them), unless the block
// lies outside the previous frame (reads[x] 0: the output written here, without history, is
// what the block would give). A tap is loaded clamped into the image (every load in bounds)
// and added where read_history adds it (inside and consistent), the same sums.
SVGF_TAP_LOOP void reproject_bilinear(const ReprojectKernel& kernel, int y, int x0, int x1,
                                      const float* __restrict lambda,
                                      const int* __restrict reads, int* __restrict fallback) {
  using History = ReprojectKernel::History;
  const ReprojectKernel k = kernel;  // a local copy: its plane pointers stay in registers
  const int last_x = k.prev_guides.width - 1, last_y = k.prev_guides.height - 1;
  const float min_weight = k.params.reproject_min_weight;
#pragma GCC ivdep
  for (int x = x0; x < x1; ++x) {
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
    blend_read(k, i, i, moved & bilinear, lambda[x], ReprojectKernel::normalized(h, weight_sum));
    fallback[x] = reads[x] & !bilinear;  // reads[x]: moved, and the block in the frame
  }
}

// The pixels of a chunk: their taps' shifts are tested together, and a chunk is one vector
// iteration (or two, or four) on every instruction set.
constexpr int kChunk = 16;

// Member-wise selects (a vector blend each): a where c, else b.
inline ReprojectKernel::TapGuides pick(bool c, const ReprojectKernel::TapGuides& a,
                                       const ReprojectKernel::TapGuides& b) {
  return {c ? a.mesh : b.mesh, c ? a.depth : b.depth,
          make_vec3(c ? a.normal.x : b.normal.x, c ? a.normal.y : b.normal.y,
                    c ? a.normal.z : b.normal.z)};
}
inline ReprojectKernel::History pick(bool c, const ReprojectKernel::History& a,
                                     const ReprojectKernel::History& b) {
  ReprojectKernel::History h;
  h.color = make_vec3(c ? a.color.x : b.color.x, c ? a.color.y : b.color.y,
                      c ? a.color.z : b.color.z);
  h.moments = make_vec2(c ? a.moments.x : b.moments.x, c ? a.moments.y : b.moments.y);
  h.length = c ? a.length : b.length;
  h.valid = true;
  return h;
}

// What read(j) gives at index j shifted right by sx (0 to kSpreadX) and down by sy (0, or 0 to
// 1 with kShiftY) in a frame pw wide: loads at indices contiguous along the chunk, and selects.
template <int kSpreadX, bool kShiftY, class Read>
inline auto read_shifted(const Read& read, int j, int sx, bool sy, int pw) {
  const auto along_row = [&](int r) {
    auto v = read(r);
    if (kSpreadX >= 1) v = pick(sx >= 1, read(r + 1), v);
    if (kSpreadX >= 2) v = pick(sx >= 2, read(r + 2), v);
    return v;
  };
  return kShiftY ? pick(sy, along_row(j + pw), along_row(j)) : along_row(j);
}

// Where the taps of the chunk of pixels x0.. lie: pixel x's top-left tap is (x + dx, y + dy)
// with dx from dx_min to dx_min + its kind's spread in x (0 to 2), dy from dy_min to dy_min +
// its spread in y (0 or 1), and all of the window's shifts inside the previous frame (whether
// a pixel uses them or not, every load below is in bounds).
struct ChunkWindow {
  int x0, dx_min, dy_min;
};

// A hint: the lines of every plane the window pass reads and writes for the chunk whose pixels
// start at index i (its window's top-left at j in the previous frame), into L2, so that they
// are there when that chunk runs. About 40 planes stream at once, more than the hardware
// prefetchers follow. It changes no value. Always inlined: a function of prefetches alone is
// "pure" to GCC (a prefetch has no effect it models), so its calls were deleted as dead code,
// and from 2026-11-29 to 2026-12-04 no prefetch was in any build (objdump showed none).
__attribute__((always_inline)) inline void prefetch_chunk(const ReprojectKernel& k, int i,
                                                          int j) {
  const float* const read_now[] = {
      k.guides.depth,    k.guides.depth_dx, k.guides.depth_dy,
      k.guides.normal.r, k.guides.normal.g, k.guides.normal.b,
      k.guides.motion_x, k.guides.motion_y, reinterpret_cast<const float*>(k.guides.mesh_id),
      k.illumination.r,  k.illumination.g,  k.illumination.b};
  for (const float* p : read_now) __builtin_prefetch(p + i, 0, 2);
  const float* const read_then[] = {
      k.prev_guides.depth, k.prev_guides.normal.r, k.prev_guides.normal.g,
      k.prev_guides.normal.b, reinterpret_cast<const float*>(k.prev_guides.mesh_id),
      k.prev_color.r, k.prev_color.g, k.prev_color.b, k.prev_moment1, k.prev_moment2,
      k.prev_history};
  for (const float* p : read_then) {
    __builtin_prefetch(p + j, 0, 2);
    __builtin_prefetch(p + j + k.prev_guides.width, 0, 2);
  }
  float* const written[] = {k.accumulated.color.r, k.accumulated.color.g, k.accumulated.color.b,
                            k.accumulated.variance, k.moment1, k.moment2, k.history};
  for (float* p : written) __builtin_prefetch(p + i, 1, 2);
}

// The chunks of row y whose taps lie in windows[0..n) through their bilinear taps as
// reproject_bilinear reads them: each tap read at its shift of the window's top-left by
// read_shifted, the same values, sums and outputs. kSpreadX and kShiftY: the windows' shifts
// (a chunk without them needs no selects). One call a row and kind of window: the setup is
// paid once, not per chunk.
template <int kSpreadX, bool kShiftY>
SVGF_TAP_LOOP void reproject_bilinear_windows(const ReprojectKernel& kernel, int y,
                                              const ChunkWindow* __restrict windows, int n,
                                              const float* __restrict lambda,
                                              int* __restrict fallback) {
  using History = ReprojectKernel::History;
  const ReprojectKernel k = kernel;
  const int pw = k.prev_guides.width;
  const float min_weight = k.params.reproject_min_weight;
  const auto guides_at = [&k](int j) { return k.tap_guides(j); };
  const auto history_at = [&k](int j) { return k.tap_history(j); };
  for (int c = 0; c < n; ++c) {
    const ChunkWindow window = windows[c];
    const int x0 = window.x0;
    // The window's top-left for pixel x0; pixel x's is `corner + x - x0`.
    const int corner = k.prev_guides.index(x0 + window.dx_min, y + window.dy_min);
    // The same chunk two rows below (a smooth motion field: its window as far below), into
    // L2. Camera-pan 720p, Zen 5 VM, reproject / atrous, medians of alternating runs: 0.227
    // with this row's chunk four ahead into L1, 0.219 one row below, 0.203 two rows below
    // (0.206 and 0.208 three and four; 0.205 with this row's four ahead as well). In the
    // last two rows the addresses lie past the planes: a prefetch does not fault.
    prefetch_chunk(k, k.guides.index(x0, y + 2), corner + 2 * pw);
#pragma GCC ivdep
    for (int l = 0; l < kChunk; ++l) {
      const int x = x0 + l;
      const int i = k.guides.index(x, y);
      float px = 0.f, py = 0.f;
      k.previous_position(x, y, i, px, py);  // true: the window holds its taps
      const BilinearTaps taps = BilinearTaps::at(px, py);
      const int sx = kSpreadX > 0 ? taps.x0 - (x + window.dx_min) : 0;
      const bool sy = kShiftY && taps.y0 != y + window.dy_min;
      const ReprojectKernel::TapTest test = k.tap_test(x, y, i);
      History h;
      float weight_sum = 0.f;
#pragma GCC unroll 4
      for (int t = 0; t < 4; ++t) {
        const int j = corner + l + (t & 1) + (t >> 1) * pw;
        History with = h;
        float with_sum = weight_sum;
        const History tap = read_shifted<kSpreadX, kShiftY>(history_at, j, sx, sy, pw);
        ReprojectKernel::add_tap(with, with_sum, tap, taps.weight(t));
        const ReprojectKernel::TapGuides guides =
            read_shifted<kSpreadX, kShiftY>(guides_at, j, sx, sy, pw);
        take_if(k.tap_matches(test, guides), with, with_sum, h, weight_sum);
      }
      const bool bilinear = weight_sum >= min_weight;
      blend_read(k, i, i, bilinear, lambda[x], ReprojectKernel::normalized(h, weight_sum));
      fallback[x] = !bilinear;
    }
  }
}

// Each pixel's top-left tap as a shift (dx[x], dy[x]) from it, for the pixels of row y;
// moved[x] where it has history to read (previous_position); reads[x] where it may find some:
// moved, and its bilinear taps or its 3x3 fallback block reach into the previous frame. A pixel
// that moved but reads nothing (the edge a camera pan uncovers) ends without history, as one
// that did not move: no tap or block pixel is consistent, and where reproject_min_weight is 0
// the empty bilinear read's length is 0 / 0, which history_kept drops.
SVGF_TAP_LOOP void tap_shifts(const ReprojectKernel& kernel, int y, int* __restrict dx,
                              int* __restrict dy, int* __restrict moved, int* __restrict reads) {
  const ReprojectKernel k = kernel;
  const int w = k.guides.width;
  const int last_x = k.prev_guides.width - 1, last_y = k.prev_guides.height - 1;
  for (int x = 0; x < w; ++x) {
    float px = 0.f, py = 0.f;
    moved[x] = k.previous_position(x, y, k.guides.index(x, y), px, py);
    const float mx = moved[x] ? px : 0.f, my = moved[x] ? py : 0.f;
    const BilinearTaps taps = BilinearTaps::at(mx, my);
    dx[x] = taps.x0 - x;
    dy[x] = taps.y0 - y;
    // The box of the 2x2 taps and of the 3x3 block around the nearest pixel.
    const int xn = ReprojectKernel::nearest(mx), yn = ReprojectKernel::nearest(my);
    const int left = xn - 1 < taps.x0 ? xn - 1 : taps.x0;
    const int right = xn + 1 > taps.x0 + 1 ? xn + 1 : taps.x0 + 1;
    const int top = yn - 1 < taps.y0 ? yn - 1 : taps.y0;
    const int bottom = yn + 1 > taps.y0 + 1 ? yn + 1 : taps.y0 + 1;
    const bool reaches = (right >= 0) & (left <= last_x) & (bottom >= 0) & (top <= last_y);
    reads[x] = moved[x] & reaches;
  }
}

// Pixels x0..x1 of row y, none of which reads history (tap_shifts): the blend of a pixel
// without history, which the bilinear pass and the fallback end in for them. At the edge a
// camera pan uncovers, whole chunks are such pixels; through the gathers and the fallback's
// nine they cost many times a window's chunk.
SVGF_TAP_LOOP void reproject_without_history(const ReprojectKernel& kernel, int y, int x0,
                                             int x1, const float* __restrict lambda,
                                             int* __restrict fallback) {
  const ReprojectKernel k = kernel;
  for (int x = x0; x < x1; ++x) {
    const int i = k.guides.index(x, y);
    blend_read(k, i, i, false, lambda[x], ReprojectKernel::History{});
    fallback[x] = 0;
  }
}

// Whether any pixel of the chunk x0.. reads history.
inline bool chunk_reads(const int* reads, int x0) {
  int any = 0;
  for (int x = x0; x < x0 + kChunk; ++x) any |= reads[x];
  return any != 0;
}

// The kinds of window: the spread in x (0 to 2), plus 3 with a shift in y.
constexpr int kWindowKinds = 6;

// Whether the chunk of pixels x0.. of row y all moved and have their taps in one window inside
// the previous frame: its kind, and the window; -1 where not.
int chunk_window(const ReprojectKernel& k, int y, int x0, const int* dx, const int* dy,
                 const int* moved, ChunkWindow& window) {
  int all_moved = 1, dx_min = dx[x0], dx_max = dx[x0], dy_min = dy[x0], dy_max = dy[x0];
  for (int x = x0; x < x0 + kChunk; ++x) {
    all_moved &= moved[x];
    dx_min = dx[x] < dx_min ? dx[x] : dx_min;
    dx_max = dx[x] > dx_max ? dx[x] : dx_max;
    dy_min = dy[x] < dy_min ? dy[x] : dy_min;
    dy_max = dy[x] > dy_max ? dy[x] : dy_max;
  }
  window = {x0, dx_min, dy_min};
  // The window's columns x0 + dx_min .. x0 + kChunk + dx_max, rows y + dy_min .. y + dy_max + 1.
  const bool inside = all_moved && dx_max - dx_min <= 2 && dy_max - dy_min <= 1 &&
                      x0 + dx_min >= 0 && x0 + kChunk + dx_max < k.prev_guides.width &&
                      y + dy_min >= 0 && y + dy_max + 1 < k.prev_guides.height;
  return inside ? (dx_max - dx_min) + 3 * (dy_max - dy_min) : -1;
}

// A row's scratch.
struct RowInts {
  std::vector<int> dx, dy, moved, reads, fallback, pending;
  std::vector<float> lambda;  // each pixel's stratum's lambda (0 without the gradient stages)
  std::vector<ChunkWindow> windows;  // kWindowKinds lists, each room for every chunk
  explicit RowInts(int width)
      : dx(static_cast<size_t>(width)), dy(dx.size()), moved(dx.size()), reads(dx.size()),
        fallback(dx.size()),
        pending(dx.size()), lambda(dx.size()),
        windows(kWindowKinds * (dx.size() / kChunk + 1)) {}
};

// Each pixel's lambda of row y, as the per-pixel kernel reads it (gradient_lambda[stratum]),
// once a row: a stratum's value three times, so that the vector passes load it contiguously
// (a gather of one value a stratum was about 80 instructions of a 16-pixel chunk's ~450).
void row_lambdas(const ReprojectKernel& k, int y, float* __restrict lambda) {
  const int w = k.guides.width;
  if (!k.gradient_lambda) {
    std::fill(lambda, lambda + w, 0.f);
    return;
  }
  for (int x = 0; x < w; ++x) lambda[x] = k.gradient_lambda[k.stratum(x, y)];
}

// Row y's bilinear pass: the chunks whose taps lie in one window through
// reproject_bilinear_windows (a call for each kind), the chunks without a pixel that reads
// history through reproject_without_history, the pixels between them through
// reproject_bilinear's gathers.
void reproject_bilinear_row(const ReprojectKernel& kernel, int y, RowInts& ints) {
  const int w = kernel.guides.width;
  int* fallback = ints.fallback.data();
  const float* lambda = ints.lambda.data();
  tap_shifts(kernel, y, ints.dx.data(), ints.dy.data(), ints.moved.data(), ints.reads.data());
  const int room = w / kChunk + 1;
  int count[kWindowKinds] = {};
  int gather_from = 0;  // the first pixel not read yet, nor in a window
  // The gathers' pixels two rows below, as the windows prefetch theirs (the previous frame's
  // lines at the pixels themselves: their taps spread, but not far). Camera-pan 720p, Zen 5
  // VM, reproject / atrous, medians of five alternating runs: 0.208 -> 0.196.
  const auto gather = [&](int x0, int x1) {
    for (int x = x0; x < x1; x += kChunk)
      prefetch_chunk(kernel, kernel.guides.index(x, y + 2), kernel.prev_guides.index(x, y + 2));
    reproject_bilinear(kernel, y, x0, x1, lambda, ints.reads.data(), fallback);
  };
  for (int x0 = 0; x0 + kChunk <= w; x0 += kChunk) {
    ChunkWindow window;
    const int kind =
        chunk_window(kernel, y, x0, ints.dx.data(), ints.dy.data(), ints.moved.data(), window);
    if (kind < 0 && chunk_reads(ints.reads.data(), x0)) continue;
    if (gather_from < x0) gather(gather_from, x0);
    if (kind < 0)
      reproject_without_history(kernel, y, x0, x0 + kChunk, lambda, fallback);
    else
      ints.windows[kind * room + count[kind]++] = window;
    gather_from = x0 + kChunk;
  }
  if (gather_from < w) gather(gather_from, w);
  const ChunkWindow* windows = ints.windows.data();
  reproject_bilinear_windows<0, false>(kernel, y, windows, count[0], lambda, fallback);
  reproject_bilinear_windows<1, false>(kernel, y, windows + room, count[1], lambda, fallback);
  reproject_bilinear_windows<2, false>(kernel, y, windows + 2 * room, count[2], lambda,
                                       fallback);
  reproject_bilinear_windows<0, true>(kernel, y, windows + 3 * room, count[3], lambda,
                                      fallback);
  reproject_bilinear_windows<1, true>(kernel, y, windows + 4 * room, count[4], lambda,
                                      fallback);
  reproject_bilinear_windows<2, true>(kernel, y, windows + 5 * room, count[5], lambda,
                                      fallback);
}

// read_history's fallback for the pixels x = pending[0..n) of row y, one a lane, the same
// way: `compact` is the kernel with its outputs in row scratch, where pixel pending[m] writes
// at m.
SVGF_TAP_LOOP void reproject_fallback(const ReprojectKernel& compact, int y,
                                      const int* __restrict pending, int n,
                                      const float* __restrict lambda) {
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
    blend_read(k, i, m, count > 0.f, lambda[x], ReprojectKernel::normalized(h, count));
  }
}

// Row y: every pixel through its bilinear taps, then those that need it through the 3x3
// fallback, their outputs copied into place.
void reproject_row(const ReprojectKernel& kernel, const ReprojectKernel& compact, int y,
                   RowInts& ints) {
  const int w = kernel.guides.width;
  int* fallback = ints.fallback.data();
  int* pending = ints.pending.data();
  row_lambdas(kernel, y, ints.lambda.data());
  reproject_bilinear_row(kernel, y, ints);
  int n = 0;
  for (int x = 0; x < w; ++x)
    if (fallback[x]) pending[n++] = x;
  if (n == 0) return;
  reproject_fallback(compact, y, pending, n, ints.lambda.data());
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
    RowInts ints(width);
    RowScratch out(7, width);
    ReprojectKernel compact = kernel;
    compact.accumulated = {RgbView(out[0], out[1], out[2]), out[3]};
    compact.moment1 = out[4];
    compact.moment2 = out[5];
    compact.history = out[6];
    for (int y = y0; y < y1; ++y) reproject_row(kernel, compact, y, ints);
  });
}

}  // namespace svgf::cpu

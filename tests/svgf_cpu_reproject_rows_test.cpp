// The reprojection's CPU row driver (kernels_cpu/svgf_reproject_rows.cpp) must give the
// per-pixel kernel's bits exactly (the per-pixel kernel is what the GPU runs), on every
// instruction-set variant this CPU runs: common pixels, disocclusions, taps off the image's
// edges, NaN and far motion, the fallback's 3x3 block (found or not), every anti-lag, A-SVGF's
// lambda.
#include <algorithm>
#include <array>
#include <limits>
#include <random>

#include <catch2/catch.hpp>

#include "io/sequence.h"
#include "cpu_variant_support.h"
#include "kernels_cpu/parallel_for.h"
#include "methods/svgf/reproject.h"
#include "test_support.h"

using namespace svgf;

namespace {

using svgf::test::kNaN;

// A frame's history as the previous frame left it, and the planes the stage writes.
struct History {
  Image color, moments, length;
  History(int w, int h, uint32_t seed) : color(w, h, 3), moments(w, h, 2), length(w, h, 1) {
    test::fill_uniform(color, 0.f, 2.f, seed);
    test::fill_uniform(moments, 0.f, 1.f, seed + 1);
    test::fill_uniform(length, 1.f, 40.f, seed + 2);
    for (float& v : length.data()) v = std::floor(v);
    for (size_t i = 7; i < length.data().size(); i += 13) length.data()[i] = 0.f;  // none left
  }
};

// The stage's kernel on the guides of `frame` and `prev`, writing into `out` (7 planes:
// accumulated color and variance, moment 1 and 2, history length).
ReprojectKernel kernel_for(const Frame& frame, const Frame& prev, const History& hist, Image& out) {
  ReprojectKernel k;
  k.guides = frame.guides();
  k.prev_guides = prev.guides();
  k.illumination = frame.color.rgb();
  k.color = frame.color.rgb();
  k.albedo = frame.albedo.rgb();
  k.prev_color = hist.color.rgb();
  k.prev_moment1 = hist.moments.plane(0);
  k.prev_moment2 = hist.moments.plane(1);
  k.prev_history = hist.length.plane(0);
  k.has_history = true;
  k.accumulated = {out.rgb(), out.plane(3)};
  k.moment1 = out.plane(4);
  k.moment2 = out.plane(5);
  k.history = out.plane(6);
  return k;
}

// The per-pixel kernel against every variant's row driver, on `k` as given.
void require_rows_equal_pixels(ReprojectKernel k, const std::string& what) {
  const int w = k.guides.width, h = k.guides.height;
  Image expected(w, h, 7, -1.f);
  k.accumulated = {expected.rgb(), expected.plane(3)};
  k.moment1 = expected.plane(4);
  k.moment2 = expected.plane(5);
  k.history = expected.plane(6);
  cpu::for_each_pixel(w, h, k);
  test::for_each_runnable_variant([&](const cpu::CpuVariant& v) {
    Image got(w, h, 7, -2.f);
    k.accumulated = {got.rgb(), got.plane(3)};
    k.moment1 = got.plane(4);
    k.moment2 = got.plane(5);
    k.history = got.plane(6);
    v.reproject_rows(k, w, h);
    test::require_identical(got, expected, what + " on " + v.name);
  });
}

// How the per-pixel kernel reads the pixels' history, by its own tests: through all four
// bilinear taps, through some of them, through the 3x3 fallback (found or not). The row driver
// has a vector pass for each; the inputs must exercise them all.
struct HistoryPaths {
  double all_taps = 0, some_taps = 0, fallback = 0;
};
HistoryPaths history_paths(const ReprojectKernel& k) {
  int all = 0, some = 0, fallback = 0;
  for (int y = 0; y < k.guides.height; ++y)
    for (int x = 0; x < k.guides.width; ++x) {
      const int i = k.guides.index(x, y);
      float px = 0.f, py = 0.f;
      if (!k.previous_position(x, y, i, px, py)) continue;
      const BilinearTaps taps = BilinearTaps::at(px, py);
      int consistent = 0;
      float weight = 0.f;
      for (int t = 0; t < 4; ++t)
        if (k.tap_consistent(k.tap_test(x, y, i), taps.x(t), taps.y(t))) {
          ++consistent;
          weight += taps.weight(t);
        }
      const bool bilinear = weight >= k.params.reproject_min_weight;
      all += consistent == 4 ? 1 : 0;
      some += consistent < 4 && bilinear ? 1 : 0;
      fallback += bilinear ? 0 : 1;
    }
  const double n = double(k.guides.width) * k.guides.height;
  return {all / n, some / n, fallback / n};
}

// A frame with random guides in patches, and a previous frame that mostly matches it: subpixel
// motion, with some pixels disoccluded (another mesh, depth or normal before), others moved off
// the image, far away or by NaN, and background holes.
std::pair<Frame, Frame> random_pair(int w, int h, uint32_t seed) {
  Frame f = test::flat_frame(w, h), prev = test::flat_frame(w, h);
  test::fill_uniform(f.color, 0.f, 3.f, seed);
  test::fill_uniform(f.depth_gradient, -0.05f, 0.05f, seed + 1);
  std::mt19937 rng(seed + 2);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  for (int i = 0; i < w * h; ++i) {
    const int x = i % w, y = i / w;
    const bool near = (x / 6 + y / 5) % 3 == 0;  // two surfaces in patches of a few pixels
    const bool hole = u(rng) < 0.02f;
    f.depth.plane(0)[i] = hole ? 0.f : (near ? 2.f + u(rng) * 0.01f : 5.f);
    f.mesh_id[i] = near ? 1u : 2u;
    const float tilt = 0.3f + u(rng) * 0.1f, n = std::sqrt(1.f + tilt * tilt);
    f.normal.plane(0)[i] = tilt / n;
    f.normal.plane(2)[i] = 1.f / n;
    f.motion.plane(0)[i] = u(rng) * 3.f - 1.5f;
    f.motion.plane(1)[i] = u(rng) * 3.f - 1.5f;
    const float odd = u(rng);
    if (odd < 0.02f) f.motion.plane(0)[i] = kNaN;
    else if (odd < 0.04f) f.motion.plane(1)[i] = 3e7f;
    else if (odd < 0.06f) f.motion.plane(0)[i] = -float(w) - 3.f;
  }
  // The previous frame: the same guides, a few changed (a disocclusion at those taps).
  for (int i = 0; i < w * h; ++i) {
    prev.depth.plane(0)[i] = f.depth.plane(0)[i] * (1.f + (u(rng) - 0.5f) * 0.01f);
    prev.mesh_id[i] = f.mesh_id[i];
    for (int c = 0; c < 3; ++c) prev.normal.plane(c)[i] = f.normal.plane(c)[i];
    const float change = u(rng);
    if (change < 0.04f) prev.mesh_id[i] = 7u;
    else if (change < 0.08f) prev.depth.plane(0)[i] = 9.f;
    else if (change < 0.12f) prev.normal.plane(0)[i] = -prev.normal.plane(0)[i] - 0.5f;
  }
  return {std::move(f), std::move(prev)};
}

// How the row driver can read the taps of 16-pixel chunks (row-aligned, as it cuts them): by a
// window's shifts (kind: the taps' spread in x, 0 to 2, plus 3 where they spread a row in y,
// kernels_cpu/svgf_reproject_rows.cpp) or, where a pixel has no history, a tap lies outside or
// the taps spread further, through gathers (kind 6). The share of chunks of each kind.
std::array<double, 7> chunk_kinds(const ReprojectKernel& k) {
  std::array<double, 7> share{};
  int chunks = 0;
  const int w = k.guides.width, h = k.guides.height;
  for (int y = 0; y < h; ++y)
    for (int x0 = 0; x0 + 16 <= w; x0 += 16, ++chunks) {
      int dx_min = 1 << 30, dx_max = -dx_min, dy_min = dx_min, dy_max = -dx_min;
      bool gather = false;
      for (int x = x0; x < x0 + 16; ++x) {
        float px = 0.f, py = 0.f;
        const bool moved = k.previous_position(x, y, k.guides.index(x, y), px, py);
        gather |= !moved;
        // Not moved: px, py may be NaN or far out, which no float-to-int conversion may see.
        const BilinearTaps taps = BilinearTaps::at(moved ? px : 0.f, moved ? py : 0.f);
        gather |= !k.prev_guides.inside(taps.x0, taps.y0) ||
                  !k.prev_guides.inside(taps.x0 + 1, taps.y0 + 1);
        dx_min = std::min(dx_min, taps.x0 - x);
        dx_max = std::max(dx_max, taps.x0 - x);
        dy_min = std::min(dy_min, taps.y0 - y);
        dy_max = std::max(dy_max, taps.y0 - y);
      }
      gather |= dx_max - dx_min > 2 || dy_max - dy_min > 1;
      share[gather ? 6 : (dx_max - dx_min) + 3 * (dy_max - dy_min)] += 1;
    }
  for (double& s : share) s /= chunks;
  return share;
}

}  // namespace

TEST_CASE("cpu rows: reprojection rows equal the per-pixel kernel bitwise", "[cpu_rows]") {
  const int sizes[][2] = {{257, 41}, {16, 16}, {2, 2}, {1, 7}, {9, 1}, {31, 9}};
  uint32_t seed = 200;
  for (const auto& size : sizes) {
    const int w = size[0], h = size[1];
    const auto [f, prev] = random_pair(w, h, ++seed);
    const History hist(w, h, ++seed);
    Image out(w, h, 7), lambda(strata_along(w), strata_along(h), 1);
    test::fill_uniform(lambda, -0.2f, 1.2f, ++seed);  // below 0, 0 to 1 and past 1
    lambda.data()[0] = 0.f;
    lambda.data().back() = 1.f;
    const std::string size_name = std::to_string(w) + "x" + std::to_string(h);
    if (w * h > 200) {
      const HistoryPaths paths = history_paths(kernel_for(f, prev, hist, out));
      CHECK(paths.all_taps > 0.2);
      CHECK(paths.some_taps > 0.1);
      CHECK(paths.fallback > 0.02);
    }
    for (Antilag antilag : {Antilag::Off, Antilag::Statistics, Antilag::Gradient})
      for (bool with_lambda : {false, true})
        for (bool has_history : {true, false}) {
          ReprojectKernel k = kernel_for(f, prev, hist, out);
          k.params.antilag = antilag;
          k.params.history_cap = with_lambda ? 8 : 32;
          k.gradient_lambda = with_lambda ? lambda.plane(0) : nullptr;
          k.has_history = has_history;
          // A moving camera's depth map (core/previous_depth.h) with the lambda cases: the
          // previous depth about 0.5% off the current, varying over the image.
          if (with_lambda) k.previous_depth = {1.004f, -2e-5f, 3e-5f, -0.002f, 1e-5f, 0.f};
          require_rows_equal_pixels(k, "reproject " + size_name + ", antilag " +
                                           std::to_string(int(antilag)) +
                                           (with_lambda ? ", lambda" : "") +
                                           (has_history ? "" : ", no history"));
        }
  }
}

TEST_CASE("cpu rows: reprojection rows equal the per-pixel kernel on fixtures", "[cpu_rows]") {
  // camera-pan: every pixel moves, the pan uncovers an edge; cornell-moving: a moving object
  // disoccludes the wall behind it.
  for (const char* name : {"camera-pan", "cornell-moving"}) {
    const io::Sequence fixture(std::string(SVGF_SOURCE_DIR) + "/fixtures/" + name);
    const Frame prev = fixture.read(2), f = fixture.read(3);
    const History hist(f.width(), f.height(), 300);
    Image out(f.width(), f.height(), 7);
    for (Antilag antilag : {Antilag::Off, Antilag::Statistics}) {
      ReprojectKernel k = kernel_for(f, prev, hist, out);
      k.params.antilag = antilag;
      k.previous_depth = PreviousViewDepth::between(prev.camera, f.camera, f.width(), f.height());
      CHECK(k.previous_depth.is_identity() == (std::string(name) == "cornell-moving"));
      CHECK(history_paths(k).all_taps > 0.5);
      require_rows_equal_pixels(k, std::string(name) + ", antilag " + std::to_string(int(antilag)));
    }
  }
}

TEST_CASE("cpu rows: reprojection rows equal the per-pixel kernel under smooth motion",
          "[cpu_rows]") {
  // A camera's motion: smooth, each row's chunks reading their taps through a window's shifts
  // (all four kinds) or, where the field turns steep, moves off the image or is NaN, through
  // gathers; disocclusions and the 3x3 fallback as in the random frames.
  const int w = 455, h = 47;  // 28 chunks and a part of one a row
  auto [f, prev] = random_pair(w, h, 900);
  std::mt19937 rng(901);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      // Bands of 64 columns: the field flat along the row, sloped in x, in y, in both, steeper
      // in x (2 pixels of spread in a chunk), that and sloped in y; then steep (3 or more).
      const int band = x / 64;
      const float slopes_x[] = {0.f, 0.045f, 0.f, 0.06f, 0.11f, 0.11f, 0.25f, 0.25f};
      const float slopes_y[] = {0.f, 0.f, 0.035f, 0.05f, 0.f, 0.05f, 0.f, 0.f};
      const float slope_x = slopes_x[band], slope_y = slopes_y[band];
      const int i = y * w + x;
      f.motion.plane(0)[i] = -2.3f + slope_x * (x - 64 * band) + 0.011f * y;
      f.motion.plane(1)[i] = 1.7f + slope_y * (x - 64 * band) - 0.015f * y;
      if (u(rng) < 0.002f) f.motion.plane(0)[i] = kNaN;
      // The edge a pan uncovers: the first rows' first two chunks move from beyond the previous
      // frame's left edge (neither their taps nor their 3x3 blocks reach it: no history
      // without a read, kernels_cpu/svgf_reproject_rows.cpp), half of the third from 1.2 to
      // 2.6 pixels left of it (their taps outside, their blocks reaching column 0 up to 2).
      if (y < 6 && x < 32) f.motion.plane(0)[i] = -45.f - float(x);
      if (y < 6 && x >= 32 && x < 40) f.motion.plane(0)[i] = -float(x) - 1.2f - 0.2f * (x - 32);
    }
  const History hist(w, h, 902);
  Image out(w, h, 7), lambda(strata_along(w), strata_along(h), 1);
  test::fill_uniform(lambda, -0.2f, 1.2f, 903);
  const std::array<double, 7> kinds = chunk_kinds(kernel_for(f, prev, hist, out));
  for (int kind = 0; kind < 7; ++kind) {
    INFO("chunks of kind " << kind);
    CHECK(kinds[kind] > 0.03);
  }
  const HistoryPaths paths = history_paths(kernel_for(f, prev, hist, out));
  CHECK(paths.some_taps > 0.1);
  CHECK(paths.fallback > 0.01);
  for (bool with_lambda : {false, true}) {
    ReprojectKernel k = kernel_for(f, prev, hist, out);
    k.gradient_lambda = with_lambda ? lambda.plane(0) : nullptr;
    if (with_lambda) k.previous_depth = {1.004f, -2e-5f, 3e-5f, -0.002f, 1e-5f, 0.f};
    require_rows_equal_pixels(k, std::string("smooth motion") + (with_lambda ? ", lambda" : ""));
  }
  // A minimum weight of 0: a bilinear read with no consistent tap is then taken, and dropped
  // (its length 0 / 0), as the rows' pixels beyond the edge are without a read.
  ReprojectKernel k = kernel_for(f, prev, hist, out);
  k.params.reproject_min_weight = 0.f;
  require_rows_equal_pixels(k, "smooth motion, reproject_min_weight 0");
}

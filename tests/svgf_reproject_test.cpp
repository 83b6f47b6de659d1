#include <algorithm>
#include <cmath>

#include <catch2/catch.hpp>

#include "methods/svgf/reproject.h"
#include "kernels_cpu/parallel_for.h"
#include "test_support.h"

using namespace svgf;

namespace {

// Drives the reproject kernel alone, feeding its accumulated color back as the next frame's
// history (what the pipeline does with feedback disabled).
struct ReprojectRig {
  int w, h;
  Frame prev_frame, cur_frame;
  Image illum, prev_color, moments_prev, history_prev, accumulated, moments, history;
  bool has_history = false;
  SvgfParams params;

  ReprojectRig(int w_, int h_)
      : w(w_), h(h_), prev_frame(test::flat_frame(w_, h_)), cur_frame(test::flat_frame(w_, h_)),
        illum(w_, h_, 3), prev_color(w_, h_, 3), moments_prev(w_, h_, 2),
        history_prev(w_, h_, 1), accumulated(w_, h_, 4), moments(w_, h_, 2), history(w_, h_, 1) {}

  void step() {
    ReprojectKernel k;
    k.guides = cur_frame.guides();
    k.prev_guides = prev_frame.guides();
    k.illumination = illum.rgb();
    k.prev_color = prev_color.rgb();
    k.prev_moment1 = moments_prev.plane(0);
    k.prev_moment2 = moments_prev.plane(1);
    k.prev_history = history_prev.plane(0);
    k.has_history = has_history;
    k.accumulated = {accumulated.rgb(), accumulated.plane(3)};
    k.moment1 = moments.plane(0);
    k.moment2 = moments.plane(1);
    k.history = history.plane(0);
    k.params = params;
    cpu::for_each_pixel(w, h, k);
    // This frame's outputs become the next frame's history.
    for (int c = 0; c < 3; ++c)
      std::copy(accumulated.plane(c), accumulated.plane(c) + w * h, prev_color.plane(c));
    moments_prev = moments;
    history_prev = history;
    prev_frame = cur_frame;
    has_history = true;
  }
};

}  // namespace

TEST_CASE("reproject: the first frame starts a history of length 1", "[reproject]") {
  ReprojectRig rig(16, 8);
  test::fill_uniform(rig.illum, 0.f, 3.f, 11);
  rig.step();
  for (int i = 0; i < 16 * 8; ++i) {
    REQUIRE(rig.history.plane(0)[i] == 1.f);
    for (int c = 0; c < 3; ++c) REQUIRE(rig.accumulated.plane(c)[i] == rig.illum.plane(c)[i]);
    const float l = luminance(rig.illum.rgb().load(i));
    REQUIRE(rig.moments.plane(0)[i] == l);
    REQUIRE(rig.moments.plane(1)[i] == l * l);
    REQUIRE(rig.accumulated.plane(3)[i] == 0.f);
  }
}

TEST_CASE("reproject: a static 4-frame sequence accumulates to the exact mean", "[reproject]") {
  ReprojectRig rig(24, 10);
  std::vector<Image> frames;
  for (int k = 0; k < 4; ++k) {
    frames.emplace_back(24, 10, 3);
    test::fill_uniform(frames.back(), 0.f, 8.f, 100 + k);
  }
  for (int k = 0; k < 4; ++k) {
    rig.illum = frames[k];
    rig.step();
    for (int i = 0; i < 240; ++i) {
      REQUIRE(rig.history.plane(0)[i] == float(k + 1));
      for (int c = 0; c < 3; ++c) {
        double mean = 0;
        for (int j = 0; j <= k; ++j) mean += frames[j].plane(c)[i];
        mean /= (k + 1);
        // alpha = 1/h makes this the running mean; each frame adds at most ~2 roundings.
        REQUIRE(rig.accumulated.plane(c)[i] == Approx(mean).epsilon(1e-6).margin(1e-6));
      }
    }
  }
  // Past history 1/alpha = 20 the blend factor stops at alpha.
  for (int k = 4; k < 40; ++k) rig.step();
  REQUIRE(rig.history.plane(0)[0] == float(rig.params.history_cap));
}

TEST_CASE("reproject: a disoccluded pixel restarts its history", "[reproject]") {
  ReprojectRig rig(12, 12);
  test::fill_uniform(rig.illum, 0.5f, 2.f, 3);
  rig.step();
  rig.step();
  // A new object (mesh 2, nearer) now covers a 4x4 block: no consistent previous tap.
  for (int y = 4; y < 8; ++y)
    for (int x = 4; x < 8; ++x) {
      const int i = y * 12 + x;
      rig.cur_frame.mesh_id[i] = 2;
      rig.cur_frame.depth.plane(0)[i] = 1.f;
    }
  test::fill_uniform(rig.illum, 0.5f, 2.f, 4);
  rig.step();
  for (int y = 0; y < 12; ++y)
    for (int x = 0; x < 12; ++x) {
      const int i = y * 12 + x;
      const bool occluder = x >= 4 && x < 8 && y >= 4 && y < 8;
      INFO("pixel " << x << "," << y);
      REQUIRE(rig.history.plane(0)[i] == (occluder ? 1.f : 3.f));
      if (occluder) REQUIRE(rig.accumulated.plane(0)[i] == rig.illum.plane(0)[i]);
    }
}

TEST_CASE("reproject: depth and normal changes reject the history", "[reproject]") {
  ReprojectRig rig(8, 4);
  test::fill_uniform(rig.illum, 0.5f, 2.f, 5);
  rig.step();
  rig.cur_frame.depth.plane(0)[1] = 2.f * 1.2f;    // 20% deeper: beyond the 3% tolerance
  rig.cur_frame.depth.plane(0)[2] = 2.f * 1.02f;   // 2% deeper: within it
  rig.cur_frame.normal.plane(0)[3] = 1.f;          // normal tilted 45 degrees: cos 0.707 < 0.9
  rig.cur_frame.normal.plane(2)[3] = 1.f;
  rig.cur_frame.normal.plane(0)[3] /= std::sqrt(2.f);
  rig.cur_frame.normal.plane(2)[3] /= std::sqrt(2.f);
  rig.step();
  CHECK(rig.history.plane(0)[0] == 2.f);
  CHECK(rig.history.plane(0)[1] == 1.f);
  CHECK(rig.history.plane(0)[2] == 2.f);
  CHECK(rig.history.plane(0)[3] == 1.f);
}

TEST_CASE("reproject: motion vectors fetch history from the previous position", "[reproject]") {
  ReprojectRig rig(16, 6);
  test::fill_uniform(rig.illum, 0.5f, 2.f, 6);
  rig.step();
  const Image first = rig.illum;
  // Everything moved 3 px right: the previous position of pixel x is x - 3.
  for (int i = 0; i < 16 * 6; ++i) rig.cur_frame.motion.plane(0)[i] = -3.f;
  Image second(16, 6, 3);
  test::fill_uniform(second, 0.5f, 2.f, 7);
  rig.illum = second;
  rig.step();
  for (int y = 0; y < 6; ++y)
    for (int x = 0; x < 16; ++x) {
      const int i = y * 16 + x;
      INFO("pixel " << x << "," << y);
      if (x >= 3) {  // integer motion: one bilinear tap with weight 1, exact mean of two
        REQUIRE(rig.history.plane(0)[i] == 2.f);
        const float prev = first.plane(0)[y * 16 + x - 3];
        REQUIRE(rig.accumulated.plane(0)[i] == prev + (second.plane(0)[i] - prev) * 0.5f);
      } else if (x == 2) {
        // Came from x = -1, outside; the 3x3 fallback around it still finds pixel 0.
        REQUIRE(rig.history.plane(0)[i] == 2.f);
      } else {
        REQUIRE(rig.history.plane(0)[i] == 1.f);  // came from outside, nothing near
      }
    }
}

TEST_CASE("reproject: half-pixel motion blends the two bilinear taps", "[reproject]") {
  ReprojectRig rig(8, 1);
  for (int x = 0; x < 8; ++x)
    for (int c = 0; c < 3; ++c) rig.illum.at(x, 0, c) = float(x);
  rig.step();
  for (int x = 0; x < 8; ++x) rig.cur_frame.motion.plane(0)[x] = -0.5f;
  for (int x = 0; x < 8; ++x)
    for (int c = 0; c < 3; ++c) rig.illum.at(x, 0, c) = 100.f;
  rig.step();
  // Pixel 4 reads 0.5*3 + 0.5*4 = 3.5 from history, then blends with 100 at alpha 1/2.
  REQUIRE(rig.accumulated.at(4, 0, 0) == 3.5f + (100.f - 3.5f) * 0.5f);
  // Pixel 0 has only one tap inside (x=0, weight 0.5): renormalized to that tap's value.
  REQUIRE(rig.accumulated.at(0, 0, 0) == 0.f + (100.f - 0.f) * 0.5f);
}

TEST_CASE("reproject: color and moments follow their own alpha, capped history, in double",
          "[reproject]") {
  // A static sequence long enough for the history cap and both alpha floors to apply, with a
  // different illumination every frame. The reference is the paper's exponential moving
  // average in double: a = max(alpha, 1 / length) for the color, max(moments_alpha, 1 / length)
  // for the moments, length capped at history_cap. Swapping the two alphas, ignoring the cap or
  // the floor changes the result far beyond float rounding.
  struct Set {
    float alpha, moments_alpha;
    int cap;
  };
  for (const Set s : {Set{0.05f, 0.2f, 32}, Set{0.2f, 0.05f, 32}, Set{0.05f, 0.2f, 8}}) {
    ReprojectRig rig(6, 4);
    rig.params.alpha = s.alpha;
    rig.params.moments_alpha = s.moments_alpha;
    rig.params.history_cap = s.cap;
    double color = 0, m1 = 0, m2 = 0, length = 0;
    for (int k = 0; k < 48; ++k) {
      const float v = 0.5f + 0.45f * std::sin(0.7f * static_cast<float>(k));  // gray illumination
      for (int c = 0; c < 3; ++c) std::fill_n(rig.illum.plane(c), 6 * 4, v);
      rig.step();
      const double l = v;  // gray: luminance weights sum to 1 (within rounding)
      length = std::min(length + 1.0, double(s.cap));
      const double a = std::max(double(s.alpha), 1.0 / length);
      const double am = std::max(double(s.moments_alpha), 1.0 / length);
      color = k == 0 ? l : color + (l - color) * a;
      m1 = k == 0 ? l : m1 + (l - m1) * am;
      m2 = k == 0 ? l * l : m2 + (l * l - m2) * am;
    }
    INFO("alpha " << s.alpha << ", moments_alpha " << s.moments_alpha << ", cap " << s.cap);
    REQUIRE(rig.history.at(3, 2, 0) == static_cast<float>(s.cap));
    REQUIRE(rig.accumulated.at(3, 2, 1) == Approx(color).epsilon(1e-5));
    REQUIRE(rig.moments.at(3, 2, 0) == Approx(m1).epsilon(1e-5));
    REQUIRE(rig.moments.at(3, 2, 1) == Approx(m2).epsilon(1e-5));
    REQUIRE(rig.accumulated.at(3, 2, 3) == Approx(std::max(0.0, m2 - m1 * m1)).margin(1e-6));
  }
}

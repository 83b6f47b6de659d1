// Stage 2, temporal reprojection and accumulation, on every backend (tests/test_device.h). Fast
// mode runs this same exact kernel (its history decisions are exact mode's): CPU and CUDA exact.
#include <algorithm>
#include <cmath>
#include <utility>

#include <catch2/catch.hpp>

#include "methods/svgf/reproject.h"
#include "test_device.h"
#include "test_support.h"

using namespace svgf;
using svgf::test::TestDevice;

namespace {

// Drives the reproject kernel alone, feeding its accumulated color back as the next frame's
// history (what the pipeline does with feedback disabled).
struct ReprojectRig {
  test::TestDevice device;
  int w, h;
  Frame prev_frame, cur_frame;
  Image illum, prev_color, moments_prev, history_prev, accumulated, moments, history;
  bool has_history = false;
  // Falcor's values (alpha 0.05, cap 32), no anti-lag: the stage's own rules.
  SvgfParams params = svgf_preset("falcor");

  ReprojectRig(const test::TestDevice& d, int w_, int h_)
      : device(d), w(w_), h(h_), prev_frame(test::flat_frame(w_, h_)), cur_frame(test::flat_frame(w_, h_)),
        illum(w_, h_, 3), prev_color(w_, h_, 3), moments_prev(w_, h_, 2),
        history_prev(w_, h_, 1), accumulated(w_, h_, 4), moments(w_, h_, 2), history(w_, h_, 1) {}

  void step() {
    test::StageRunner r(device);  // a fresh one each step: the images below are reassigned
    ReprojectKernel k;
    k.guides = r.guides(cur_frame);
    k.prev_guides = r.guides(prev_frame);
    k.illumination = r.rgb(std::as_const(illum));
    // The anti-lag demodulates the neighbours again: the frame's color over an albedo of 1 is
    // the illumination.
    cur_frame.albedo = Image(w, h, 3, 1.f);
    cur_frame.color = illum;
    k.color = r.rgb(std::as_const(cur_frame.color));
    k.albedo = r.rgb(std::as_const(cur_frame.albedo));
    k.prev_color = r.rgb(std::as_const(prev_color));
    k.prev_moment1 = r.plane(std::as_const(moments_prev), 0);
    k.prev_moment2 = r.plane(std::as_const(moments_prev), 1);
    k.prev_history = r.plane(std::as_const(history_prev));
    k.has_history = has_history;
    k.accumulated = r.illum_var(accumulated);
    k.moment1 = r.plane(moments, 0);
    k.moment2 = r.plane(moments, 1);
    k.history = r.plane(history);
    k.params = params;
    r.run(k, w, h, "reproject");
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

namespace {

void first_frame_starts_history(const TestDevice& d) {
  ReprojectRig rig(d, 16, 8);
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

void static_sequence_accumulates_mean(const TestDevice& d) {
  ReprojectRig rig(d, 24, 10);
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

// Issue 12, item 3's fallback: a history that disagrees with this frame's neighbourhood (5x5)
// loses a share of its length. A constant frame has no spread, so the tolerance is
// antilag_relative * max(history, neighbourhood) luminance and the answers are exact.
void antilag_shortens_contradicted_history(const TestDevice& d) {
  const auto run = [&](bool antilag, float planted) {
    ReprojectRig rig(d, 9, 9);
    rig.params.antilag = antilag ? Antilag::Statistics : Antilag::Off;
    rig.params.antilag_relative = 0.1f;
    rig.params.antilag_low = 3.f;
    rig.params.antilag_high = 6.f;
    rig.illum = Image(9, 9, 3, 1.f);
    for (int k = 0; k < 4; ++k) rig.step();  // history 4 of a grey 1 everywhere
    for (int c = 0; c < 3; ++c) rig.prev_color.at(4, 4, c) = planted;
    rig.step();
    return rig;
  };
  // An outlier (50x): |50 - 1| / (0.1 * 50) = 9.8 >= 6, all dropped: the pixel restarts.
  // And one so large (1e8) that blending it out would lose the new sample in rounding
  // (1e8 + (1 - 1e8) = 0 in float): a restart keeps nothing of it.
  for (float planted : {50.f, 1e8f}) {
    const ReprojectRig outlier = run(true, planted);
    INFO("planted " << planted);
    REQUIRE(outlier.history.at(4, 4, 0) == 1.f);
    for (int c = 0; c < 3; ++c) REQUIRE(outlier.accumulated.at(4, 4, c) == 1.f);
    REQUIRE(outlier.moments.at(4, 4, 0) == luminance(make_vec3(1.f, 1.f, 1.f)));
  }
  const ReprojectRig outlier = run(true, 50.f);
  // Its neighbours agree with the frame (the outlier is in the history, not in this frame's
  // samples): they keep their history.
  REQUIRE(outlier.history.at(3, 4, 0) == 5.f);
  REQUIRE(outlier.history.at(0, 0, 0) == 5.f);
  // Off, the outlier stays and is blended in at 1/5.
  const ReprojectRig kept = run(false, 50.f);
  REQUIRE(kept.history.at(4, 4, 0) == 5.f);
  REQUIRE(kept.accumulated.at(4, 4, 0) == Approx(50.0 + (1.0 - 50.0) / 5.0));
  // Part of the way: |1.5 - 1| / (0.1 * 1.5) = 3.33, so 1/9 of the history goes: length
  // 4 * 8/9 + 1 = 4.556, alpha 1 / 4.556, color 1.5 + (1 - 1.5) / 4.556.
  const ReprojectRig partial = run(true, 1.5f);
  const double drop = (0.5 / 0.15 - 3.0) / 3.0;
  const double length = 4.0 * (1.0 - drop) + 1.0;
  REQUIRE(partial.history.at(4, 4, 0) == Approx(length).epsilon(1e-5));
  REQUIRE(partial.accumulated.at(4, 4, 0) == Approx(1.5 - 0.5 / length).epsilon(1e-5));
  // Below antilag_low nothing changes: |1.2 - 1| / 0.12 = 1.67.
  REQUIRE(run(true, 1.2f).history.at(4, 4, 0) == 5.f);
}

void disocclusion_restarts_history(const TestDevice& d) {
  ReprojectRig rig(d, 12, 12);
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

void depth_and_normal_reject_history(const TestDevice& d) {
  ReprojectRig rig(d, 8, 4);
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

void motion_fetches_previous_position(const TestDevice& d) {
  ReprojectRig rig(d, 16, 6);
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

void half_pixel_motion_blends_taps(const TestDevice& d) {
  ReprojectRig rig(d, 8, 1);
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

void own_alphas_and_cap_in_double(const TestDevice& d) {
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
    ReprojectRig rig(d, 6, 4);
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

void depth_and_normal_thresholds(const TestDevice& d) {
  // A static 5x5 frame whose previous depth or normal is moved, everywhere (else the 3x3
  // fallback would find the unmoved neighbours), just inside or just outside the tolerance
  // |z - z_prev| <= scale * fwidth(z) + relative * z (and n . n_prev >= reproject_normal_cos).
  // Kept: history length 2; rejected: 1.
  auto history_after = [&](auto change_params, float prev_depth, float prev_nx) {
    ReprojectRig rig(d, 5, 5);
    change_params(rig.params);
    for (int i = 0; i < 25; ++i) rig.cur_frame.depth_gradient.plane(0)[i] = 0.01f;
    test::fill_uniform(rig.illum, 0.1f, 1.f, 5);
    rig.prev_frame = rig.cur_frame;
    rig.step();  // frame 0: history 1 everywhere, prev_frame := cur_frame
    const float nz = std::sqrt(1.f - prev_nx * prev_nx);
    for (int i = 0; i < 25; ++i) {
      rig.prev_frame.depth.plane(0)[i] = prev_depth;
      rig.prev_frame.normal.plane(0)[i] = prev_nx;
      rig.prev_frame.normal.plane(2)[i] = nz;
    }
    rig.step();
    return rig.history.at(2, 2, 0);
  };
  const auto defaults = [](SvgfParams&) {};
  // Defaults: tolerance 10 * 0.01 + 0.03 * 2 = 0.16.
  REQUIRE(history_after(defaults, 2.15f, 0.f) == 2.f);
  REQUIRE(history_after(defaults, 2.17f, 0.f) == 1.f);
  // The gradient scale multiplies fwidth: 5 * 0.01 + 0.06 = 0.11.
  const auto scale5 = [](SvgfParams& p) { p.reproject_depth_gradient_scale = 5.f; };
  REQUIRE(history_after(scale5, 2.10f, 0.f) == 2.f);
  REQUIRE(history_after(scale5, 2.12f, 0.f) == 1.f);
  // The relative term multiplies the depth: 0.1 + 0.1 * 2 = 0.3.
  const auto relative = [](SvgfParams& p) { p.reproject_depth_relative = 0.1f; };
  REQUIRE(history_after(relative, 2.29f, 0.f) == 2.f);
  REQUIRE(history_after(relative, 2.31f, 0.f) == 1.f);
  // Normals: cos = sqrt(1 - nx^2); 0.3 -> 0.954, 0.45 -> 0.893 (threshold 0.9, then 0.96).
  REQUIRE(history_after(defaults, 2.f, 0.3f) == 2.f);
  REQUIRE(history_after(defaults, 2.f, 0.45f) == 1.f);
  const auto strict = [](SvgfParams& p) { p.reproject_normal_cos = 0.96f; };
  REQUIRE(history_after(strict, 2.f, 0.3f) == 1.f);
}

void min_weight_falls_back_to_3x3(const TestDevice& d) {
  // Motion (0.7, 0.7): bilinear weights 0.09 (x, y), 0.21, 0.21, 0.49. Only tap (x, y) passes
  // the depth test, so the kept weight is 0.09: above the default 0.01 the history is that
  // tap's color; with min_weight 0.1 it is the mean of the consistent pixels of the 3x3 block
  // around the nearest previous pixel (x + 1, y + 1).
  auto accumulate = [&](float min_weight) {
    ReprojectRig rig(d, 7, 7);
    rig.params.reproject_min_weight = min_weight;
    test::fill_uniform(rig.illum, 0.1f, 1.f, 9);
    rig.prev_frame = rig.cur_frame;
    rig.step();  // frame 0: the history is this illumination
    for (int i = 0; i < 49; ++i) {
      rig.cur_frame.motion.plane(0)[i] = 0.7f;
      rig.cur_frame.motion.plane(1)[i] = 0.7f;
    }
    rig.prev_frame.depth.at(3, 2, 0) = 5.f;  // taps (x+1, y), (x, y+1), (x+1, y+1) of (2, 2)
    rig.prev_frame.depth.at(2, 3, 0) = 5.f;
    rig.prev_frame.depth.at(3, 3, 0) = 5.f;
    const Image history_color = rig.prev_color;
    test::fill_uniform(rig.illum, 1.5f, 2.5f, 10);  // a new sample, unlike any history
    rig.step();
    return std::make_pair(rig, history_color);
  };
  const auto [kept, prev_kept] = accumulate(0.01f);
  REQUIRE(kept.history.at(2, 2, 0) == 2.f);
  // alpha = 1/2 at length 2: (history + sample) / 2 with history = the one tap's color.
  const float h_tap = prev_kept.at(2, 2, 1);
  const float sample = kept.illum.at(2, 2, 1);
  REQUIRE(kept.accumulated.at(2, 2, 1) == Approx(h_tap + (sample - h_tap) * 0.5f).epsilon(1e-5));

  const auto [fell_back, prev_fb] = accumulate(0.1f);
  REQUIRE(fell_back.history.at(2, 2, 0) == 2.f);
  double mean = 0;
  int count = 0;
  for (int y = 2; y <= 4; ++y)
    for (int x = 2; x <= 4; ++x)
      if (!((x == 3 && y == 2) || (x == 2 && y == 3) || (x == 3 && y == 3))) {
        mean += prev_fb.at(x, y, 1);
        ++count;
      }
  mean /= count;
  REQUIRE(fell_back.accumulated.at(2, 2, 1) == Approx(mean + (sample - mean) * 0.5).epsilon(1e-5));
}

}  // namespace

SVGF_BACKEND_TEST("reproject: the first frame starts a history of length 1",
                  "[reproject]", first_frame_starts_history)
SVGF_BACKEND_TEST("reproject: a static 4-frame sequence accumulates to the exact mean",
                  "[reproject]", static_sequence_accumulates_mean)
SVGF_BACKEND_TEST("reproject: the anti-lag shortens a history the frame's neighbourhood contradicts",
                  "[reproject][antilag]", antilag_shortens_contradicted_history)
SVGF_BACKEND_TEST("reproject: a disoccluded pixel restarts its history",
                  "[reproject]", disocclusion_restarts_history)
SVGF_BACKEND_TEST("reproject: depth and normal changes reject the history",
                  "[reproject]", depth_and_normal_reject_history)
SVGF_BACKEND_TEST("reproject: motion vectors fetch history from the previous position",
                  "[reproject]", motion_fetches_previous_position)
SVGF_BACKEND_TEST("reproject: half-pixel motion blends the two bilinear taps",
                  "[reproject]", half_pixel_motion_blends_taps)
SVGF_BACKEND_TEST("reproject: color and moments follow their own alpha, capped history, in double",
                  "[reproject]", own_alphas_and_cap_in_double)
SVGF_BACKEND_TEST("reproject: the depth test's two tolerances and the normal test, at their thresholds",
                  "[reproject]", depth_and_normal_thresholds)
SVGF_BACKEND_TEST("reproject: below reproject_min_weight the bilinear taps give way to the 3x3 fallback",
                  "[reproject]", min_weight_falls_back_to_3x3)

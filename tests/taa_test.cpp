// core/taa.h, the temporal anti-aliasing stage, with known answers on every backend (CPU and
// CUDA exact, bitwise with the CPU; fast mode runs this same kernel).
#include <cstring>
#include <utility>

#include <catch2/catch.hpp>

#include "core/taa.h"
#include "test_device.h"
#include "test_support.h"

using namespace svgf;
using svgf::test::StageRunner;
using svgf::test::TestDevice;

namespace {

constexpr float kAlpha = 0.2f;

// Runs the stage on `f`'s motion; returns the output (and checks the history it leaves is the
// same image).
Image run_taa(const TestDevice& d, const Frame& f, const Image& current, const Image& history,
              bool has_history) {
  const int w = f.width(), h = f.height();
  Image out(w, h, 3, -1.f), next(w, h, 3, -1.f);
  StageRunner r(d);
  TemporalAntiAliasing k;
  k.guides = r.guides(f);
  k.current = r.rgb(current);
  k.history = r.rgb(history);
  k.history_out = r.rgb(next);
  k.output = r.rgb(out);
  k.has_history = has_history;
  k.alpha = kAlpha;
  r.run(k, w, h, "taa");
  test::require_identical(out, next, "TAA output vs the history it leaves");
  return out;
}

Image gray(int w, int h, float v) { return Image(w, h, 3, v); }

void without_history_the_frame_passes(const TestDevice& d) {
  const Frame f = test::flat_frame(9, 6);
  Image current(9, 6, 3);
  test::fill_uniform(current, 0.f, 5.f, 3);
  test::require_identical(run_taa(d, f, current, gray(9, 6, 100.f), false), current,
                          "no history");
  // History, but every tap outside the image: at the right edge, moved one pixel right.
  Frame moved = f;
  for (size_t i = 0; i < moved.motion.pixel_count(); ++i) moved.motion.plane(0)[i] = 1.f;
  const Image out = run_taa(d, moved, current, gray(9, 6, 100.f), true);
  for (int y = 0; y < 6; ++y)
    for (int c = 0; c < 3; ++c) REQUIRE(out.at(8, y, c) == current.at(8, y, c));
}

void history_is_clamped_to_the_rounder_box(const TestDevice& d) {
  // A gray frame (YCoCg (4g, 0, 0)) of 0.2 with, around (2, 2), 0.4 to the right (in the
  // cross) and 0.6 down-right (in the box only): the upper bound is (0.6 + 0.4) / 2 = 0.5, the
  // lower (0.2 + 0.2) / 2 = 0.2.
  const Frame f = test::flat_frame(6, 5);
  Image current = gray(6, 5, 0.2f);
  for (int c = 0; c < 3; ++c) {
    current.at(3, 2, c) = 0.4f;
    current.at(3, 3, c) = 0.6f;
  }
  const Image bright = run_taa(d, f, current, gray(6, 5, 10.f), true);
  const Image dark = run_taa(d, f, current, gray(6, 5, 0.f), true);
  for (int c = 0; c < 3; ++c) {
    REQUIRE(bright.at(2, 2, c) == Approx(kAlpha * 0.2f + (1 - kAlpha) * 0.5f).margin(1e-6));
    REQUIRE(dark.at(2, 2, c) == Approx(0.2f).margin(1e-6));
  }
  // A colored frame, constant: its neighbourhood is one point, so any history becomes it.
  Image colored(6, 5, 3);
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 6; ++x) {
      colored.at(x, y, 0) = 0.3f;
      colored.at(x, y, 1) = 0.5f;
      colored.at(x, y, 2) = 0.7f;
    }
  Image other(6, 5, 3);
  test::fill_uniform(other, 0.f, 3.f, 9);
  const Image out = run_taa(d, f, colored, other, true);
  REQUIRE(test::max_relative_difference(out, colored, 1e-3) <= 1e-6);
}

void history_follows_the_motion(const TestDevice& d) {
  // A checkerboard of 0 and 1 (every neighbourhood spans [0, 1]: no clamping) and a history
  // that is x / 16. Motion (+1, 0): pixel x reads the history at x + 1, weight 1. Motion
  // (+0.5, 0) at the right edge: one tap in the image, weight 1/2, renormalized to the tap.
  const int w = 12, h = 4;
  Frame f = test::flat_frame(w, h);
  Image current(w, h, 3), history(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) {
        current.at(x, y, c) = static_cast<float>((x + y) % 2);
        history.at(x, y, c) = static_cast<float>(x) / 16.f;
      }
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) f.motion.at(x, y, 0) = x == w - 1 ? 0.5f : 1.f;
  const Image out = run_taa(d, f, current, history, true);
  for (int y = 1; y < h - 1; ++y) {
    for (int x = 1; x < w - 1; ++x) {
      const float expected = kAlpha * current.at(x, y, 0) + (1 - kAlpha) * (x + 1) / 16.f;
      INFO("pixel " << x << ", " << y);
      REQUIRE(out.at(x, y, 1) == Approx(expected).margin(1e-6));
    }
    const float edge = kAlpha * current.at(w - 1, y, 0) + (1 - kAlpha) * (w - 1) / 16.f;
    REQUIRE(out.at(w - 1, y, 1) == Approx(edge).margin(1e-6));
  }
}

}  // namespace

SVGF_BACKEND_TEST("taa: without history, or with no tap in the image, the frame passes",
                  "[taa]", without_history_the_frame_passes)
SVGF_BACKEND_TEST("taa: history is clamped to this frame's rounder box in YCoCg", "[taa]",
                  history_is_clamped_to_the_rounder_box)
SVGF_BACKEND_TEST("taa: history follows the motion, taps outside the image renormalized",
                  "[taa]", history_follows_the_motion)

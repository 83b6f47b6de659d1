// The joint bilateral filter's vectorized CPU rows (kernels_cpu/jbf_rows.cpp) must give the
// per-pixel kernel's bits exactly (the per-pixel kernel is what the GPU runs), in both forms,
// for every step, border and guide oddity.
#include <cmath>
#include <limits>
#include <string>

#include <catch2/catch.hpp>

#include "kernels_cpu/jbf_rows.h"
#include "kernels_cpu/parallel_for.h"
#include "test_support.h"

using namespace svgf;

TEST_CASE("cpu rows: JBF rows equal the per-pixel kernel bitwise", "[cpu_rows]") {
  const int sizes[][2] = {{97, 41}, {16, 16}, {3, 2}, {1, 7}};
  const float nan = std::numeric_limits<float>::quiet_NaN();
  uint32_t seed = 500;
  for (const auto& size : sizes) {
    const int w = size[0], h = size[1];
    Frame f = test::flat_frame(w, h);
    Image noise(w, h, 4), in(w, h, 3);
    test::fill_uniform(noise, 0.f, 1.f, ++seed);
    test::fill_uniform(in, 0.f, 2.f, ++seed);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {  // two surfaces, holes, tilted normals
        const int i = y * w + x;
        const float u = noise.plane(0)[i];
        f.depth.plane(0)[i] = u < 0.08f ? 0.f : 2.f;
        const float tilt = noise.plane(1)[i] * 1.6f - 0.8f;  // angles on both sides of 0
        f.normal.at(x, y, 0) = tilt / std::sqrt(1.f + tilt * tilt);
        f.normal.at(x, y, 2) = (u < 0.3f ? -1.f : 1.f) / std::sqrt(1.f + tilt * tilt);
        f.position.at(x, y, 0) = 0.1f * x;
        f.position.at(x, y, 1) = 0.1f * y;
        f.position.at(x, y, 2) = u < 0.5f ? 0.3f * noise.plane(2)[i] : 1.f;
      }
    if (w * h > 100) {
      f.normal.at(1, 1, 1) = nan;  // a NaN guide zeroes the weight
      f.position.at(4, 2, 0) = nan;
      f.position.at(6, 3, 0) = f.position.at(5, 3, 0);  // coinciding positions: D_plane = 0
      f.position.at(6, 3, 1) = f.position.at(5, 3, 1);
      f.position.at(6, 3, 2) = f.position.at(5, 3, 2);
    }
    const JbfScales scales = JbfScales::of(JbfParams{});
    const struct {
      int radius, step;
      bool b3;
    } forms[] = {{16, 1, false}, {3, 1, false}, {2, 1, true}, {2, 4, true}, {2, 16, true}};
    for (const auto& form : forms) {
      Image a(w, h, 3, -1.f), b(w, h, 3, -2.f);
      const JbfPass<ExactArith> k{f.guides(), f.position.rgb(), in.rgb(), a.rgb(),
                                  form.radius, form.step,       form.b3,  scales};
      JbfPass<ExactArith> k2 = k;
      k2.out = b.rgb();
      cpu::for_each_pixel(w, h, k);
      cpu::run_jbf_rows(k2, w, h);
      test::require_identical(b, a, "jbf " + std::to_string(w) + "x" + std::to_string(h) +
                                        " radius " + std::to_string(form.radius) + " step " +
                                        std::to_string(form.step) + (form.b3 ? " a-trous" : ""));
    }
  }
}

// A tap without a surface must leave the sums alone, -0 included: surface pixels of color -0
// among background keep -0 (the per-pixel kernel skips the background taps), one inside (the
// grouped taps) and one at the border (the single taps).
TEST_CASE("cpu rows: a JBF tap without a surface leaves a -0 sum alone", "[cpu_rows]") {
  const int w = 9, h = 7;
  Frame f = test::flat_frame(w, h);
  for (float& d : f.depth.data()) d = 0.f;
  Image in(w, h, 3, 0.5f);
  for (int x : {0, 4}) {
    f.depth.at(x, 3, 0) = 2.f;
    for (int c = 0; c < 3; ++c) in.at(x, 3, c) = -0.f;
  }
  for (bool b3 : {false, true}) {
    Image a(w, h, 3, -1.f), b(w, h, 3, -2.f);
    const JbfPass<ExactArith> k{f.guides(), f.position.rgb(), in.rgb(), a.rgb(), b3 ? 2 : 4, 1,
                                b3, JbfScales::of(JbfParams{})};
    JbfPass<ExactArith> k2 = k;
    k2.out = b.rgb();
    cpu::for_each_pixel(w, h, k);
    cpu::run_jbf_rows(k2, w, h);
    REQUIRE(std::signbit(a.at(0, 3, 0)));
    REQUIRE(std::signbit(a.at(4, 3, 0)));
    test::require_identical(b, a, b3 ? "a-trous" : "full window");
  }
}

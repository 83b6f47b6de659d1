// The stability suite's measures on hand-made images (metrics/detail.h, metrics/disocclusion.h,
// metrics/outlier_spread.h): edge preservation, high-frequency ratio, disoccluded pixels and
// an outlier's spread.
#include <cmath>
#include <vector>

#include <catch2/catch.hpp>

#include "metrics/detail.h"
#include "metrics/disocclusion.h"
#include "metrics/outlier_spread.h"

#include "test_support.h"

using namespace svgf;
using namespace svgf::metrics;

namespace {

using svgf::test::set_gray;

// Columns x >= 4 at height[y] (clamped to [0, 1] by the measures), the rest 0.
Image steps(const std::vector<float>& height) {
  Image im(8, static_cast<int>(height.size()), 3, 0.f);
  for (int y = 0; y < im.height(); ++y)
    for (int x = 4; x < 8; ++x) set_gray(im, x, y, height[static_cast<size_t>(y)]);
  return im;
}

// 12x3: columns 0-3 at level[0], 4-7 at level[1], 8-11 at level[2].
Image terraces(const std::vector<float>& level) {
  Image im(12, 3, 3);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 12; ++x) set_gray(im, x, y, level[static_cast<size_t>(x / 4)]);
  return im;
}

Image checkerboard(int n, float a, float b) {
  Image im(n, n, 3);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) set_gray(im, x, y, (x + y) % 2 ? b : a);
  return im;
}

}  // namespace

TEST_CASE("detail: gradient magnitude and edge pixels of a step", "[metrics]") {
  const Image step = steps({3.f, 3.f, 3.f, 3.f});  // clamped to 1
  const std::vector<double> g = gradient_magnitude(clamped_luminance(step), 8, 4);
  // A unit step between columns 3 and 4: 0.5 on both, 0 elsewhere, on every row (the borders
  // repeat the edge rows).
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 8; ++x)
      REQUIRE(g[static_cast<size_t>(y) * 8 + x] ==
              Approx(x == 3 || x == 4 ? 0.5 : 0.0).margin(1e-12));
  // 10% of 32 pixels is 4, but the 8 tied at the cut all count; the flat rest never does.
  const std::vector<uint8_t> edge = edge_pixels(step, 0.1);
  int count = 0;
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 8; ++x) {
      const bool on = edge[static_cast<size_t>(y) * 8 + x] != 0;
      REQUIRE(on == (x == 3 || x == 4));
      count += on;
    }
  REQUIRE(count == 8);
  REQUIRE(edge_pixels(steps({0.f, 0.f, 0.f, 0.f}), 0.5)[3] == 0);  // below the floor
}

TEST_CASE("detail: edge preservation", "[metrics]") {
  // Two edges on every row: 0 -> 0.2 between columns 3 and 4, 0.2 -> 1 between 7 and 8.
  const Image ref = terraces({0.f, 0.2f, 1.f});
  REQUIRE(edge_preservation(ref, ref, 0.5) == Approx(1.0));
  // Half as bright: every edge keeps its relative strength.
  Image half = ref;
  for (float& v : half.data()) v *= 0.5f;
  REQUIRE(edge_preservation(half, ref, 0.5) == Approx(1.0));
  // The strengths swapped (the strong edge became the weak one): -1.
  REQUIRE(edge_preservation(terraces({0.f, 0.8f, 1.f}), ref, 0.5) == Approx(-1.0));
  // The edges blurred away entirely: the test is flat, undefined.
  REQUIRE(std::isnan(edge_preservation(Image(12, 3, 3, 0.4f), ref, 0.5)));
  REQUIRE(std::isnan(edge_preservation(ref, Image(12, 3, 3, 0.4f), 0.5)));  // no edges
  REQUIRE_THROWS_AS(edge_preservation(Image(4, 4, 3), ref), std::invalid_argument);
}

TEST_CASE("detail: high-frequency ratio", "[metrics]") {
  const Image ref = checkerboard(6, 0.f, 0.8f);
  REQUIRE(high_frequency_ratio(ref, ref) == Approx(1.0));
  Image half = checkerboard(6, 0.f, 0.4f);
  REQUIRE(high_frequency_ratio(half, ref) == Approx(0.25));  // energy: amplitude squared
  REQUIRE(high_frequency_ratio(Image(6, 6, 3, 0.4f), ref) == Approx(0.0).margin(1e-12));
  REQUIRE(high_frequency_ratio(checkerboard(6, 0.f, 1.6f), ref) == Approx(1.5625));  // clamped to 1
  REQUIRE(std::isnan(high_frequency_ratio(ref, Image(6, 6, 3, 0.4f))));
}

// A 5x1 row: the wall (mesh 1) and an object (mesh 2) at x = 1 that moves to x = 2; x = 4 is
// background.
TEST_CASE("disocclusion: the pixels a moving object uncovered", "[metrics]") {
  const std::vector<uint32_t> previous = {1, 2, 1, 1, 0};
  const std::vector<uint32_t> current = {1, 1, 2, 1, 0};
  Image motion(5, 1, 2, 0.f);
  motion.at(2, 0, 0) = -1.f;    // the object's pixel came from x = 1: history
  motion.at(3, 0, 0) = 5.f;     // off the image: no history
  motion.at(4, 0, 0) = -4.f;    // background: never counted
  const PixelMask m = disoccluded_pixels(previous, current, motion);
  REQUIRE(m.count == 2);
  REQUIRE(m.inside == std::vector<uint8_t>{0, 1, 0, 1, 0});
  motion.at(2, 0, 0) = 0.f;  // a wrong motion vector leaves the object on the wall's pixel
  REQUIRE(disoccluded_pixels(previous, current, motion).count == 3);
  motion.at(2, 0, 0) = -0.6f;  // rounds to x = 1
  REQUIRE(disoccluded_pixels(previous, current, motion).count == 2);
  REQUIRE_THROWS_AS(disoccluded_pixels(previous, {1, 1}, motion), std::invalid_argument);
}

TEST_CASE("outlier spread: pixels made worse, and how far from the outlier", "[metrics]") {
  const Image ref(5, 5, 3, 1.f);
  const Image clean(5, 5, 3, 1.1f);  // error 0.01 / 1.01 everywhere
  REQUIRE(pixel_relative_error(clean, ref, 0) == Approx(0.01 / 1.01));
  Image outlier = clean;
  set_gray(outlier, 2, 2, 5.f);
  set_gray(outlier, 4, 2, 1.2f);   // 0.04 / 1.01: over twice the clean error
  set_gray(outlier, 0, 0, 1.12f);  // 0.0144 / 1.01: worse, but under twice
  const OutlierSpread s = outlier_spread(outlier, clean, ref, 2, 2);
  REQUIRE(s.pixels == 2);
  REQUIRE(s.radius == 2);
  const OutlierSpread none = outlier_spread(clean, clean, ref, 2, 2);
  REQUIRE(none.pixels == 0);
  REQUIRE(none.radius == -1);
  // Where the clean run is exact, the floor keeps a tiny difference out.
  Image tiny = ref;
  set_gray(tiny, 1, 1, 1.0001f);
  REQUIRE(outlier_spread(tiny, ref, ref, 2, 2).pixels == 0);
  REQUIRE_THROWS_AS(outlier_spread(Image(4, 4, 3), clean, ref, 0, 0), std::invalid_argument);
}

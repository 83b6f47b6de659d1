#include <cmath>
#include <limits>

#include <catch2/catch.hpp>

#include "methods/svgf/demodulate.h"
#include "methods/svgf/remodulate.h"
#include "kernels_cpu/parallel_for.h"
#include "test_support.h"

using namespace svgf;

TEST_CASE("demodulate: a constant image stays constant", "[demodulate]") {
  Image color(19, 7, 3, 0.75f), albedo(19, 7, 3, 0.3f), illum(19, 7, 3, -1.f);
  DemodulateKernel k{19, color.rgb(), albedo.rgb(), {}, illum.rgb(), 1e-3f};
  REQUIRE(cpu::count_pixels(19, 7, k) == 0);
  for (float v : illum.data()) REQUIRE(v == 0.75f / 0.3f);
}

TEST_CASE("demodulate: zero and NaN albedo are clamped, never divided by", "[demodulate]") {
  Image color(4, 1, 3, 2.f), albedo(4, 1, 3, 0.f), illum(4, 1, 3);
  albedo.at(1, 0, 0) = std::numeric_limits<float>::quiet_NaN();
  albedo.at(2, 0, 1) = -1.f;
  DemodulateKernel k{4, color.rgb(), albedo.rgb(), {}, illum.rgb(), 1e-3f};
  cpu::for_each_pixel(4, 1, k);
  for (float v : illum.data()) REQUIRE(v == 2.f / 1e-3f);
}

TEST_CASE("demodulate: NaN, Inf and negative color are replaced by 0 and counted",
          "[demodulate]") {
  Image color(5, 2, 3), albedo(5, 2, 3, 0.5f), illum(5, 2, 3);
  test::fill_uniform(color, 0.1f, 4.f, 7);
  color.at(0, 0, 0) = std::numeric_limits<float>::quiet_NaN();
  color.at(3, 0, 2) = std::numeric_limits<float>::infinity();
  color.at(4, 1, 1) = -0.25f;
  color.at(4, 1, 2) = -std::numeric_limits<float>::infinity();  // same pixel: counted once
  DemodulateKernel k{5, color.rgb(), albedo.rgb(), {}, illum.rgb(), 1e-3f};
  REQUIRE(cpu::count_pixels(5, 2, k) == 3);
  CHECK(illum.at(0, 0, 0) == 0.f);
  CHECK(illum.at(0, 0, 1) == color.at(0, 0, 1) / 0.5f);  // the other channels are kept
  CHECK(illum.at(3, 0, 2) == 0.f);
  CHECK(illum.at(4, 1, 1) == 0.f);
  CHECK(illum.at(4, 1, 2) == 0.f);
  for (float v : illum.data()) REQUIRE(std::isfinite(v));
}

TEST_CASE("remodulate undoes demodulate to within an ulp", "[demodulate][remodulate]") {
  Image color(33, 9, 3), albedo(33, 9, 3), illum(33, 9, 3), out(33, 9, 3);
  test::fill_uniform(color, 0.f, 20.f, 1);
  test::fill_uniform(albedo, 0.01f, 1.f, 2);
  cpu::for_each_pixel(33, 9, DemodulateKernel{33, color.rgb(), albedo.rgb(), {}, illum.rgb(), 1e-3f});
  cpu::for_each_pixel(33, 9, RemodulateKernel{33, illum.rgb(), {albedo.rgb(), {}, out.rgb(), 1e-3f}});
  REQUIRE(test::max_relative_difference(out, color) <= 2.4e-7);  // two roundings
}

TEST_CASE("demodulate takes the emission out and remodulate puts it back", "[demodulate]") {
  Image color(6, 4, 3), albedo(6, 4, 3, 0.5f), emission(6, 4, 3), illum(6, 4, 3), out(6, 4, 3);
  test::fill_uniform(emission, 1.f, 20.f, 81);
  test::fill_uniform(color, 0.f, 1.f, 82);
  for (size_t i = 0; i < color.data().size(); ++i) color.data()[i] += emission.data()[i];
  color.at(2, 1, 0) = emission.at(2, 1, 0) * 0.999f;  // a hair below the emission: clamped to 0
  cpu::for_each_pixel(6, 4, DemodulateKernel{6, color.rgb(), albedo.rgb(), emission.rgb(), illum.rgb(), 1e-3f});
  CHECK(illum.at(2, 1, 0) == 0.f);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 6; ++x)
      if (x != 2 || y != 1)
        REQUIRE(illum.at(x, y, 1) == (color.at(x, y, 1) - emission.at(x, y, 1)) / 0.5f);
  cpu::for_each_pixel(6, 4, RemodulateKernel{6, illum.rgb(), {albedo.rgb(), emission.rgb(), out.rgb(), 1e-3f}});
  CHECK(out.at(2, 1, 0) == emission.at(2, 1, 0));
  CHECK(out.at(3, 2, 2) == Approx(color.at(3, 2, 2)).epsilon(1e-6));
}

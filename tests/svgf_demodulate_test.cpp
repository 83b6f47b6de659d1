// Stages 1 and 5, demodulation and remodulation, on every backend (tests/test_device.h). Fast
// mode runs these same exact kernels (fused into its other launches), so they run on the CPU
// and CUDA exact.
#include <cmath>
#include <limits>
#include <utility>

#include <catch2/catch.hpp>

#include "methods/svgf/demodulate.h"
#include "methods/svgf/remodulate.h"
#include "test_device.h"
#include "test_support.h"

using namespace svgf;
using svgf::test::StageRunner;
using svgf::test::TestDevice;

namespace {

void demodulate_constant_stays_constant(const TestDevice& d) {
  Image color(19, 7, 3, 0.75f), albedo(19, 7, 3, 0.3f), illum(19, 7, 3, -1.f);
  StageRunner r(d);
  r.run(DemodulateKernel{19, r.rgb(std::as_const(color)), r.rgb(std::as_const(albedo)), {},
                         r.rgb(illum), 1e-3f},
        19, 7);
  for (float v : illum.data()) REQUIRE(v == 0.75f / 0.3f);
}

void albedo_clamped(const TestDevice& d) {
  Image color(4, 1, 3, 2.f), albedo(4, 1, 3, 0.f), illum(4, 1, 3);
  albedo.at(1, 0, 0) = std::numeric_limits<float>::quiet_NaN();
  albedo.at(2, 0, 1) = -1.f;
  StageRunner r(d);
  r.run(DemodulateKernel{4, r.rgb(std::as_const(color)), r.rgb(std::as_const(albedo)), {},
                         r.rgb(illum), 1e-3f},
        4, 1);
  for (float v : illum.data()) REQUIRE(v == 2.f / 1e-3f);
}

void remodulate_undoes_demodulate(const TestDevice& d) {
  Image color(33, 9, 3), albedo(33, 9, 3), illum(33, 9, 3), out(33, 9, 3);
  test::fill_uniform(color, 0.f, 20.f, 1);
  test::fill_uniform(albedo, 0.01f, 1.f, 2);
  StageRunner r(d);
  const ConstRgbView a = r.rgb(std::as_const(albedo));
  r.run(DemodulateKernel{33, r.rgb(std::as_const(color)), a, {}, r.rgb(illum), 1e-3f}, 33, 9);
  r.run(RemodulateKernel{33, r.rgb(std::as_const(illum)), {a, {}, r.rgb(out), 1e-3f}}, 33, 9);
  REQUIRE(test::max_relative_difference(out, color) <= 2.4e-7);  // two roundings
}

void emission_out_and_back(const TestDevice& d) {
  Image color(6, 4, 3), albedo(6, 4, 3, 0.5f), emission(6, 4, 3), illum(6, 4, 3), out(6, 4, 3);
  test::fill_uniform(emission, 1.f, 20.f, 81);
  test::fill_uniform(color, 0.f, 1.f, 82);
  for (size_t i = 0; i < color.data().size(); ++i) color.data()[i] += emission.data()[i];
  color.at(2, 1, 0) = emission.at(2, 1, 0) * 0.999f;  // a hair below the emission: clamped to 0
  StageRunner r(d);
  const ConstRgbView a = r.rgb(std::as_const(albedo)), e = r.rgb(std::as_const(emission));
  r.run(DemodulateKernel{6, r.rgb(std::as_const(color)), a, e, r.rgb(illum), 1e-3f}, 6, 4);
  CHECK(illum.at(2, 1, 0) == 0.f);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 6; ++x)
      if (x != 2 || y != 1)
        REQUIRE(illum.at(x, y, 1) == (color.at(x, y, 1) - emission.at(x, y, 1)) / 0.5f);
  r.run(RemodulateKernel{6, r.rgb(std::as_const(illum)), {a, e, r.rgb(out), 1e-3f}}, 6, 4);
  CHECK(out.at(2, 1, 0) == emission.at(2, 1, 0));
  CHECK(out.at(3, 2, 2) == Approx(color.at(3, 2, 2)).epsilon(1e-6));
}

}  // namespace

SVGF_BACKEND_TEST("demodulate: a constant image stays constant", "[demodulate]",
                  demodulate_constant_stays_constant)
SVGF_BACKEND_TEST("demodulate: zero and NaN albedo are clamped, never divided by",
                  "[demodulate]", albedo_clamped)
SVGF_BACKEND_TEST("remodulate undoes demodulate to within an ulp", "[demodulate][remodulate]",
                  remodulate_undoes_demodulate)
SVGF_BACKEND_TEST("demodulate takes the emission out and remodulate puts it back",
                  "[demodulate]", emission_out_and_back)

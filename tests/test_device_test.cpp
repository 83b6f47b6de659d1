// The test harness itself (tests/test_device.h), on the host: the CPU == CUDA comparison is bit
// for bit and names where it failed; tolerances widen only in fast mode; the CPU runner runs
// the kernel on the images themselves and counts.
#include <cstring>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <catch2/catch.hpp>

#include "methods/svgf/demodulate.h"
#include "test_device.h"

using namespace svgf;
using namespace svgf::test;

namespace {
uint32_t bits(float v) {
  uint32_t u;
  std::memcpy(&u, &v, 4);
  return u;
}
}  // namespace

TEST_CASE("test device: the exact comparison is bitwise and names the first differences",
          "[harness]") {
  // Two planes of a 3x2 image.
  std::vector<uint32_t> want(12), got(12);
  for (size_t i = 0; i < want.size(); ++i) want[i] = got[i] = bits(0.25f * static_cast<float>(i));
  std::string first;
  REQUIRE(differing_words(want, got, 6, 3, {"color", "variance"}, &first) == 0);
  got[1] = bits(-0.f);  // +0 vs -0: equal as floats, different bits
  want[1] = bits(0.f);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  want[10] = bits(nan);
  got[10] = bits(nan) | 1u;  // another NaN payload
  REQUIRE(differing_words(want, got, 6, 3, {"color", "variance"}, &first) == 2);
  INFO(first);
  REQUIRE(first.find("color (1,0)") != std::string::npos);
  REQUIRE(first.find("variance (1,1)") != std::string::npos);
  got.pop_back();
  REQUIRE(differing_words(want, got, 6, 3, {}, nullptr) == 3);  // a size mismatch counts
}

TEST_CASE("test device: names, configurations and tolerances", "[harness]") {
  REQUIRE(kCpu.name() == "cpu");
  REQUIRE(kCudaExact.name() == "cuda");
  REQUIRE(kCudaFast.name() == "cuda-fast");
  REQUIRE(kCudaExact.tolerance(1e-6) == 1e-6);
  REQUIRE(kCudaFast.tolerance(1e-6) == kFastTolerance);
  REQUIRE(kCudaFast.tolerance(1e-2) == 1e-2);
  EngineConfig c;
  c = kCudaFast.config(c);
  REQUIRE(c.backend == Backend::Cuda);
  REQUIRE(c.mode == Mode::Fast);
}

namespace {
// Halves a plane in place; true where the value was above 1 (a counting kernel).
struct HalveAboveOne {
  float* v;
  int width;
  SVGF_HD bool operator()(int x, int y) const {
    const int i = y * width + x;
    const bool above = v[i] > 1.f;
    v[i] = v[i] * 0.5f;
    return above;
  }
};
}  // namespace

TEST_CASE("test device: on the CPU the runner runs on the images and counts", "[harness]") {
  Image im(5, 3, 1, 1.f);
  im.at(2, 1, 0) = 4.f;
  StageRunner r(kCpu);
  float* p = r.plane(im);
  REQUIRE(p == im.plane(0));  // the host plane itself
  REQUIRE(r.run(HalveAboveOne{p, 5}, 5, 3) == 1);
  REQUIRE(im.at(0, 0, 0) == 0.5f);
  REQUIRE(im.at(2, 1, 0) == 2.f);
}

#include <limits>

#include <catch2/catch.hpp>

#include "methods/svgf/atrous.h"
#include "kernels_cpu/parallel_for.h"
#include "test_support.h"

using namespace svgf;

namespace {

struct AtrousRig {
  int w, h;
  Frame frame;
  Image in, out;
  SvgfParams params;
  AtrousRig(int w_, int h_) : w(w_), h(h_), frame(test::flat_frame(w_, h_)), in(w_, h_, 4), out(w_, h_, 4) {}
  void run(int step) {
    cpu::for_each_pixel(w, h, AtrousKernel{frame.guides(), {in.rgb(), in.plane(3)},
                                           {out.rgb(), out.plane(3)}, step, params});
  }
};

constexpr float kInf = std::numeric_limits<float>::infinity();

}  // namespace

TEST_CASE("atrous: a constant image stays constant at every step", "[atrous]") {
  for (int step : {1, 2, 4, 8, 16}) {
    AtrousRig rig(37, 23);
    for (int c = 0; c < 3; ++c) std::fill_n(rig.in.plane(c), 37 * 23, 1.7f);
    std::fill_n(rig.in.plane(3), 37 * 23, 0.01f);
    rig.run(step);
    for (int i = 0; i < 37 * 23; ++i)
      for (int c = 0; c < 3; ++c) REQUIRE(rig.out.plane(c)[i] == Approx(1.7f).epsilon(3e-7));
  }
}

TEST_CASE("atrous: known answer for the variance, filtered with squared weights", "[atrous]") {
  AtrousRig rig(15, 15);
  rig.params.phi_color = kInf;  // every edge-stopping weight is exactly 1
  rig.params.phi_normal = 0.f;
  test::fill_uniform(rig.in, 0.1f, 1.f, 31);
  std::fill_n(rig.in.plane(3), 15 * 15, 0.5f);
  rig.run(1);
  // sum k^2 = (3/8^2 + 2 (1/4)^2 + 2 (1/16)^2)^2 = 0.2734375^2, sum k = 1: both exact.
  REQUIRE(rig.out.at(7, 7, 3) == Approx(0.5 * 0.2734375 * 0.2734375).epsilon(1e-6));
  // The color is the B3-weighted mean of the 5x5 neighbourhood.
  double expect = 0;
  for (int dy = -2; dy <= 2; ++dy)
    for (int dx = -2; dx <= 2; ++dx)
      expect += double(b3_weight(std::abs(dx))) * b3_weight(std::abs(dy)) * rig.in.at(7 + dx, 7 + dy, 0);
  REQUIRE(rig.out.at(7, 7, 0) == Approx(expect).epsilon(1e-6));
}

TEST_CASE("atrous: the variance prefilter is a renormalized 3x3 Gaussian", "[atrous]") {
  Frame f = test::flat_frame(5, 4);
  Image var(5, 4, 1);
  test::fill_uniform(var, 0.f, 1.f, 41);
  // Interior: the full kernel, weights sum to 1.
  double interior = 0;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx)
      interior += double(gauss3_weight(std::abs(dx))) * gauss3_weight(std::abs(dy)) * var.at(2 + dx, 1 + dy, 0);
  REQUIRE(prefiltered_variance(f.guides(), var.plane(0), 2, 1) == Approx(interior).epsilon(1e-6));
  // Corner: 4 taps, weights 1/4, 1/8, 1/8, 1/16 renormalized by their sum 9/16.
  const double corner = (0.25 * var.at(0, 0, 0) + 0.125 * var.at(1, 0, 0) + 0.125 * var.at(0, 1, 0) +
                         0.0625 * var.at(1, 1, 0)) / 0.5625;
  REQUIRE(prefiltered_variance(f.guides(), var.plane(0), 0, 0) == Approx(corner).epsilon(1e-6));
}

TEST_CASE("atrous: a flat noisy region keeps its mean", "[atrous]") {
  AtrousRig rig(64, 64);
  test::fill_uniform(rig.in, 0.5f, 1.5f, 51);
  std::fill_n(rig.in.plane(3), 64 * 64, 1.f / 12.f);  // the uniform noise's variance
  rig.run(1);
  double mean_in = 0, mean_out = 0, var_in = 0, var_out = 0;
  for (int i = 0; i < 64 * 64; ++i) {
    mean_in += rig.in.plane(1)[i];
    mean_out += rig.out.plane(1)[i];
  }
  mean_in /= 4096;
  mean_out /= 4096;
  for (int i = 0; i < 64 * 64; ++i) {
    var_in += (rig.in.plane(1)[i] - mean_in) * (rig.in.plane(1)[i] - mean_in);
    var_out += (rig.out.plane(1)[i] - mean_out) * (rig.out.plane(1)[i] - mean_out);
  }
  REQUIRE(mean_out == Approx(mean_in).epsilon(2e-3));
  REQUIRE(var_out < 0.5 * var_in);  // and it did filter
}

namespace {
// Two flat regions, left and right of x = 10, that differ in one guide; both colors constant.
void require_no_bleeding(AtrousRig& rig, float left, float right) {
  for (int y = 0; y < rig.h; ++y)
    for (int x = 0; x < rig.w; ++x) {
      for (int c = 0; c < 3; ++c) rig.in.at(x, y, c) = x < 10 ? left : right;
      rig.in.at(x, y, 3) = 1e-3f;
    }
  for (int step : {1, 2, 4}) {
    rig.run(step);
    for (int y = 0; y < rig.h; ++y) {
      INFO("step " << step << " row " << y);
      REQUIRE(rig.out.at(9, y, 0) == Approx(left).epsilon(1e-4));
      REQUIRE(rig.out.at(10, y, 0) == Approx(right).epsilon(1e-4));
    }
  }
}
}  // namespace

TEST_CASE("atrous: weights fall to ~0 across a depth edge", "[atrous]") {
  AtrousRig rig(20, 8);
  rig.params.phi_color = kInf;  // only the depth term can stop the filter
  for (int y = 0; y < 8; ++y)
    for (int x = 10; x < 20; ++x) rig.frame.depth.at(x, y, 0) = 3.f;
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 20; ++x) rig.frame.depth_gradient.at(x, y, 0) = 1e-3f;
  require_no_bleeding(rig, 0.2f, 0.8f);
}

TEST_CASE("atrous: weights fall to ~0 across a normal edge", "[atrous]") {
  AtrousRig rig(20, 8);
  rig.params.phi_color = kInf;
  for (int y = 0; y < 8; ++y)
    for (int x = 10; x < 20; ++x) {
      rig.frame.normal.at(x, y, 0) = 0.6f;  // 53 degrees apart: 0.8^128 ~ 4e-13
      rig.frame.normal.at(x, y, 2) = 0.8f;
    }
  require_no_bleeding(rig, 0.2f, 0.8f);
}

TEST_CASE("atrous: weights fall to ~0 across a luminance edge", "[atrous]") {
  AtrousRig rig(20, 8);  // same depth and normal everywhere: only luminance separates
  // Luminance 0.1 vs 10 with variance 1e-3: |dl| / phi_l = 9.9 / (10 sqrt(1.1e-3)) ~ 30.
  require_no_bleeding(rig, 0.1f, 10.f);
}

TEST_CASE("atrous: NaN guides drop the tap instead of poisoning the pixel", "[atrous]") {
  AtrousRig rig(9, 9);
  test::fill_uniform(rig.in, 0.1f, 1.f, 61);
  rig.frame.normal.at(5, 4, 0) = std::numeric_limits<float>::quiet_NaN();
  rig.frame.depth.at(3, 4, 0) = std::numeric_limits<float>::quiet_NaN();
  rig.run(1);
  for (float v : rig.out.data()) REQUIRE(std::isfinite(v));
}

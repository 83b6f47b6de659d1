#include <catch2/catch.hpp>

#include "methods/svgf/variance.h"
#include "kernels_cpu/parallel_for.h"
#include "test_support.h"

using namespace svgf;

namespace {

struct VarianceRig {
  int w, h;
  Frame frame;
  Image accumulated, moments, history, out;
  SvgfParams params;
  VarianceRig(int w_, int h_, float history_length)
      : w(w_), h(h_), frame(test::flat_frame(w_, h_)), accumulated(w_, h_, 4), moments(w_, h_, 2),
        history(w_, h_, 1, history_length), out(w_, h_, 4) {}
  void run() {
    cpu::for_each_pixel(w, h, VarianceKernel{frame.guides(), {accumulated.rgb(), accumulated.plane(3)},
                                             moments.plane(0), moments.plane(1), history.plane(0),
                                             {out.rgb(), out.plane(3)}, params});
  }
};

}  // namespace

TEST_CASE("variance: with history >= 4 the temporal estimate passes through", "[variance]") {
  VarianceRig rig(13, 5, 4.f);
  test::fill_uniform(rig.accumulated, 0.f, 2.f, 21);
  test::fill_uniform(rig.moments, 0.f, 2.f, 22);
  rig.run();
  test::require_identical(rig.out, rig.accumulated, "passthrough");
}

TEST_CASE("variance: young history on a constant image gives zero variance", "[variance]") {
  VarianceRig rig(15, 9, 1.f);
  for (int c = 0; c < 3; ++c) std::fill_n(rig.accumulated.plane(c), 15 * 9, 0.6f);
  const float l = luminance(make_vec3(0.6f, 0.6f, 0.6f));
  std::fill_n(rig.moments.plane(0), 15 * 9, l);
  std::fill_n(rig.moments.plane(1), 15 * 9, l * l);
  rig.run();
  for (int i = 0; i < 15 * 9; ++i) {
    for (int c = 0; c < 3; ++c) REQUIRE(rig.out.plane(c)[i] == Approx(0.6f).epsilon(1e-6));
    REQUIRE(rig.out.plane(3)[i] == Approx(0.f).margin(1e-6));
  }
}

TEST_CASE("variance: the spatial estimate is the moments' variance, boosted by 4/h",
          "[variance]") {
  // Interior pixel of a flat, equal-luminance-weighted region (phi_color huge): the estimate is
  // the plain 7x7 mean of the moments, variance m2 - m1^2, times 4 / history.
  VarianceRig rig(21, 21, 2.f);
  rig.params.phi_color = std::numeric_limits<float>::infinity();
  rig.params.phi_normal = 0.f;
  test::fill_uniform(rig.accumulated, 0.f, 2.f, 23);
  test::fill_uniform(rig.moments, 0.f, 1.f, 24);
  for (int i = 0; i < 21 * 21; ++i) rig.moments.plane(1)[i] += rig.moments.plane(0)[i] * rig.moments.plane(0)[i];
  rig.run();
  double m1 = 0, m2 = 0;
  for (int y = 7; y <= 13; ++y)
    for (int x = 7; x <= 13; ++x) {
      m1 += rig.moments.at(x, y, 0);
      m2 += rig.moments.at(x, y, 1);
    }
  m1 /= 49;
  m2 /= 49;
  REQUIRE(rig.out.at(10, 10, 3) == Approx((m2 - m1 * m1) * 2.0).epsilon(1e-4));
}

TEST_CASE("variance: the spatial estimate does not bleed across a depth edge", "[variance]") {
  VarianceRig rig(20, 6, 1.f);
  for (int y = 0; y < 6; ++y)
    for (int x = 0; x < 20; ++x) {
      const bool right = x >= 10;
      rig.frame.depth.at(x, y, 0) = right ? 6.f : 2.f;
      for (int c = 0; c < 3; ++c) rig.accumulated.at(x, y, c) = right ? 4.f : 0.25f;
      const float l = right ? 4.f : 0.25f;
      rig.moments.at(x, y, 0) = l;
      rig.moments.at(x, y, 1) = l * l;
    }
  rig.run();
  for (int y = 0; y < 6; ++y) {
    REQUIRE(rig.out.at(9, y, 0) == Approx(0.25f).epsilon(1e-5));
    REQUIRE(rig.out.at(10, y, 0) == Approx(4.f).epsilon(1e-5));
    REQUIRE(rig.out.at(9, y, 3) == Approx(0.f).margin(1e-5));
  }
}

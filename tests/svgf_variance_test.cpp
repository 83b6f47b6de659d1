// Stage 3, the variance estimate, on the CPU, CUDA exact and CUDA fast (tests/test_device.h):
// known answers in double, exact to float rounding, fast to its tolerance.
#include <cmath>
#include <limits>
#include <type_traits>
#include <utility>

#include <catch2/catch.hpp>

#include "methods/svgf/variance.h"
#include "svgf_flavor_views.h"
#include "test_device.h"
#include "test_support.h"

using namespace svgf;
using svgf::test::TestDevice;

namespace {

struct VarianceRig {
  test::TestDevice device;
  int w, h;
  Frame frame;
  Image accumulated, moments, history, out;
  SvgfParams params;
  VarianceRig(const test::TestDevice& d, int w_, int h_, float history_length)
      : device(d), w(w_), h(h_), frame(test::flat_frame(w_, h_)), accumulated(w_, h_, 4), moments(w_, h_, 2),
        history(w_, h_, 1, history_length), out(w_, h_, 4) {
    // The paper's estimate (the sample variance); the variance of the mean has its own test.
    params.variance_of_mean = false;
  }
  // The stage as the pipeline runs it, in the device's flavor (exact planes or fast packed).
  void run() {
    test::StageRunner r(device);
    test::with_flavor(device, [&](auto flavor) {
      using Flavor = decltype(flavor);
      Flavor::with_normal_power(params.phi_normal, [&](const auto& power) {
        using Power = std::decay_t<decltype(power)>;
        r.run(VarianceEstimate<Flavor, Power>{test::filter_guides(flavor, r, frame),
                                              r.illum_var(std::as_const(accumulated)),
                                              r.plane(std::as_const(moments), 0),
                                              r.plane(std::as_const(moments), 1),
                                              r.plane(std::as_const(history)),
                                              test::signal(flavor, r, out), params},
              w, h, "variance");
      });
    });
  }
};

}  // namespace

namespace {

void old_history_passes_through(const TestDevice& d) {
  VarianceRig rig(d, 13, 5, 4.f);
  test::fill_uniform(rig.accumulated, 0.f, 2.f, 21);
  test::fill_uniform(rig.moments, 0.f, 2.f, 22);
  rig.run();
  test::require_identical(rig.out, rig.accumulated, "passthrough");
}

void constant_image_zero_variance(const TestDevice& d) {
  VarianceRig rig(d, 15, 9, 1.f);
  for (int c = 0; c < 3; ++c) std::fill_n(rig.accumulated.plane(c), 15 * 9, 0.6f);
  const float l = luminance(make_vec3(0.6f, 0.6f, 0.6f));
  std::fill_n(rig.moments.plane(0), 15 * 9, l);
  std::fill_n(rig.moments.plane(1), 15 * 9, l * l);
  rig.run();
  for (int i = 0; i < 15 * 9; ++i) {
    for (int c = 0; c < 3; ++c) REQUIRE(rig.out.plane(c)[i] == Approx(0.6f).epsilon(d.tolerance(1e-6)));
    REQUIRE(rig.out.plane(3)[i] == Approx(0.f).margin(1e-6));
  }
}

void spatial_estimate_boosted(const TestDevice& d) {
  // Interior pixel of a flat, equal-luminance-weighted region (phi_color huge): the estimate is
  // the plain 7x7 mean of the moments, variance m2 - m1^2, times 4 / history.
  VarianceRig rig(d, 21, 21, 2.f);
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

void no_bleeding_across_depth_edge(const TestDevice& d) {
  VarianceRig rig(d, 20, 6, 1.f);
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
    REQUIRE(rig.out.at(9, y, 0) == Approx(0.25f).epsilon(d.tolerance(1e-5)));
    REQUIRE(rig.out.at(10, y, 0) == Approx(4.f).epsilon(d.tolerance(1e-5)));
    REQUIRE(rig.out.at(9, y, 3) == Approx(0.f).margin(1e-5));
  }
}

void radius_threshold_depth_scale(const TestDevice& d) {
  // Unit luminance and normal weights: each parameter is then seen in a known answer.
  auto rig_for = [&](float history_length) {
    VarianceRig rig(d, 21, 21, history_length);
    rig.params.phi_color = std::numeric_limits<float>::infinity();
    rig.params.phi_normal = 0.f;
    test::fill_uniform(rig.accumulated, 0.f, 2.f, 31);
    test::fill_uniform(rig.moments, 0.f, 1.f, 32);
    for (int i = 0; i < 21 * 21; ++i)
      rig.moments.plane(1)[i] += rig.moments.plane(0)[i] * rig.moments.plane(0)[i];
    return rig;
  };
  auto mean_variance = [](const VarianceRig& rig, int r, double boost) {
    double m1 = 0, m2 = 0;
    const int n = (2 * r + 1) * (2 * r + 1);
    for (int y = 10 - r; y <= 10 + r; ++y)
      for (int x = 10 - r; x <= 10 + r; ++x) {
        m1 += rig.moments.at(x, y, 0);
        m2 += rig.moments.at(x, y, 1);
      }
    m1 /= n;
    m2 /= n;
    return (m2 - m1 * m1) * boost;
  };
  SECTION("spatial_variance_radius sets the footprint (2r+1)^2") {
    for (int r : {1, 2, 3}) {
      VarianceRig rig = rig_for(2.f);
      rig.params.spatial_variance_radius = r;
      rig.run();
      INFO("radius " << r);
      REQUIRE(rig.out.at(10, 10, 3) == Approx(mean_variance(rig, r, 2.0)).epsilon(1e-4));
    }
  }
  SECTION("spatial_variance_history is the threshold and the boost's numerator") {
    VarianceRig rig = rig_for(5.f);  // history 5: temporal by default (threshold 4)
    rig.run();
    REQUIRE(rig.out.at(10, 10, 3) == rig.accumulated.at(10, 10, 3));
    rig.params.spatial_variance_history = 8;  // now young: spatial, boosted by 8 / 5
    rig.run();
    REQUIRE(rig.out.at(10, 10, 3) == Approx(mean_variance(rig, 3, 8.0 / 5.0)).epsilon(1e-4));
  }
  SECTION("spatial_variance_phi_depth scales the depth tolerance") {
    // A depth ramp of 0.1 a pixel with fwidth 0.1: a tap d pixels away along x has
    // |dz| / (phi * fwidth * |d|) = 1 / phi, so each weight is exp(-1/phi) off the centre's
    // column: the weighted mean is a known blend, different for each phi.
    for (float phi : {0.5f, 3.f}) {
      VarianceRig rig = rig_for(2.f);
      rig.params.spatial_variance_phi_depth = phi;
      for (int y = 0; y < 21; ++y)
        for (int x = 0; x < 21; ++x) {
          rig.frame.depth.at(x, y, 0) = 2.f + 0.1f * x;
          rig.frame.depth_gradient.at(x, y, 0) = 0.1f;
        }
      rig.run();
      // Weight of tap (dx, dy): exp(-|dx| / (phi * sqrt(dx^2 + dy^2))) (1 at the centre).
      double ws = 0, m1 = 0, m2 = 0;
      for (int dy = -3; dy <= 3; ++dy)
        for (int dx = -3; dx <= 3; ++dx) {
          const double d = std::sqrt(double(dx * dx + dy * dy));
          const double w = d == 0 ? 1.0 : std::exp(-std::abs(dx) / (phi * d));
          ws += w;
          m1 += w * rig.moments.at(10 + dx, 10 + dy, 0);
          m2 += w * rig.moments.at(10 + dx, 10 + dy, 1);
        }
      m1 /= ws;
      m2 /= ws;
      INFO("phi " << phi);
      REQUIRE(rig.out.at(10, 10, 3) == Approx((m2 - m1 * m1) * 2.0).epsilon(1e-4));
    }
  }
}

// With variance_of_mean on, the variance passed on is the paper's estimate / n for
// n = min(history, (2 - alpha) / alpha), in the temporal and in the spatial branch.
void variance_of_the_mean(const TestDevice& d) {
  struct Case {
    float history, alpha, n;
  };
  // n below, at and above the cap (2 - alpha) / alpha; alpha 0.5 caps it at 3 (history 8).
  for (const Case c : {Case{5.f, 0.03f, 5.f}, Case{40.f, 0.03f, 40.f},
                       Case{80.f, 0.03f, (2.f - 0.03f) / 0.03f}, Case{8.f, 0.5f, 3.f},
                       Case{2.f, 0.03f, 2.f}, Case{1.f, 0.03f, 1.f}}) {
    VarianceRig paper(d, 21, 21, c.history);
    paper.params.alpha = c.alpha;
    test::fill_uniform(paper.accumulated, 0.f, 2.f, 31);
    test::fill_uniform(paper.moments, 0.f, 1.f, 32);
    for (int i = 0; i < 21 * 21; ++i)
      paper.moments.plane(1)[i] += paper.moments.plane(0)[i] * paper.moments.plane(0)[i];
    VarianceRig mean = paper;
    mean.params.variance_of_mean = true;
    paper.run();
    mean.run();
    INFO("history " << c.history << ", alpha " << c.alpha);
    for (int i = 0; i < 21 * 21; ++i) {
      // Same colors; the variance divided by n (one extra rounding).
      for (int ch = 0; ch < 3; ++ch) REQUIRE(mean.out.plane(ch)[i] == paper.out.plane(ch)[i]);
      REQUIRE(mean.out.plane(3)[i] ==
              Approx(paper.out.plane(3)[i] / c.n).epsilon(d.tolerance(2e-7)).margin(1e-30));
    }
  }
}

}  // namespace

SVGF_DEVICE_TEST("variance: variance_of_mean divides by min(history, (2 - alpha) / alpha)",
                 "[variance]", variance_of_the_mean)
SVGF_DEVICE_TEST("variance: with history >= 4 the temporal estimate passes through",
                 "[variance]", old_history_passes_through)
SVGF_DEVICE_TEST("variance: young history on a constant image gives zero variance",
                 "[variance]", constant_image_zero_variance)
SVGF_DEVICE_TEST("variance: the spatial estimate is the moments' variance, boosted by 4/h",
                 "[variance]", spatial_estimate_boosted)
SVGF_DEVICE_TEST("variance: the spatial estimate does not bleed across a depth edge",
                 "[variance]", no_bleeding_across_depth_edge)
SVGF_DEVICE_TEST("variance: the radius, the young-history threshold and the depth tolerance's scale",
                 "[variance]", radius_threshold_depth_scale)

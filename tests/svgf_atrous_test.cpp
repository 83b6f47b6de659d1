// Stage 4, the a-trous iterations, on the CPU, CUDA exact and CUDA fast (tests/test_device.h):
// known answers in double, exact to float rounding, fast to its tolerance. The prefilter and
// the weight function are also checked alone, on the host.
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <catch2/catch.hpp>

#include "methods/svgf/atrous.h"
#include "svgf_flavor_views.h"
#include "test_device.h"
#include "test_support.h"

using namespace svgf;
using svgf::test::TestDevice;

namespace {

struct AtrousRig {
  test::TestDevice device;
  int w, h;
  Frame frame;
  Image in, out;
  SvgfParams params;
  AtrousRig(const test::TestDevice& d, int w_, int h_)
      : device(d), w(w_), h(h_), frame(test::flat_frame(w_, h_)), in(w_, h_, 4), out(w_, h_, 4) {}
  // One iteration as the pipeline runs it, in the device's flavor (exact planes or fast
  // packed pixels).
  void run(int step) {
    test::StageRunner r(device);
    test::with_flavor(device, [&](auto flavor) {
      using Flavor = decltype(flavor);
      Flavor::with_normal_power(params.phi_normal, [&](const auto& power) {
        using Power = std::decay_t<decltype(power)>;
        r.run(AtrousIteration<Flavor, Power>{test::filter_guides(flavor, r, frame),
                                             test::signal(flavor, r, std::as_const(in)),
                                             test::signal(flavor, r, out), step, params},
              w, h, "atrous");
      });
    });
  }
};

using svgf::test::kInf;

void atrous_constant_stays_constant(const TestDevice& d) {
  for (int step : {1, 2, 4, 8, 16}) {
    AtrousRig rig(d, 37, 23);
    for (int c = 0; c < 3; ++c) std::fill_n(rig.in.plane(c), 37 * 23, 1.7f);
    std::fill_n(rig.in.plane(3), 37 * 23, 0.01f);
    rig.run(step);
    for (int i = 0; i < 37 * 23; ++i)
      for (int c = 0; c < 3; ++c) REQUIRE(rig.out.plane(c)[i] == Approx(1.7f).epsilon(d.tolerance(3e-7)));
  }
}

void variance_with_squared_weights(const TestDevice& d) {
  AtrousRig rig(d, 15, 15);
  rig.params.phi_color = kInf;  // every edge-stopping weight is exactly 1
  rig.params.phi_normal = 0.f;
  test::fill_uniform(rig.in, 0.1f, 1.f, 31);
  std::fill_n(rig.in.plane(3), 15 * 15, 0.5f);
  rig.run(1);
  // sum k^2 = (3/8^2 + 2 (1/4)^2 + 2 (1/16)^2)^2 = 0.2734375^2, sum k = 1: both exact.
  REQUIRE(rig.out.at(7, 7, 3) == Approx(0.5 * 0.2734375 * 0.2734375).epsilon(d.tolerance(1e-6)));
  // The color is the B3-weighted mean of the 5x5 neighbourhood.
  double expect = 0;
  for (int dy = -2; dy <= 2; ++dy)
    for (int dx = -2; dx <= 2; ++dx)
      expect += double(b3_weight(std::abs(dx))) * b3_weight(std::abs(dy)) * rig.in.at(7 + dx, 7 + dy, 0);
  REQUIRE(rig.out.at(7, 7, 0) == Approx(expect).epsilon(d.tolerance(1e-6)));
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

void flat_region_keeps_mean(const TestDevice& d) {
  AtrousRig rig(d, 64, 64);
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

void no_bleeding_across_depth(const TestDevice& d) {
  AtrousRig rig(d, 20, 8);
  rig.params.phi_color = kInf;  // only the depth term can stop the filter
  for (int y = 0; y < 8; ++y)
    for (int x = 10; x < 20; ++x) rig.frame.depth.at(x, y, 0) = 3.f;
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 20; ++x) rig.frame.depth_gradient.at(x, y, 0) = 1e-3f;
  require_no_bleeding(rig, 0.2f, 0.8f);
}

void no_bleeding_across_normal(const TestDevice& d) {
  AtrousRig rig(d, 20, 8);
  rig.params.phi_color = kInf;
  for (int y = 0; y < 8; ++y)
    for (int x = 10; x < 20; ++x) {
      rig.frame.normal.at(x, y, 0) = 0.6f;  // 53 degrees apart: 0.8^128 ~ 4e-13
      rig.frame.normal.at(x, y, 2) = 0.8f;
    }
  require_no_bleeding(rig, 0.2f, 0.8f);
}

void no_bleeding_across_luminance(const TestDevice& d) {
  AtrousRig rig(d, 20, 8);  // same depth and normal everywhere: only luminance separates
  // Luminance 0.1 vs 10 with variance 1e-3: |dl| / phi_l = 9.9 / (10 sqrt(1.1e-3)) ~ 30.
  require_no_bleeding(rig, 0.1f, 10.f);
}

void nan_guides_drop_the_tap(const TestDevice& d) {
  AtrousRig rig(d, 9, 9);
  test::fill_uniform(rig.in, 0.1f, 1.f, 61);
  rig.frame.normal.at(5, 4, 0) = std::numeric_limits<float>::quiet_NaN();
  rig.frame.depth.at(3, 4, 0) = std::numeric_limits<float>::quiet_NaN();
  rig.run(1);
  for (float v : rig.out.data()) REQUIRE(std::isfinite(v));
}


// An independent double-precision a-trous iteration (paper Eq. 1-5, Falcor's weights): the
// reference every parameter is pinned against below. Written from the formulas, not from
// methods/svgf/: B3 spline, 3x3 Gaussian prefilter renormalized at the border, luminance sigma
// phi_color * sqrt(eps + variance), depth sigma phi_depth * max(fwidth, floor) * |tap| * step
// (phi_depth 0: no depth term), normal weight clamp(n.n', 0, 1)^phi_normal.
Image reference_atrous(const Frame& f, const Image& in, int step, const SvgfParams& p) {
  const int w = f.width(), h = f.height();
  const double b3[3] = {3.0 / 8, 1.0 / 4, 1.0 / 16};
  const double g3[2] = {0.5, 0.25};
  auto lum = [&](int x, int y) {
    return 0.2126 * in.at(x, y, 0) + 0.7152 * in.at(x, y, 1) + 0.0722 * in.at(x, y, 2);
  };
  Image out(w, h, 4);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (!(f.depth.at(x, y, 0) > 0)) {
        for (int c = 0; c < 4; ++c) out.at(x, y, c) = in.at(x, y, c);
        continue;
      }
      double vs = 0, ks = 0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          if (x + dx < 0 || y + dy < 0 || x + dx >= w || y + dy >= h) continue;
          const double k = g3[std::abs(dx)] * g3[std::abs(dy)];
          vs += k * in.at(x + dx, y + dy, 3);
          ks += k;
        }
      const double sigma_l = p.phi_color * std::sqrt(std::max(0.0, p.variance_epsilon + vs / ks));
      const double fw = std::max(std::fabs(double(f.depth_gradient.at(x, y, 0))),
                                 std::fabs(double(f.depth_gradient.at(x, y, 1))));
      const double sigma_z = p.phi_depth * std::max(fw, double(p.depth_gradient_floor));
      double ws = 0, cs[3] = {0, 0, 0}, var = 0;
      for (int dy = -2; dy <= 2; ++dy)
        for (int dx = -2; dx <= 2; ++dx) {
          const int xq = x + dx * step, yq = y + dy * step;
          if (xq < 0 || yq < 0 || xq >= w || yq >= h) continue;
          const double k = b3[std::abs(dx)] * b3[std::abs(dy)];
          double wt = k;
          if (dx != 0 || dy != 0) {
            double cosine = 0;
            for (int c = 0; c < 3; ++c)
              cosine += double(f.normal.at(x, y, c)) * f.normal.at(xq, yq, c);
            cosine = std::min(1.0, std::max(0.0, cosine));
            const double dist = std::sqrt(double(dx * dx + dy * dy)) * step;
            const double e_z =
                p.phi_depth == 0
                    ? 0.0
                    : std::fabs(double(f.depth.at(x, y, 0)) - f.depth.at(xq, yq, 0)) /
                          (sigma_z * dist);
            const double e_l = std::fabs(lum(x, y) - lum(xq, yq)) / sigma_l;
            wt = k * std::exp(-e_l - e_z) * std::pow(cosine, double(p.phi_normal));
          }
          ws += wt;
          for (int c = 0; c < 3; ++c) cs[c] += wt * in.at(xq, yq, c);
          var += wt * wt * in.at(xq, yq, 3);
        }
      for (int c = 0; c < 3; ++c) out.at(x, y, c) = static_cast<float>(cs[c] / ws);
      out.at(x, y, 3) = static_cast<float>(var / (ws * ws));
    }
  return out;
}


void every_parameter_role(const TestDevice& d) {
  // A tilted plane (depth changes by 0.05 and 0.08 per pixel, the gradient says so), normals
  // near +z some of them slightly longer than 1 (as half-float storage leaves them), noisy
  // color and variance. Each parameter set moves one parameter far from its default; a value
  // used in the wrong role, at the wrong step scale or not at all moves the output by far more
  // than the float rounding the tolerance allows.
  const int w = 23, h = 19;
  AtrousRig rig(d, w, h);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.f, 1.f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      rig.frame.depth.at(x, y, 0) = 2.f + 0.05f * x + 0.08f * y;
      rig.frame.depth_gradient.at(x, y, 0) = 0.05f;
      rig.frame.depth_gradient.at(x, y, 1) = 0.08f;
      const float nx = 0.1f * u(rng), ny = 0.1f * u(rng);
      const float len = std::sqrt(nx * nx + ny * ny + 1.f) / (1.f + 0.0002f * (u(rng) + 1.f));
      rig.frame.normal.at(x, y, 0) = nx / len;
      rig.frame.normal.at(x, y, 1) = ny / len;
      rig.frame.normal.at(x, y, 2) = 1.f / len;
    }
  test::fill_uniform(rig.in, 0.2f, 2.f, 17);
  for (int i = 0; i < w * h; ++i) rig.in.plane(3)[i] *= 0.05f;
  rig.frame.depth.at(4, 4, 0) = 0.f;  // one background pixel: passes through

  std::vector<std::pair<std::string, SvgfParams>> sets;
  sets.emplace_back("defaults", SvgfParams());
  auto with = [&](const std::string& name, auto change) {
    SvgfParams p;
    change(p);
    sets.emplace_back(name, p);
  };
  with("phi_color 2", [](SvgfParams& p) { p.phi_color = 2.f; });
  with("phi_normal 16", [](SvgfParams& p) { p.phi_normal = 16.f; });
  with("phi_normal 300 (not a power of 2)", [](SvgfParams& p) { p.phi_normal = 300.f; });
  with("phi_depth 0.2", [](SvgfParams& p) { p.phi_depth = 0.2f; });
  with("phi_depth 0 (no depth term)", [](SvgfParams& p) { p.phi_depth = 0.f; });
  with("variance_epsilon 0.5", [](SvgfParams& p) { p.variance_epsilon = 0.5f; });
  with("depth_gradient_floor 1", [](SvgfParams& p) { p.depth_gradient_floor = 1.f; });
  for (const auto& [name, p] : sets)
    for (int step : {1, 2, 4}) {
      rig.params = p;
      rig.run(step);
      const Image want = reference_atrous(rig.frame, rig.in, step, p);
      double worst = 0;
      for (size_t i = 0; i < want.data().size(); ++i)
        worst = std::max(worst, std::fabs(double(rig.out.data()[i]) - want.data()[i]) /
                                    std::max(1e-3, std::fabs(double(want.data()[i]))));
      INFO(name << ", step " << step << ": worst relative difference " << worst);
      REQUIRE(worst < d.tolerance(2e-5));
    }
}

TEST_CASE("atrous: the normal weight is capped at 1 for normals a little longer than 1", "[atrous]") {
  // |n| = 1.0002 (half-float storage): uncapped, (n.n)^128 = 1.05 would weigh a neighbour above
  // the centre's own edge-stopping weight of 1.
  const Vec3 n = make_vec3(0.f, 0.f, 1.0002f);
  const EdgeSample c{2.f, n, 0.5f}, q{2.f, n, 0.5f};
  REQUIRE(edge_stopping_weight(c, q, 1.f, 128.f, 1.f) == 1.f);
  REQUIRE(edge_stopping_weight(c, q, 1.f, 100.f, 1.f) == 1.f);  // the det_pow path too
}

}  // namespace

SVGF_DEVICE_TEST("atrous: a constant image stays constant at every step",
                 "[atrous]", atrous_constant_stays_constant)
SVGF_DEVICE_TEST("atrous: known answer for the variance, filtered with squared weights",
                 "[atrous]", variance_with_squared_weights)
SVGF_DEVICE_TEST("atrous: a flat noisy region keeps its mean", "[atrous]", flat_region_keeps_mean)
SVGF_DEVICE_TEST("atrous: weights fall to ~0 across a depth edge",
                 "[atrous]", no_bleeding_across_depth)
SVGF_DEVICE_TEST("atrous: weights fall to ~0 across a normal edge",
                 "[atrous]", no_bleeding_across_normal)
SVGF_DEVICE_TEST("atrous: weights fall to ~0 across a luminance edge",
                 "[atrous]", no_bleeding_across_luminance)
SVGF_DEVICE_TEST("atrous: NaN guides drop the tap instead of poisoning the pixel",
                 "[atrous]", nan_guides_drop_the_tap)
SVGF_DEVICE_TEST("atrous: every parameter's role, against a double-precision reference",
                 "[atrous]", every_parameter_role)

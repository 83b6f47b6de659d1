// Known answers added by the planted-bug check (docs/svgf.md, "Planted-bug check") for the
// Gaussian baseline: the default parameters as the denoiser uses them, and the radius rule
// ceil(3 sigma) where 3 sigma is not an integer. Expected values are computed in double from
// constants written out here.
#include <cmath>
#include <vector>

#include <catch2/catch.hpp>

#include "methods/gaussian/denoiser.h"
#include "pipeline/make_denoiser.h"
#include "test_support.h"

using namespace svgf;

namespace {

// The response to a unit impulse at (cx, cy) of a Gaussian denoiser configured by `c`.
Image impulse_response(DenoiserConfig c, int n, int cx, int cy) {
  c.method = Method::Gaussian;
  c.backend = Backend::Cpu;
  c.threads = 2;
  Frame f = test::flat_frame(n, n);
  for (int ch = 0; ch < 3; ++ch) f.color.at(cx, cy, ch) = 1.f;
  auto d = make_denoiser(c);
  Image out;
  d->denoise(f, out);
  return out;
}

// Requires out(x, y) = g(x - cx) g(y - cy) with g the normalized exp(-k^2 / (2 sigma^2)) over
// |k| <= radius, and 0 outside.
void require_separable_kernel(const Image& out, int cx, int cy, double sigma, int radius) {
  std::vector<double> g;
  double sum = 0;
  for (int k = -radius; k <= radius; ++k) {
    g.push_back(std::exp(-double(k) * k / (2 * sigma * sigma)));
    sum += g.back();
  }
  for (double& v : g) v /= sum;
  for (int y = 0; y < out.height(); ++y)
    for (int x = 0; x < out.width(); ++x) {
      const int dx = x - cx, dy = y - cy;
      const double want =
          (std::abs(dx) <= radius && std::abs(dy) <= radius) ? g[dx + radius] * g[dy + radius] : 0.0;
      INFO("sigma " << sigma << " radius " << radius << " at (" << x << "," << y << ")");
      REQUIRE(std::fabs(out.at(x, y, 1) - want) <= 4e-6 * want + 1e-12);
    }
}

}  // namespace

TEST_CASE("params: a default-configured Gaussian blurs with sigma 2 over 6 taps either side",
          "[params][gaussian]") {
  // No sigma or radius given: the documented defaults sigma = 2, radius = 0, i.e. ceil(3 * 2) = 6.
  require_separable_kernel(impulse_response(DenoiserConfig(), 31, 15, 15), 15, 15, 2.0, 6);
}

TEST_CASE("params: the Gaussian radius rule is ceil(3 sigma), also where 3 sigma is not whole",
          "[params][gaussian]") {
  // 3 * 2.1 = 6.3 -> 7 taps either side; 3 * 0.9 = 2.7 -> 3; 3 * 1.2 = 3.6 -> 4.
  for (const auto& [sigma, radius] : {std::pair<float, int>{2.1f, 7}, {0.9f, 3}, {1.2f, 4}}) {
    DenoiserConfig c;
    c.gaussian.sigma = sigma;
    c.gaussian.radius = 0;
    require_separable_kernel(impulse_response(c, 31, 15, 15), 15, 15, sigma, radius);
  }
}

// The Gaussian baseline (methods/gaussian/) through the public interface: known answers that pin
// sigma, radius and the border rule, and bad samples, on the CPU, CUDA exact and CUDA fast
// (tests/test_device.h); CPU thread determinism and configuration errors.
#include <cmath>
#include <limits>
#include <vector>

#include <catch2/catch.hpp>

#include "methods/gaussian/denoiser.h"
#include "pipeline/make_denoiser.h"
#include "test_device.h"
#include "test_support.h"

using namespace svgf;
using svgf::test::kCpu;
using svgf::test::TestDevice;

namespace {

DenoiserConfig gaussian_config(const TestDevice& d, float sigma, int radius, int threads = 2) {
  DenoiserConfig c = d.config(DenoiserConfig());
  c.method = Method::Gaussian;
  c.threads = threads;
  c.gaussian.sigma = sigma;
  c.gaussian.radius = radius;
  return c;
}

Image blur(const TestDevice& device, const Frame& f, float sigma, int radius, int threads = 2) {
  auto d = make_denoiser(gaussian_config(device, sigma, radius, threads));
  Image out;
  d->denoise(f, out);
  return out;
}

// The 1-D kernel in double: exp(-k^2 / (2 sigma^2)) for the taps in [lo, hi], normalized.
std::vector<double> kernel_1d(double sigma, int radius) {
  std::vector<double> w;
  double sum = 0;
  for (int k = -radius; k <= radius; ++k) {
    w.push_back(std::exp(-double(k) * k / (2 * sigma * sigma)));
    sum += w.back();
  }
  for (double& v : w) v /= sum;
  return w;
}

void impulse_response(const TestDevice& d) {
  // An impulse far from the borders: out(x, y) = g(x - cx) g(y - cy), which pins both sigma and
  // radius (a wrong radius truncates or widens the support, a wrong sigma changes every value).
  for (const auto& [sigma, radius] : {std::pair<float, int>{2.f, 0}, {1.3f, 3}, {3.f, 5}}) {
    const int n = 41, cx = 20, cy = 20;
    Frame f = test::flat_frame(n, n);
    for (int c = 0; c < 3; ++c) f.color.at(cx, cy, c) = 1.f;
    const Image out = blur(d, f, sigma, radius);
    const int r = radius > 0 ? radius : static_cast<int>(std::ceil(3 * sigma));
    const std::vector<double> g = kernel_1d(sigma, r);
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const int dx = x - cx, dy = y - cy;
        const double want = (std::abs(dx) <= r && std::abs(dy) <= r) ? g[dx + r] * g[dy + r] : 0.0;
        INFO("sigma " << sigma << " radius " << radius << " at (" << x << "," << y << ")");
        REQUIRE(std::fabs(out.at(x, y, 1) - want) <= d.tolerance(1e-6) * want + 1e-12);
      }
  }
}

void constant_stays_constant(const TestDevice& d) {
  Frame f = test::flat_frame(23, 9);
  for (float& v : f.color.data()) v = 0.7f;
  const Image out = blur(d, f, 2.f, 0);
  for (float v : out.data()) REQUIRE(v == Approx(0.7f).epsilon(d.tolerance(1e-6)));
}

void corner_taps_inside(const TestDevice& d) {
  // A ramp along x: at the left border the missing taps are skipped, so the result is the
  // weighted mean of the inside taps, not pulled toward 0 by zero padding.
  const float sigma = 1.5f;
  const int r = 5, w = 16, h = 16;
  Frame f = test::flat_frame(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) f.color.at(x, y, c) = static_cast<float>(x);
  const Image out = blur(d, f, sigma, r);
  double num = 0, den = 0;
  for (int k = 0; k <= r; ++k) {
    const double wk = std::exp(-double(k) * k / (2.0 * sigma * sigma));
    num += wk * k;
    den += wk;
  }
  REQUIRE(out.at(0, 0, 0) == Approx(num / den).epsilon(d.tolerance(1e-5)));
  REQUIRE(out.at(0, h - 1, 2) == Approx(num / den).epsilon(d.tolerance(1e-5)));
}

void bad_samples_replaced(const TestDevice& device) {
  Frame f = test::flat_frame(12, 10);
  for (float& v : f.color.data()) v = 1.f;
  f.color.at(3, 4, 0) = std::numeric_limits<float>::quiet_NaN();
  f.color.at(5, 5, 1) = std::numeric_limits<float>::infinity();
  f.color.at(8, 2, 2) = -2.f;
  auto d = make_denoiser(gaussian_config(device, 2.f, 0));
  Image out;
  d->denoise(f, out);
  REQUIRE(d->last_report().replaced_samples == 3);
  for (float v : out.data()) REQUIRE(std::isfinite(v));
  REQUIRE(out.at(3, 4, 0) < 1.f);  // the replaced 0 pulled its neighbourhood down
}

}  // namespace

SVGF_DEVICE_TEST("gaussian: the impulse response is the separable normalized kernel",
                 "[gaussian]", impulse_response)
SVGF_DEVICE_TEST("gaussian: a constant image stays constant, borders renormalized", "[gaussian]",
                 constant_stays_constant)
SVGF_DEVICE_TEST("gaussian: at a corner only the taps inside count", "[gaussian]",
                 corner_taps_inside)
SVGF_DEVICE_TEST("gaussian: NaN, Inf and negative color are replaced by 0 and counted",
                 "[gaussian]", bad_samples_replaced)

TEST_CASE("gaussian: same bits on 1 and 2 threads, stages and buffers by name", "[gaussian]") {
  Frame f = test::flat_frame(37, 23);
  test::fill_uniform(f.color, 0.f, 4.f, 5u);
  test::require_identical(blur(kCpu, f, 2.f, 0, 1), blur(kCpu, f, 2.f, 0, 2), "1 vs 2 threads");
  auto d = make_denoiser(gaussian_config(kCpu, 2.f, 0));
  REQUIRE(d->description().rfind("gaussian cpu exact", 0) == 0);
  REQUIRE(d->stages() == std::vector<std::string>{"sanitize", "blur_x", "blur_y"});
  REQUIRE(d->read_buffer("blurred_x").empty());  // before the first frame
  Image out;
  d->denoise(f, out);
  REQUIRE(d->last_report().times["blur_x"] > 0);
  REQUIRE_THROWS_WITH(d->read_buffer("moments"), Catch::Contains("no debug buffer 'moments'"));
}

TEST_CASE("gaussian: bad parameters and fast mode on the CPU are clear errors", "[gaussian]") {
  REQUIRE_THROWS_WITH(make_denoiser(gaussian_config(kCpu, 0.f, 0)), Catch::Contains("--sigma"));
  REQUIRE_THROWS_WITH(make_denoiser(gaussian_config(kCpu, 2.f, -1)), Catch::Contains("--radius"));
  DenoiserConfig fast = gaussian_config(kCpu, 2.f, 0);
  fast.mode = Mode::Fast;
  REQUIRE_THROWS_WITH(make_denoiser(fast), Catch::Contains("fast mode"));
  REQUIRE(parse_method("gaussian") == Method::Gaussian);
  REQUIRE_THROWS_WITH(parse_method("oidn"), Catch::Contains("known: svgf, gaussian"));
}

// The CIS 565 wavelet filter (methods/wavelet/): each stage against a double-precision
// reference written from the formulas of docs/wavelet.md (not from the code), edge stopping,
// bad samples, and the whole filter through make_denoiser; every body on the CPU, CUDA exact
// and CUDA fast (tests/test_device.h).
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <catch2/catch.hpp>

#include "methods/wavelet/atrous.h"
#include "methods/wavelet/deviation.h"
#include "methods/wavelet/denoiser.h"
#include "pipeline/make_denoiser.h"
#include "test_device.h"
#include "test_support.h"

using namespace svgf;
using svgf::test::StageRunner;
using svgf::test::TestDevice;
using svgf::test::with_arith;

namespace {

// A tilted, bumpy surface: depth 2 + 0.05 x + 0.08 y, normals within ~6 degrees of +z (some a
// little longer than 1, as half floats leave them), one background pixel.
Frame wavelet_bumpy_frame(int w, int h, uint32_t seed) {
  Frame f = test::flat_frame(w, h);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.f, 1.f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      f.depth.at(x, y, 0) = 2.f + 0.05f * x + 0.08f * y;
      const float nx = 0.1f * u(rng), ny = 0.1f * u(rng);
      const float len = std::sqrt(nx * nx + ny * ny + 1.f) / (1.f + 0.0002f * (u(rng) + 1.f));
      f.normal.at(x, y, 0) = nx / len;
      f.normal.at(x, y, 1) = ny / len;
      f.normal.at(x, y, 2) = 1.f / len;
    }
  f.depth.at(3, 2, 0) = 0.f;
  return f;
}

// Binomial row of `size` taps, in double.
double binomial(int size, int d) {
  double c = 1;
  const int n = size - 1, k = d + n / 2;
  for (int i = 1; i <= k; ++i) c = c * (n - i + 1) / i;
  return c / std::pow(2.0, n);
}

// One pass in double (docs/wavelet.md): W = exp(-|dZ|/(sZ+eps) - |dL|/(sL Dev+eps)) *
// clamp(N.N', 0, 1)^sN, binomial h, taps outside skipped, background passes through.
Image reference_pass(const Frame& f, const Image& in, const Image& luma, const Image& dev,
                     int step, const WaveletParams& p) {
  const int w = f.width(), h = f.height(), r = p.kernel_size / 2;
  Image out(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (!(f.depth.at(x, y, 0) > 0)) {
        for (int c = 0; c < 3; ++c) out.at(x, y, c) = in.at(x, y, c);
        continue;
      }
      double ws = 0, cs[3] = {0, 0, 0};
      for (int dy = -r; dy <= r; ++dy)
        for (int dx = -r; dx <= r; ++dx) {
          const int xq = x + dx * step, yq = y + dy * step;
          if (xq < 0 || yq < 0 || xq >= w || yq >= h) continue;
          double wt = binomial(p.kernel_size, dx) * binomial(p.kernel_size, dy);
          if (dx != 0 || dy != 0) {
            double cosine = 0;
            for (int c = 0; c < 3; ++c) cosine += double(f.normal.at(x, y, c)) * f.normal.at(xq, yq, c);
            cosine = std::min(1.0, std::max(0.0, cosine));
            const double ez = std::fabs(double(f.depth.at(x, y, 0)) - f.depth.at(xq, yq, 0)) /
                              (double(p.sigma_depth) + p.epsilon);
            const double el = std::fabs(double(luma.at(x, y, 0)) - luma.at(xq, yq, 0)) /
                              (double(p.sigma_luma) * dev.at(x, y, 0) + p.epsilon);
            wt *= std::exp(-ez - el) * std::pow(cosine, double(p.sigma_normal));
          }
          ws += wt;
          for (int c = 0; c < 3; ++c) cs[c] += wt * in.at(xq, yq, c);
        }
      for (int c = 0; c < 3; ++c) out.at(x, y, c) = static_cast<float>(cs[c] / ws);
    }
  return out;
}

void wavelet_pass_against_double(const TestDevice& d) {
  const int w = 29, h = 23;
  const Frame f = wavelet_bumpy_frame(w, h, 3);
  Image in(w, h, 3), luma(w, h, 1), dev(w, h, 1), out(w, h, 3);
  test::fill_uniform(in, 0.2f, 2.f, 5);
  for (int i = 0; i < w * h; ++i)
    luma.plane(0)[i] = 0.299f * in.plane(0)[i] + 0.587f * in.plane(1)[i] + 0.114f * in.plane(2)[i];
  test::fill_uniform(dev, 0.01f, 1.f, 7);
  // Each setting moves one parameter far from its default: a value in the wrong role, at the
  // wrong step or not used at all moves the result far beyond the tolerance.
  std::vector<std::pair<std::string, WaveletParams>> sets;
  auto with = [&](const std::string& name, auto change) {
    WaveletParams p;
    change(p);
    sets.emplace_back(name, p);
  };
  with("defaults", [](WaveletParams&) {});
  for (int k : {3, 7, 9}) with("kernel " + std::to_string(k), [k](WaveletParams& p) { p.kernel_size = k; });
  with("sigma_depth 0.05", [](WaveletParams& p) { p.sigma_depth = 0.05f; });
  with("sigma_normal 300", [](WaveletParams& p) { p.sigma_normal = 300.f; });
  with("sigma_normal 0", [](WaveletParams& p) { p.sigma_normal = 0.f; });
  with("sigma_luma 0.3", [](WaveletParams& p) { p.sigma_luma = 0.3f; });
  with("epsilon 0.5", [](WaveletParams& p) { p.epsilon = 0.5f; });
  for (const auto& set : sets)
    for (int step : {1, 2, 4}) {
      const std::string& name = set.first;
      const WaveletParams& p = set.second;
      StageRunner r(d);
      with_arith(d, [&](auto arith) {
        using Arith = decltype(arith);
        using Power = NormalPower<Arith>;
        r.run(WaveletIteration<Arith, Power>{r.guides(f), r.rgb(std::as_const(in)), r.rgb(out),
                                             r.plane(std::as_const(luma)),
                                             r.plane(std::as_const(dev)), step, p.kernel_size,
                                             1.f / (p.sigma_depth + p.epsilon), p.sigma_luma,
                                             p.epsilon, Power::of(p.sigma_normal)},
              w, h, "wavelet pass");
      });
      const double worst =
          test::max_relative_difference(out, reference_pass(f, in, luma, dev, step, p), 1e-3);
      INFO(name << ", step " << step << ": worst relative difference " << worst);
      REQUIRE(worst < d.tolerance(2e-5));
    }
}

void deviation_against_double(const TestDevice& d) {
  // Dev = clamp(g3x3(sqrt(|mean3x3(L^2) - mean3x3(L)^2|)), eps, 1), borders renormalized.
  for (const float eps : {0.01f, 0.2f}) {
    const int w = 13, h = 9;
    Image luma(w, h, 1), spread(w, h, 1), dev(w, h, 1);
    test::fill_uniform(luma, 0.f, 3.f, 11);
    luma.at(6, 4, 0) = 40.f;  // a firefly: spread far above 1, clamped
    for (int y = 0; y < 5; ++y)  // a flat corner: spread 0, clamped to eps
      for (int x = 0; x < 5; ++x) luma.at(x, y, 0) = 1.25f;
    StageRunner r(d);
    r.run(WaveletSpreadKernel{w, h, r.plane(std::as_const(luma)), r.plane(spread)}, w, h);
    r.run(WaveletDeviationKernel{w, h, r.plane(std::as_const(spread)), r.plane(dev), eps}, w, h);
    std::vector<double> s(w * h);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        double m1 = 0, m2 = 0;
        int n = 0;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int xq = x + dx, yq = y + dy;
            if (xq < 0 || yq < 0 || xq >= w || yq >= h) continue;
            m1 += luma.at(xq, yq, 0);
            m2 += double(luma.at(xq, yq, 0)) * luma.at(xq, yq, 0);
            ++n;
          }
        s[y * w + x] = std::sqrt(std::fabs(m2 / n - (m1 / n) * (m1 / n)));
      }
    int clamped_low = 0, clamped_high = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        double sum = 0, weight = 0;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int xq = x + dx, yq = y + dy;
            if (xq < 0 || yq < 0 || xq >= w || yq >= h) continue;
            const double k = (dx == 0 ? 2 : 1) * (dy == 0 ? 2 : 1) / 16.0;
            sum += k * s[yq * w + xq];
            weight += k;
          }
        const double g = sum / weight;
        const double want = std::min(std::max(g, double(eps)), 1.0);
        clamped_low += g < eps;
        clamped_high += g > 1;
        INFO("(" << x << "," << y << ") epsilon " << eps);
        REQUIRE(spread.at(x, y, 0) == Approx(s[y * w + x]).epsilon(1e-4).margin(1e-5));
        REQUIRE(dev.at(x, y, 0) == Approx(want).epsilon(1e-4).margin(1e-6));
      }
    REQUIRE(clamped_high > 0);  // the firefly's neighbourhood
    REQUIRE(clamped_low > 0);   // the flat corner
  }
}

std::unique_ptr<Denoiser> wavelet_on(const TestDevice& d, const WaveletParams& p, int threads = 2) {
  DenoiserConfig c = d.config(DenoiserConfig());
  c.method = Method::Wavelet;
  c.threads = threads;
  c.wavelet = p;
  return make_denoiser(c);
}

void wavelet_constant_stays_constant(const TestDevice& d) {
  for (int k : {3, 5, 7, 9}) {
    Frame f = wavelet_bumpy_frame(37, 23, 13);
    for (float& v : f.color.data()) v = 0.7f;
    for (float& v : f.albedo.data()) v = 0.4f;
    WaveletParams p;
    p.kernel_size = k;
    Image out;
    wavelet_on(d, p)->denoise(f, out);
    INFO("kernel " << k);
    for (float v : out.data()) REQUIRE(v == Approx(0.7f).epsilon(d.tolerance(1e-6)));
  }
}

// Left and right of x = 10 differ in one guide; the color differs too. Nothing may cross.
void no_bleeding(const TestDevice& d, const std::function<void(Frame&)>& split, float left,
                 float right) {
  Frame f = test::flat_frame(20, 8);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 20; ++x)
      for (int c = 0; c < 3; ++c) f.color.at(x, y, c) = x < 10 ? left : right;
  for (float& v : f.albedo.data()) v = 1.f;
  split(f);
  Image out;
  wavelet_on(d, WaveletParams())->denoise(f, out);
  for (int y = 0; y < 8; ++y) {
    INFO("row " << y);
    REQUIRE(out.at(9, y, 0) == Approx(left).epsilon(2e-3));
    REQUIRE(out.at(10, y, 0) == Approx(right).epsilon(2e-3));
  }
}

void wavelet_edges_stop_the_filter(const TestDevice& d) {
  SECTION("depth: a 30-unit step, W_Z = exp(-30/1.01)") {
    no_bleeding(d, [](Frame& f) {
      for (int y = 0; y < 8; ++y)
        for (int x = 10; x < 20; ++x) f.depth.at(x, y, 0) = 32.f;
    }, 0.3f, 0.6f);
  }
  SECTION("normal: 53 degrees apart, 0.6^64 ~ 6e-15") {
    no_bleeding(d, [](Frame& f) {
      for (int y = 0; y < 8; ++y)
        for (int x = 10; x < 20; ++x) {
          f.normal.at(x, y, 0) = 0.8f;
          f.normal.at(x, y, 2) = 0.6f;
        }
    }, 0.3f, 0.6f);
  }
  SECTION("luma: 0.1 against 100 on one surface, W_L = exp(-99 / (4 Dev + 0.01))") {
    no_bleeding(d, [](Frame&) {}, 0.1f, 100.f);
  }
}

void wavelet_bad_samples_replaced(const TestDevice& d) {
  Frame f = wavelet_bumpy_frame(16, 12, 17);
  for (float& v : f.color.data()) v = 0.5f;
  f.color.at(3, 4, 0) = std::numeric_limits<float>::quiet_NaN();
  f.color.at(5, 5, 1) = std::numeric_limits<float>::infinity();
  f.color.at(8, 2, 2) = -2.f;
  f.albedo.at(9, 9, 1) = std::numeric_limits<float>::quiet_NaN();  // sanitized to 1
  auto den = wavelet_on(d, WaveletParams());
  Image out;
  den->denoise(f, out);
  REQUIRE(den->last_report().replaced_samples == 3);
  REQUIRE(den->last_report().repairs.albedo == 1);
  for (float v : out.data()) REQUIRE(std::isfinite(v));
  const Image illum = den->read_buffer(wavelet_buffer::kIllumination);
  REQUIRE(illum.at(3, 4, 0) == 0.f);
  REQUIRE(illum.at(9, 9, 1) == Approx(0.5 / 1.01).epsilon(1e-6));
}

}  // namespace

SVGF_DEVICE_TEST("wavelet: one pass against a double-precision reference, every parameter",
                 "[wavelet]", wavelet_pass_against_double)
SVGF_BACKEND_TEST("wavelet: Dev is the clamped 3x3 Gaussian of the 3x3 luma deviation",
                  "[wavelet]", deviation_against_double)
SVGF_DEVICE_TEST("wavelet: a constant image stays constant, every kernel size", "[wavelet]",
                 wavelet_constant_stays_constant)
SVGF_DEVICE_TEST("wavelet: depth, normal and luma edges stop the filter", "[wavelet]",
                 wavelet_edges_stop_the_filter)
SVGF_DEVICE_TEST("wavelet: NaN, Inf and negative color are replaced by 0 and counted",
                 "[wavelet]", wavelet_bad_samples_replaced)

TEST_CASE("wavelet: binomial weights are rows of Pascal's triangle and sum to 1", "[wavelet]") {
  for (int k : {3, 5, 7, 9}) {
    double sum = 0;
    for (int d = -k / 2; d <= k / 2; ++d) {
      REQUIRE(double(binomial_weight(k, d)) == binomial(k, d));
      sum += binomial_weight(k, d);
    }
    REQUIRE(sum == 1.0);
  }
  REQUIRE(binomial_weight(5, 2) == 0.0625f);  // the B3 spline 1/16, 1/4, 3/8
}

TEST_CASE("wavelet: same bits on 1 and 2 threads; stages, buffers, defaults and errors",
          "[wavelet]") {
  const Frame f = wavelet_bumpy_frame(41, 27, 19);
  Frame noisy = f;
  test::fill_uniform(noisy.color, 0.f, 3.f, 23);
  Image a, b;
  wavelet_on(test::kCpu, WaveletParams(), 1)->denoise(noisy, a);
  auto two = wavelet_on(test::kCpu, WaveletParams(), 2);
  two->denoise(noisy, b);
  test::require_identical(a, b, "1 vs 2 threads");
  REQUIRE(two->stages() ==
          std::vector<std::string>{"sanitize", "demodulate", "spread", "deviation", "atrous",
                                   "remodulate"});
  REQUIRE(two->last_report().times["atrous"] > 0);
  REQUIRE_THROWS_WITH(two->read_buffer("moments"), Catch::Contains("no debug buffer 'moments'"));
  // The documented defaults (docs/wavelet.md: Nagi's gui.hpp and the CIS 565 filter size 80).
  const WaveletParams p;
  REQUIRE(p.iterations == 4);
  REQUIRE(p.kernel_size == 5);
  REQUIRE(p.sigma_depth == 1.f);
  REQUIRE(p.sigma_normal == 64.f);
  REQUIRE(p.sigma_luma == 4.f);
  REQUIRE(p.epsilon == 0.01f);
  REQUIRE(parse_method("wavelet") == Method::Wavelet);
  auto bad = [](auto change) {
    WaveletParams q;
    change(q);
    return wavelet_on(test::kCpu, q);
  };
  REQUIRE_THROWS_WITH(bad([](WaveletParams& q) { q.kernel_size = 4; }), Catch::Contains("--kernel-size"));
  REQUIRE_THROWS_WITH(bad([](WaveletParams& q) { q.sigma_depth = -1.f; }), Catch::Contains("--sigma-depth"));
  REQUIRE_THROWS_WITH(bad([](WaveletParams& q) { q.sigma_normal = -1.f; }), Catch::Contains("--sigma-normal"));
  REQUIRE_THROWS_WITH(bad([](WaveletParams& q) { q.sigma_luma = 0.f; }), Catch::Contains("--sigma-luma"));
  REQUIRE_THROWS_WITH(bad([](WaveletParams& q) { q.iterations = -1; }), Catch::Contains("--iterations"));
}

// Bad input, every method, every backend and mode (tests/test_device.h): a frame with NaN, Inf
// and absurd values planted in any plane gives finite output, says what it repaired, damages
// nothing beyond the filter's reach, and the history recovers (docs/bad-input.md).
#include <cmath>
#include <cstdlib>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <catch2/catch.hpp>

#include "metrics/image_metrics.h"
#include "pipeline/make_denoiser.h"
#include "synthetic_sequence.h"
#include "test_device.h"
#include "test_support.h"

using namespace svgf;
using svgf::test::TestDevice;

namespace {

using svgf::test::kNaN;
using svgf::test::kInf;

constexpr int kWidth = 128, kHeight = 48;
// Values are planted in columns [kPatchX0, kPatchX1); a method reaches at most kReach pixels
// (SVGF: 1 reprojection + 3 variance + 30 a-trous; wavelet: 30 + its 3x3 deviation windows;
// JBF: 16 or 30, + 3 clamp window + 1 reprojection; BMFR: its 32-pixel block + 1 reprojection), so columns from kPatchX1 + kReach on must
// not see them in the frame they arrive.
constexpr int kPatchX0 = 2, kPatchX1 = 10, kReach = 40;
constexpr int kPoisoned = 3, kFrames = 20;

// The synthetic sequence, wider, with emission planes (zeros) so that they can be poisoned too.
Frame clean_frame(int k) {
  test::SyntheticScene scene;
  scene.width = kWidth;
  scene.height = kHeight;
  Frame f = scene.frame(k);
  f.emission = Image(kWidth, kHeight, 3, 0.f);
  return f;
}

// Plants `count` bad values at random pixels of the patch, in random planes.
void poison(Frame& f, uint32_t seed, int count) {
  const float bad[] = {kNaN, kInf, -kInf, 3e38f, -3e38f, 1e30f, -1.f, 1e-40f, 0.f, 1e20f};
  std::mt19937 rng(seed);
  auto pick = [&](int n) { return static_cast<int>(rng() % static_cast<uint32_t>(n)); };
  for (int k = 0; k < count; ++k) {
    const int x = kPatchX0 + pick(kPatchX1 - kPatchX0), y = pick(kHeight);
    const float v = bad[pick(10)];
    Image* planes[] = {&f.color, &f.albedo, &f.emission, &f.normal, &f.position, &f.depth,
                       &f.depth_gradient, &f.motion};
    Image& im = *planes[pick(8)];
    if (&im == &f.normal && pick(2) == 0) {  // a whole normal: zero, or scaled
      for (int c = 0; c < 3; ++c) im.at(x, y, c) = v == 0.f ? 0.f : im.at(x, y, c) * 1.5f;
      continue;
    }
    im.at(x, y, pick(im.channels())) = v;
  }
}

struct Run {
  std::vector<Image> out;
  std::vector<InputRepairs> repairs;
};

Run denoise(const DenoiserConfig& c, uint32_t poison_seed) {
  auto d = make_denoiser(c);
  Run r;
  for (int k = 0; k < kFrames; ++k) {
    Frame f = clean_frame(k);
    if (poison_seed != 0 && k == kPoisoned) poison(f, poison_seed, 24);
    r.out.emplace_back();
    d->denoise(f, r.out.back());
    r.repairs.push_back(d->last_report().repairs);
  }
  return r;
}

// The columns [x0, width) of an image.
Image columns_from(const Image& im, int x0) {
  Image c(im.width() - x0, im.height(), im.channels());
  for (int ch = 0; ch < im.channels(); ++ch)
    for (int y = 0; y < im.height(); ++y)
      for (int x = x0; x < im.width(); ++x) c.at(x - x0, y, ch) = im.at(x, y, ch);
  return c;
}

void bad_values_stay_local(const TestDevice& device, Method method) {
  DenoiserConfig c = device.config(DenoiserConfig());
  c.method = method;
  c.threads = 2;
  const Run clean = denoise(c, 0);
  for (uint32_t seed : {11u, 12u, 13u}) {
    INFO(to_string(method) << " on " << device.name() << ", poison seed " << seed);
    const Run bad = denoise(c, seed);
    for (int k = 0; k < kFrames; ++k) {
      INFO("frame " << k);
      for (float v : bad.out[k].data()) REQUIRE(std::isfinite(v));
      REQUIRE((bad.repairs[k].total() > 0) == (k == kPoisoned));
    }
    // Beyond the reach of the planted values, the frame they arrive in is the clean run's.
    const Image far_bad = columns_from(bad.out[kPoisoned], kPatchX1 + kReach);
    const Image far_clean = columns_from(clean.out[kPoisoned], kPatchX1 + kReach);
    if (device.fast())
      REQUIRE(test::max_relative_difference(far_bad, far_clean, 1e-3) <= test::kFastTolerance);
    else
      test::require_identical(far_bad, far_clean, "columns beyond the planted values' reach");
    // The history recovers: 16 frames later the output is as close to the reference as the
    // clean run's, within 0.3 dB over the whole image (SVGF, the slowest with its alpha of
    // 0.05, was 0.06-0.18 dB behind there, 1.5-3.5 dB in the poisoned frame).
    const Frame last = clean_frame(kFrames - 1);
    const double psnr_clean = metrics::psnr(clean.out.back(), last.reference);
    const double psnr_bad = metrics::psnr(bad.out.back(), last.reference);
    INFO("last frame PSNR: clean " << psnr_clean << " dB, poisoned " << psnr_bad << " dB");
    REQUIRE(psnr_bad >= psnr_clean - 0.3);
  }
}

void svgf_case(const TestDevice& d) { bad_values_stay_local(d, Method::Svgf); }
void gaussian_case(const TestDevice& d) { bad_values_stay_local(d, Method::Gaussian); }
void wavelet_case(const TestDevice& d) { bad_values_stay_local(d, Method::Wavelet); }
void jbf_case(const TestDevice& d) { bad_values_stay_local(d, Method::Jbf); }
void jbf_atrous_case(const TestDevice& d) { bad_values_stay_local(d, Method::JbfAtrous); }
void bmfr_case(const TestDevice& d) { bad_values_stay_local(d, Method::Bmfr); }

// The repairs a frame reports, per kind, on every backend: what the planted values call for.
void repairs_counted_per_kind(const TestDevice& device) {
  DenoiserConfig c = device.config(DenoiserConfig());
  c.method = Method::Jbf;  // reads world positions too
  Frame f = clean_frame(0);
  f.color.at(20, 5, 0) = kNaN;
  f.color.at(21, 5, 1) = 1e30f;
  f.albedo.at(22, 5, 2) = kInf;
  f.emission.at(23, 5, 0) = -kInf;
  f.normal.at(24, 5, 2) = 3.f;    // renormalized
  f.depth.at(25, 5, 0) = kNaN;    // background
  f.position.at(26, 5, 1) = kInf; // background
  f.motion.at(27, 5, 0) = kNaN;
  auto d = make_denoiser(c);
  Image out;
  d->denoise(f, out);
  const InputRepairs& r = d->last_report().repairs;
  CHECK(r.color == 2);
  CHECK(r.albedo == 1);
  CHECK(r.emission == 1);
  CHECK(r.normal == 1);
  CHECK(r.surface == 2);
  CHECK(r.motion == 1);
  CHECK(d->last_report().replaced_samples == 2);
  REQUIRE(d->last_report().times[kSanitizeStage] >= 0.0);
  REQUIRE(d->stages().front() == kSanitizeStage);
}

// Every weight stays finite for any parameter validate() accepts: each method at the smallest and
// largest values of its ranges, on a noisy sequence with edges and motion.
void extreme_parameters_finite(const TestDevice& device) {
  const float tiny = 1e-30f, huge = 3e38f;
  std::vector<std::pair<std::string, DenoiserConfig>> configs;
  for (int extreme = 0; extreme < 2; ++extreme) {
    const float lo_hi = extreme ? huge : tiny;
    DenoiserConfig c = device.config(DenoiserConfig());
    c.svgf.phi_color = lo_hi;
    c.svgf.phi_normal = extreme ? huge : 0.f;
    c.svgf.phi_depth = extreme ? huge : tiny;
    c.svgf.alpha = c.svgf.moments_alpha = extreme ? 1.f : tiny;
    c.svgf.variance_epsilon = lo_hi;
    c.svgf.depth_gradient_floor = lo_hi;
    c.svgf.albedo_epsilon = extreme ? 1.f : tiny;
    c.method = Method::Svgf;
    configs.emplace_back("svgf", c);
    c.method = Method::Wavelet;
    c.wavelet.sigma_depth = c.wavelet.sigma_luma = lo_hi;
    c.wavelet.sigma_normal = extreme ? huge : 0.f;
    c.wavelet.epsilon = extreme ? 1.f : tiny;
    configs.emplace_back("wavelet", c);
    for (Method m : {Method::Jbf, Method::JbfAtrous}) {
      c.method = m;
      c.jbf.levels = m == Method::JbfAtrous ? 4 : 0;
      c.jbf.sigma_coord = c.jbf.sigma_color = c.jbf.sigma_normal = c.jbf.sigma_plane = lo_hi;
      c.jbf.alpha = extreme ? 1.f : tiny;
      c.jbf.clamp_k = extreme ? huge : 0.f;
      configs.emplace_back(to_string(m), c);
    }
    c.method = Method::Bmfr;
    for (BmfrRankStrategy s : {BmfrRankStrategy::Noise, BmfrRankStrategy::Skip}) {
      c.bmfr.rank_strategy = s;
      c.bmfr.pre_alpha = c.bmfr.post_alpha = extreme ? 1.f : tiny;
      c.bmfr.position_limit_sq = c.bmfr.normal_limit_sq = lo_hi;
      c.bmfr.noise_amount = extreme ? 1.f : 0.f;
      c.bmfr.skip_threshold = extreme ? 0.999f : 0.f;
      c.bmfr.albedo_epsilon = extreme ? 1.f : tiny;
      configs.emplace_back(std::string("bmfr ") + to_string(s), c);
    }
    c.method = Method::Gaussian;
    c.gaussian.sigma = extreme ? 256.f : 1e-3f;
    c.gaussian.radius = extreme ? 40 : 0;
    configs.emplace_back("gaussian", c);
  }
  for (const auto& [name, c] : configs) {
    INFO(name << " on " << device.name() << ", phi_color " << c.svgf.phi_color);
    auto d = make_denoiser(c);
    for (int k = 0; k < 4; ++k) {
      Frame f = clean_frame(k);
      Image out;
      d->denoise(f, out);
      for (float v : out.data()) REQUIRE(std::isfinite(v));
    }
  }
}

}  // namespace

SVGF_DEVICE_TEST("bad input: every method's output is finite at the ends of its parameter ranges",
                 "[bad-input]", extreme_parameters_finite)
SVGF_DEVICE_TEST("bad input: svgf keeps planted NaN, Inf and huge values local and recovers",
                 "[bad-input]", svgf_case)
SVGF_DEVICE_TEST("bad input: gaussian keeps planted NaN, Inf and huge values local",
                 "[bad-input]", gaussian_case)
SVGF_DEVICE_TEST("bad input: wavelet keeps planted NaN, Inf and huge values local",
                 "[bad-input]", wavelet_case)
SVGF_DEVICE_TEST("bad input: jbf keeps planted NaN, Inf and huge values local and recovers",
                 "[bad-input]", jbf_case)
SVGF_DEVICE_TEST("bad input: jbf-atrous keeps planted NaN, Inf and huge values local and recovers",
                 "[bad-input]", jbf_atrous_case)
SVGF_DEVICE_TEST("bad input: bmfr keeps planted NaN, Inf and huge values local and recovers",
                 "[bad-input]", bmfr_case)
SVGF_DEVICE_TEST("bad input: every repair is counted by kind", "[bad-input]",
                 repairs_counted_per_kind)

// OpenCV check 8 (docs/opencv-checks.md): a whole-pipeline sanity check that shares no code
// with the project's metrics or filters. On every sequence with a reference, after the
// warm-up, the denoised frame must be closer to the reference, by cv::PSNR, than
// cv::GaussianBlur and cv::bilateralFilter of the noisy input at matched blur: the spatial
// sigma of the a-trous cascade with every weight 1, sqrt(sum_i 4^i) over the iterations
// (the B3 kernel has variance 1 per axis, dilated by 2^i). The bilateral filter's range sigma
// is the best of three multiples of the true noise level (an oracle, which only helps it).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

#include <catch2/catch.hpp>
#include <opencv2/imgproc.hpp>

#include "pipeline/make_denoiser.h"
#include "io/sequence.h"
#include "opencv_support.h"
#include "synthetic_sequence.h"

using namespace svgf;
using namespace svgf::cvtest;
namespace fs = std::filesystem;

namespace {

// Frames since the start (or a camera cut) before comparing: the variance estimate switches
// from spatial to temporal at spatial_variance_history = 4.
constexpr int kWarmup = 4;
// Frames denoised per fixture sequence, a bound on the runtime only.
constexpr int kMaxFixtureFrames = 32;
// Fixtures where the check is measured and printed but not enforced; empty since the defaults
// follow changes of lighting (issue 12: A-SVGF's anti-lag), which Falcor's did not on
// light-switch and moving-shadow (docs/opencv-checks.md).
const std::vector<std::string> kNotEnforcedYet = {};

struct Sequence {
  std::string name;
  int frames = 0;
  std::function<Frame(int)> read;
  std::function<bool(int)> is_cut;
};

// Noisy input as the baselines see it: radiance with NaN, Inf and negatives set to 0 (the
// pipeline's own bad-sample rule, so neither side gets a head start), CV_32FC3.
cv::Mat sanitized(const Image& color) {
  cv::Mat m = rgb_mat(color, 0, CV_32F);
  for (int y = 0; y < m.rows; ++y)
    for (int x = 0; x < m.cols; ++x)
      for (int c = 0; c < 3; ++c) {
        float& v = m.at<cv::Vec3f>(y, x)[c];
        if (!(v >= 0.f && std::isfinite(v))) v = 0.f;
      }
  return m;
}

// cv::PSNR on images clamped to [0, 1], peak 1 (the project's definition, check 6).
double psnr_cv(const cv::Mat& test, const cv::Mat& reference) {
  cv::Mat a, b;
  test.convertTo(a, CV_64FC3);
  reference.convertTo(b, CV_64FC3);
  cv::min(cv::max(a, 0.0), 1.0, a);
  cv::min(cv::max(b, 0.0), 1.0, b);
  return cv::PSNR(a, b, 1.0);
}

double matched_sigma(const SvgfParams& p) {
  double variance = 0;
  for (int i = 0; i < p.iterations; ++i) variance += std::pow(4.0, i);
  return std::sqrt(variance);
}

struct Scores {
  double svgf = 0, gaussian = 0, bilateral = 0;
};

Scores score(const Image& denoised, const Frame& f, const SvgfParams& p) {
  const cv::Mat noisy = sanitized(f.color), ref = rgb_mat(f.reference, 0, CV_32F);
  const double sigma_s = matched_sigma(p);
  Scores s;
  s.svgf = psnr_cv(rgb_mat(denoised, 0, CV_32F), ref);
  cv::Mat g;
  cv::GaussianBlur(noisy, g, cv::Size(0, 0), sigma_s);
  s.gaussian = psnr_cv(g, ref);
  // Noise level: RMS of noisy - reference on clamped values (the PSNR's domain).
  cv::Mat a = cv::min(cv::max(noisy, 0.0), 1.0), b = cv::min(cv::max(ref, 0.0), 1.0);
  const double sigma_n = std::max(1e-3, cv::norm(a, b, cv::NORM_L2) /
                                            std::sqrt(3.0 * noisy.rows * noisy.cols));
  s.bilateral = -1e30;
  // sigma_n, 2 sigma_n, and phi_color sigma_n / sqrt(2), where a Gaussian range kernel has
  // the e^-1 point of SVGF's exp(-|dl| / (phi_color sigma)).
  for (double k : {1.0, 2.0, p.phi_color / std::sqrt(2.0)}) {
    cv::Mat bl;
    cv::bilateralFilter(noisy, bl, -1, k * sigma_n, sigma_s);
    s.bilateral = std::max(s.bilateral, psnr_cv(bl, ref));
  }
  return s;
}

// Denoises `seq` on `device` and checks every frame past the warm-up that has a reference
// (only measures it when `enforce` is false). Returns the number of frames compared.
int check_sequence(const Sequence& seq, const TestDevice& device, bool enforce = true) {
  const DenoiserConfig config = device.config(DenoiserConfig());
  auto denoiser = make_denoiser(config);
  const auto t0 = std::chrono::steady_clock::now();
  int since_reset = 0, compared = 0;
  double worst_margin = 1e30;
  Scores last;
  for (int k = 0; k < seq.frames; ++k) {
    const Frame f = seq.read(k);
    if (k > 0 && seq.is_cut(k)) {
      denoiser->reset();
      since_reset = 0;
    }
    Image out;
    denoiser->denoise(f, out);
    ++since_reset;
    if (since_reset <= kWarmup || !f.has_reference()) continue;
    const Scores s = score(out, f, config.svgf);
    INFO(seq.name << " (" << device.name() << ") frame " << k << ": svgf " << s.svgf
                  << " dB, GaussianBlur " << s.gaussian << " dB, bilateralFilter "
                  << s.bilateral << " dB");
    // CHECK, not REQUIRE: every losing frame is reported.
    if (enforce) {
      CHECK(s.svgf > s.gaussian);
      CHECK(s.svgf > s.bilateral);
    }
    worst_margin = std::min(worst_margin, s.svgf - std::max(s.gaussian, s.bilateral));
    last = s;
    ++compared;
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::cout << "opencv check 8: " << seq.name << " (" << device.name() << "), " << compared
            << " frames compared, last: svgf " << last.svgf << " dB, GaussianBlur "
            << last.gaussian << " dB, bilateralFilter " << last.bilateral
            << " dB; smallest margin " << worst_margin << " dB; " << seconds << " s"
            << (enforce ? "" : " (not enforced yet: issue 12's anti-lag)") << "\n";
  return compared;
}

Sequence synthetic(int w, int h, int square, int speed, uint32_t seed) {
  test::SyntheticScene scene;
  scene.width = w;
  scene.height = h;
  scene.square = square;
  scene.speed = speed;
  scene.seed = seed;
  Sequence s;
  s.name = "synthetic " + std::to_string(w) + "x" + std::to_string(h);
  s.frames = 12;
  s.read = [scene](int k) { return scene.frame(k); };
  s.is_cut = [](int) { return false; };
  return s;
}

void synthetic_sequences(const TestDevice& device) {
  for (const Sequence& s : {synthetic(64, 48, 14, 2, 1), synthetic(129, 67, 20, 3, 2)}) {
    const int compared = check_sequence(s, device);
    REQUIRE(compared == s.frames - kWarmup);
  }
}

void fixture_sequences(const TestDevice& device) {
  const FixtureScan scan = scan_fixtures();
  if (scan.folders == 0) {
    WARN("no fixture sequences under " << scan.root
                                       << " yet: check 8 ran on the synthetic sequences only");
    return;
  }
  // Once fixtures exist, finding none would make the check vacuous: fail instead.
  INFO(scan.folders << " sequence folders under " << scan.root);
  REQUIRE(!scan.sequences.empty());
  int with_reference = 0;
  for (const std::string& dir : scan.sequences) {
    const io::Sequence seq(dir);
    const std::string name = fs::path(dir).filename().string();
    if (seq.manifest().reference_spp <= 0) {
      WARN(name << ": no reference, not compared");
      continue;
    }
    ++with_reference;
    Sequence s;
    s.name = "fixture " + name;
    s.frames = std::min(seq.size(), kMaxFixtureFrames);
    s.read = [&seq](int k) { return seq.read(k); };
    s.is_cut = [&seq](int k) { return seq.is_camera_cut(k); };
    const bool enforce =
        std::find(kNotEnforcedYet.begin(), kNotEnforcedYet.end(), name) == kNotEnforcedYet.end();
    const int compared = check_sequence(s, device, enforce);
    INFO(s.name << ": a fixture needs more than " << kWarmup << " frames with a reference");
    REQUIRE(compared > 0);
  }
  REQUIRE(with_reference > 0);
}

}  // namespace

SVGF_OPENCV_CHECK("opencv 8a: synthetic sequences beat GaussianBlur and bilateralFilter",
                  "[pipeline]", synthetic_sequences)
SVGF_OPENCV_CHECK("opencv 8b: every fixture with a reference beats GaussianBlur and bilateral",
                  "[pipeline]", fixture_sequences)

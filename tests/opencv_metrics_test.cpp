// OpenCV check 6 (docs/opencv-checks.md): the project's PSNR and SSIM agree with cv::PSNR and
// cv::quality::QualitySSIM on the same images. Host-only code: no backend.
//  PSNR: ours clamps to [0, 1] and uses peak 1; OpenCV gets the clamped images in double and
//        R = 1.
//  SSIM: QualitySSIM hard-codes C1 = (0.01 * 255)^2 and C2 = (0.03 * 255)^2, i.e. L = 255, so it
//        gets the clamped images scaled by 255 (exact in double; SSIM is invariant under
//        scaling the images and L together). It blurs with GaussianBlur 11x11, sigma 1.5,
//        BORDER_REFLECT_101 and averages the full-size map, as ours does.
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <catch2/catch.hpp>
#include <opencv2/core/ocl.hpp>
#include <opencv2/quality.hpp>

#include "metrics/image_metrics.h"
#include "metrics/ssim.h"
#include "opencv_support.h"
#include "synthetic_sequence.h"

using namespace svgf;
using namespace svgf::cvtest;

namespace {

// Both sides sum in double: over n <= 7e4 values the relative error of the MSE is below
// n * 2^-53 ~ 1e-11, i.e. 5e-11 dB; cv::PSNR's + DBL_EPSILON on the RMSE adds < 1e-11 dB for
// RMSE >= 1e-4. 1e-9 dB is 20x the sum of both.
constexpr double kPsnrTolDb = 1e-9;
// SSIM in double on both sides; the worst-conditioned step, 2 cov + C2 over a denominator
// >= C1 C2, turns ~1e-14 absolute blur error into < 1e-11 per pixel. 1e-10 absolute leaves 10x.
constexpr double kSsimTol = 1e-10;

struct Pair {
  std::string name;
  Image test, reference;
};

// Non-trivial pairs per size: HDR noise with values outside [0, 1] against a smooth target
// (exercises the clamp), and the synthetic scene's noisy frame against its reference.
std::vector<Pair> pairs(int w, int h, uint32_t seed) {
  std::vector<Pair> out;
  Pair a{"random HDR", Image(w, h, 3), Image(w, h, 3)};
  fill_uniform(a.test, -0.2f, 1.5f, seed);
  for (int c = 0; c < 3; ++c)
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        a.reference.at(x, y, c) = 0.5f + 0.4f * std::sin(0.21f * x + 0.13f * y + c);
  out.push_back(a);
  test::SyntheticScene scene;
  scene.width = w;
  scene.height = h;
  scene.seed = seed;
  const Frame f = scene.frame(2);
  out.push_back(Pair{"synthetic frame", f.color, f.reference});
  return out;
}

// The pairs for every size, then every fixture's first frame against its reference.
std::vector<Pair> all_pairs(uint32_t seed) {
  std::vector<Pair> out;
  for (const Size2 s : check_sizes())
    for (Pair& p : pairs(s.w, s.h, ++seed)) out.push_back(std::move(p));
  for (const Frame& f : fixture_frames())
    if (f.has_reference()) out.push_back(Pair{"fixture frame", f.color, f.reference});
  return out;
}

cv::Mat clamped(const Image& im, double scale) {
  cv::Mat m = rgb_mat(im);
  cv::min(cv::max(m, 0.0), 1.0, m);
  return m * scale;
}

}  // namespace

TEST_CASE("opencv 6a: PSNR equals cv::PSNR on clamped images", "[opencv][metrics]") {
  for (const Pair& p : all_pairs(800)) {
    const int w = p.test.width(), h = p.test.height();
    const double ours = metrics::psnr(p.test, p.reference);
    const double theirs = cv::PSNR(clamped(p.test, 1.0), clamped(p.reference, 1.0), 1.0);
    INFO(p.name << " " << w << "x" << h << ": ours " << ours << " dB, OpenCV " << theirs
                << " dB");
    REQUIRE(std::fabs(ours - theirs) <= kPsnrTolDb);
    // The MSE itself, against the squared L2 norm.
    const double mse_cv = cv::norm(clamped(p.test, 1.0), clamped(p.reference, 1.0),
                                   cv::NORM_L2SQR) / (3.0 * w * h);
    REQUIRE(std::fabs(metrics::mse_clamped(p.test, p.reference) - mse_cv) <= 1e-11 * mse_cv);
  }
  // Identical images: ours is +Inf, OpenCV's epsilon caps it near 20 log10(1 / 2^-52) = 313 dB.
  Image a(31, 17, 3);
  fill_uniform(a, 0.f, 1.f, 899);
  REQUIRE(metrics::psnr(a, a) == std::numeric_limits<double>::infinity());
  REQUIRE(cv::PSNR(clamped(a, 1.0), clamped(a, 1.0), 1.0) > 300.0);
}

TEST_CASE("opencv 6b: SSIM equals cv::quality::QualitySSIM", "[opencv][metrics]") {
  // QualitySSIM works on UMat: keep it off OpenCL so the reference is the CPU double code.
  cv::ocl::setUseOpenCL(false);
  Coverage coverage;
  for (const Pair& p : all_pairs(900)) {
    const int w = p.test.width(), h = p.test.height();
    cv::Mat map_cv;  // one image in, one 3-channel map out (a vector output throws in 4.6)
    const cv::Scalar q = cv::quality::QualitySSIM::compute(clamped(p.reference, 255.0),
                                                           clamped(p.test, 255.0), map_cv);
    const double theirs = (q[0] + q[1] + q[2]) / 3.0;
    const double ours = metrics::ssim(p.test, p.reference);
    INFO(p.name << " " << w << "x" << h << ": ours " << ours << ", OpenCV " << theirs);
    REQUIRE(std::fabs(ours - theirs) <= kSsimTol);

    // The per-pixel map, edges included (ours is stored in float: + u |v|).
    REQUIRE(map_cv.size() == cv::Size(w, h));
    const Image map = metrics::ssim_map(p.test, p.reference);
    cv::Mat map_cv_d;
    map_cv.convertTo(map_cv_d, CV_64FC3);
    PlaneCheck check("ssim map, " + p.name, w, h, 5);
    for (int c = 0; c < 3; ++c)
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          const double v = map_cv_d.at<cv::Vec3d>(y, x)[c];
          check.add(x, y, c, map.at(x, y, c), v, kSsimTol + kU * std::fabs(v));
        }
    check.require();
    coverage.add(check);
  }
  coverage.require();
}

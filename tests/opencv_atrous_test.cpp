// OpenCV checks 1 and 2 (docs/opencv-checks.md). The a-trous iteration with every edge-stopping
// weight forced to 1 is the B3-spline kernel dilated by 2^i (cv::sepFilter2D), and the 3x3
// variance prefilter is OpenCV's 3x3 Gaussian (cv::GaussianBlur, cv::sepFilter2D). Both use the
// project's border rule, out-of-image taps skipped and the weights renormalized, which OpenCV
// reproduces as filter(data) / filter(ones) with BORDER_CONSTANT. OpenCV runs in double.
#include <limits>
#include <string>

#include <catch2/catch.hpp>
#include <opencv2/imgproc.hpp>

#include "methods/svgf/atrous.h"
#include "opencv_support.h"

using namespace svgf;
using namespace svgf::cvtest;

namespace {

// 25 positive float terms, one rounding each for the product and the 24 sums, one for the
// division by the (exact) weight sum: |error| <= gamma_26 * value; 27u leaves room for the
// double reference's own error (~1e-15).
constexpr double kAtrousTol = 27 * kU;
// 9 exact products (power-of-two weights), 8 sums, one division: gamma_9; 10u with room.
constexpr double kPrefilterTol = 10 * kU;

// The B3 spline (1/16, 1/4, 3/8, 1/4, 1/16) written out here rather than taken from
// methods/svgf/params.h: the check must not share the weights it checks. Taps `step` apart; squared
// for the variance, which the filter carries with squared weights.
cv::Mat b3_dilated(int step, bool squared) {
  const double b3[5] = {1.0 / 16, 1.0 / 4, 3.0 / 8, 1.0 / 4, 1.0 / 16};
  cv::Mat k = cv::Mat::zeros(4 * step + 1, 1, CV_64F);
  for (int t = 0; t < 5; ++t) k.at<double>(t * step) = squared ? b3[t] * b3[t] : b3[t];
  return k;
}

cv::Mat sep_filter(const cv::Mat& src, const cv::Mat& k) {
  cv::Mat dst;
  cv::sepFilter2D(src, dst, CV_64F, k, k, cv::Point(-1, -1), 0, cv::BORDER_CONSTANT);
  return dst;
}

// One a-trous iteration at 2^level through one driver, against OpenCV.
void check_atrous_level(const TestDevice& device, Driver driver, const Frame& frame, const Image& in,
                        int level, Coverage& coverage) {
  const int w = in.width(), h = in.height(), step = 1 << level;
  // phi_color = phi_depth = inf: |difference| / inf = 0, no luminance or depth term;
  // phi_normal = 0: normal term pow(., 0) = 1. With depth > 0 everywhere (no background) every
  // weight is exactly 1, although the guides themselves are random.
  SvgfParams p;
  p.phi_color = std::numeric_limits<float>::infinity();
  p.phi_depth = std::numeric_limits<float>::infinity();
  p.phi_normal = 0.f;
  Image out(w, h, 4, -1.f);
  StageRunner r(device);
  const AtrousKernel kernel{r.guides(frame), r.illum_var(in), r.illum_var(out), step, p};
  if (driver == Driver::Rows)
    run_rows(r, kernel, w, h);
  else
    r.run(kernel, w, h);

  const cv::Mat k = b3_dilated(step, false), k2 = b3_dilated(step, true);
  const cv::Mat norm = sep_filter(cv::Mat::ones(h, w, CV_64F), k);  // weight inside the image
  const cv::Mat norm2 = norm.mul(norm);
  PlaneCheck check("atrous level " + std::to_string(level) + " (" + driver_name(device, driver) +
                       ")",
                   w, h, 2 * step);
  for (int c = 0; c < 4; ++c) {
    const cv::Mat src = plane_mat(in, c);
    const cv::Mat want =
        c < 3 ? cv::Mat(sep_filter(src, k) / norm) : cv::Mat(sep_filter(src, k2) / norm2);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const double v = want.at<double>(y, x);
        check.add(x, y, c, out.at(x, y, c), v, kAtrousTol * v);
      }
  }
  check.require();
  coverage.add(check);
}

void atrous_unit_weights(const TestDevice& device) {
  Coverage coverage;
  uint32_t seed = 100;
  for (const Size2 s : check_sizes()) {
    const Frame frame = random_frame(s.w, s.h, ++seed);
    Image in(s.w, s.h, 4);
    fill_uniform(in, 0.05f, 4.f, ++seed);  // HDR color; the variance plane is redrawn below
    const std::vector<float> var = uniform_values(in.pixel_count(), 1e-3f, 1.f, ++seed);
    std::copy(var.begin(), var.end(), in.plane(3));
    // Every level the pipeline runs (iterations = 4) and the paper's fifth.
    for (const Driver driver : drivers(device))
      for (int level = 0; level <= 4; ++level)
        check_atrous_level(device, driver, frame, in, level, coverage);
  }
  // Fixture images as the color (random guides: the weights are 1 whatever they hold).
  for (const Frame& f : fixture_frames()) {
    const Frame frame = random_frame(f.width(), f.height(), ++seed);
    Image in(f.width(), f.height(), 4);
    std::copy(f.color.data().begin(), f.color.data().end(), in.plane(0));
    const std::vector<float> var = uniform_values(in.pixel_count(), 1e-3f, 1.f, ++seed);
    std::copy(var.begin(), var.end(), in.plane(3));
    for (const Driver driver : drivers(device))
      for (int level = 0; level <= 4; ++level)
        check_atrous_level(device, driver, frame, in, level, coverage);
  }
  coverage.require();
}

void prefilter_equals_gaussian(const TestDevice& device) {
  // OpenCV's 3x3 Gaussian: for ksize 3 and sigma 0 it uses its fixed table (1/4, 1/2, 1/4),
  // which is the paper's prefilter. Premise of the check, about OpenCV only.
  const cv::Mat g = cv::getGaussianKernel(3, 0, CV_64F);
  REQUIRE(g.at<double>(0) == 0.25);
  REQUIRE(g.at<double>(1) == 0.5);
  REQUIRE(g.at<double>(2) == 0.25);

  Coverage coverage;
  uint32_t seed = 200;
  for (const Size2 s : check_sizes()) {
    const int w = s.w, h = s.h;
    const Frame frame = random_frame(w, h, ++seed);
    Image var(w, h, 1), out(w, h, 1, -1.f);
    fill_uniform(var, 1e-3f, 2.f, ++seed);
    StageRunner r(device);
    r.run(PrefilterProbe{r.guides(frame), r.plane(static_cast<const Image&>(var)), r.plane(out)},
          w, h);

    const cv::Mat v = plane_mat(var, 0), ones = cv::Mat::ones(h, w, CV_64F);
    cv::Mat blurred, norm;
    cv::GaussianBlur(v, blurred, cv::Size(3, 3), 0, 0, cv::BORDER_CONSTANT);
    cv::GaussianBlur(ones, norm, cv::Size(3, 3), 0, 0, cv::BORDER_CONSTANT);
    const cv::Mat want = blurred / norm;
    // The same through sepFilter2D with the kernel spelled out: OpenCV's two routes agree.
    const cv::Mat k = (cv::Mat_<double>(3, 1) << 0.25, 0.5, 0.25);
    const cv::Mat want_sep = sep_filter(v, k) / sep_filter(ones, k);
    REQUIRE(cv::norm(want, want_sep, cv::NORM_INF) <= 1e-15);

    PlaneCheck check(std::string("variance prefilter (") + device.name() + ")", w, h, 1);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const double wv = want.at<double>(y, x);
        check.add(x, y, 0, out.at(x, y, 0), wv, kPrefilterTol * wv);
      }
    check.require();
    coverage.add(check);
  }
  coverage.require();
}

}  // namespace

SVGF_OPENCV_CHECK("opencv 1: a-trous with unit weights equals the dilated B3 sepFilter2D",
                  "[atrous]", atrous_unit_weights)
SVGF_OPENCV_CHECK("opencv 2: the 3x3 variance prefilter equals GaussianBlur and sepFilter2D",
                  "[atrous]", prefilter_equals_gaussian)

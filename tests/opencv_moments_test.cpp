// OpenCV checks 4 and 5 (docs/opencv-checks.md).
//  4a: over a static sequence the reprojection stage's accumulated color, luminance moments and
//      variance are the per-pixel temporal mean and variance, cv::meanStdDev.
//  4b: the variance stage's spatial estimate with every weight 1 is the 7x7 box mean of the
//      moments, cv::boxFilter / cv::sqrBoxFilter (unnormalized, BORDER_CONSTANT) divided by
//      the box sum of ones, boosted by 4 / history.
//  5:  luminance is cv::transform with the Rec. 709 coefficients, seen through the
//      reprojection stage's first frame (moment1 = l, moment2 = l^2).
#include <cmath>
#include <limits>
#include <string>

#include <catch2/catch.hpp>
#include <opencv2/imgproc.hpp>

#include "methods/svgf/reproject.h"
#include "methods/svgf/variance.h"
#include "opencv_support.h"

using namespace svgf;
using namespace svgf::cvtest;

namespace {

// Written out here, not taken from core/vec.h: the check must not share what it checks.
const cv::Matx13d kRec709(0.2126, 0.7152, 0.0722);  // R, G, B

// Luminance of every pixel in double through OpenCV.
cv::Mat luminance_cv(const Image& rgb) {
  cv::Mat l;
  cv::transform(rgb_mat(rgb), l, kRec709);
  return l;
}

// Float luminance (a*r + b*g) + c*b of positive values: three coefficient roundings, three
// products, two sums, at most four roundings on any path: gamma_4 -> 4u relative.
constexpr double kLuminanceTol = 5 * kU;
// Its square: 2 * 4u + u.
constexpr double kLuminanceSqTol = 10 * kU;

// Running mean m_n = m + (x - m) * fl(1/n) in float over N positive values <= X: each step
// adds at most 3u X / n (subtraction, 1/n, product) + u X (the sum), and earlier errors shrink
// by (1 - 1/n): |error| <= (3 H_N + N) u X, H_N the harmonic number.
double running_mean_tol(int frames) {
  double harmonic = 0;
  for (int k = 1; k <= frames; ++k) harmonic += 1.0 / k;
  return (3 * harmonic + frames) * kU;
}

// ------------------------------------------------------------------ check 5

void check_luminance(const TestDevice& device, const Image& illum, uint32_t seed, Coverage& coverage) {
  const int w = illum.width(), h = illum.height();
  const Frame frame = consistent_frame(w, h, seed);
  Image acc(w, h, 4, -1.f), moments(w, h, 2, -1.f), length(w, h, 1, -1.f);

  StageRunner r(device);
  ReprojectKernel k;
  k.guides = r.guides(frame);
  k.prev_guides = k.guides;
  k.illumination = r.rgb(static_cast<const Image&>(illum));
  k.prev_color = k.illumination;  // not read: no history
  k.has_history = false;          // first frame: moment1 = l, moment2 = l * l exactly
  k.accumulated = r.illum_var(acc);
  k.moment1 = r.plane(moments, 0);
  k.moment2 = r.plane(moments, 1);
  k.history = r.plane(length);
  r.run(k, w, h);

  const cv::Mat l = luminance_cv(illum);
  PlaneCheck check(std::string("luminance (") + device.name() + ")", w, h, 1);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double v = l.at<double>(y, x);
      check.add(x, y, 0, moments.at(x, y, 0), v, kLuminanceTol * v);
      check.add(x, y, 1, moments.at(x, y, 1), v * v, kLuminanceSqTol * v * v);
    }
  check.require();
  coverage.add(check);
}

void luminance_equals_transform(const TestDevice& device) {
  Coverage coverage;
  uint32_t seed = 500;
  for (const Size2 s : check_sizes()) {
    Image illum(s.w, s.h, 3);
    fill_uniform(illum, 0.05f, 10.f, ++seed);  // HDR
    check_luminance(device, illum, ++seed, coverage);
  }
  for (const Frame& f : fixture_frames()) check_luminance(device, f.color, ++seed, coverage);
  coverage.require();
}

// ------------------------------------------------------------------ check 4a

constexpr int kStaticFrames = 12;

void static_sequence_equals_meanstddev(const TestDevice& device) {
  Coverage coverage;
  uint32_t seed = 600;
  for (const Size2 s : check_sizes()) {
    const int w = s.w, h = s.h;
    const Frame frame = consistent_frame(w, h, ++seed);  // motion 0: each pixel reads itself
    std::vector<Image> illum;
    for (int f = 0; f < kStaticFrames; ++f) {
      illum.emplace_back(w, h, 3);
      fill_uniform(illum.back(), 0.05f, 3.f, ++seed);
    }

    // alpha = 0 and a cap above N: the blend factor is 1/n, an exact running mean.
    SvgfParams p = svgf_preset("falcor");  // the sample variance, no anti-lag
    p.alpha = 0.f;
    p.moments_alpha = 0.f;
    p.history_cap = 1000;
    Image acc(w, h, 4), moments(w, h, 2), length(w, h, 1);
    for (int f = 0; f < kStaticFrames; ++f) {
      const Image prev_acc = acc, prev_moments = moments, prev_length = length;
      StageRunner r(device);
      ReprojectKernel k;
      k.guides = r.guides(frame);
      k.prev_guides = k.guides;
      k.illumination = r.rgb(static_cast<const Image&>(illum[f]));
      k.prev_color = r.rgb(prev_acc);
      k.prev_moment1 = r.plane(prev_moments, 0);
      k.prev_moment2 = r.plane(prev_moments, 1);
      k.prev_history = r.plane(prev_length);
      k.has_history = f > 0;
      k.accumulated = r.illum_var(acc);
      k.moment1 = r.plane(moments, 0);
      k.moment2 = r.plane(moments, 1);
      k.history = r.plane(length);
      k.params = p;
      r.run(k, w, h);
    }

    std::vector<cv::Mat> lum;
    for (const Image& im : illum) lum.push_back(luminance_cv(im));
    const double t_mean = running_mean_tol(kStaticFrames);
    PlaneCheck check(std::string("static sequence moments (") + device.name() + ")", w,
                     h, 1);
    cv::Mat colors(kStaticFrames, 1, CV_64FC3), lums(kStaticFrames, 1, CV_64F);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        double cmax[3] = {0, 0, 0}, lmax = 0;
        for (int f = 0; f < kStaticFrames; ++f) {
          cv::Vec3d c(illum[f].at(x, y, 0), illum[f].at(x, y, 1), illum[f].at(x, y, 2));
          colors.at<cv::Vec3d>(f) = c;
          lums.at<double>(f) = lum[f].at<double>(y, x);
          for (int ch = 0; ch < 3; ++ch) cmax[ch] = std::max(cmax[ch], c[ch]);
          lmax = std::max(lmax, lum[f].at<double>(y, x));
        }
        cv::Scalar cmean, cstd, lmean, lstd;
        cv::meanStdDev(colors, cmean, cstd);
        cv::meanStdDev(lums, lmean, lstd);
        const double m1 = lmean[0], var = lstd[0] * lstd[0], m2 = var + m1 * m1;
        const double l2 = lmax * lmax;
        check.add(x, y, 6, length.at(x, y, 0), kStaticFrames, 0.0);  // history kept throughout
        for (int ch = 0; ch < 3; ++ch)
          check.add(x, y, ch, acc.at(x, y, ch), cmean[ch], t_mean * cmax[ch]);
        check.add(x, y, 4, moments.at(x, y, 0), m1, (t_mean + 4 * kU) * lmax);
        check.add(x, y, 5, moments.at(x, y, 1), m2, (t_mean + 9 * kU) * l2);
        // m2 - m1^2: e2 + 2 m1 e1 + rounding of the square and the difference.
        check.add(x, y, 3, acc.at(x, y, 3), var, (3 * t_mean + 19 * kU) * l2);
      }
    check.require();
    coverage.add(check);
  }
  coverage.require();
}

// ------------------------------------------------------------------ check 4b

// The spatial estimate through one driver, against OpenCV.
void check_spatial_variance(const TestDevice& device, Driver driver, const Frame& frame,
                            const Image& acc, const Image& moments, const Image& history,
                            Coverage& coverage) {
  const int w = acc.width(), h = acc.height();
  // Unit weights with random guides: no luminance or depth term (phi = inf: |d| / inf = 0;
  // at the centre 0 * inf = NaN, which the weight drops) and pow(., 0) = 1 for the normals.
  SvgfParams p = svgf_preset("falcor");  // the sample variance
  p.phi_color = std::numeric_limits<float>::infinity();
  p.spatial_variance_phi_depth = std::numeric_limits<float>::infinity();
  p.phi_normal = 0.f;
  Image out(w, h, 4, -1.f);
  StageRunner r(device);
  const VarianceKernel kernel{r.guides(frame), r.illum_var(acc), r.plane(moments, 0),
                              r.plane(moments, 1), r.plane(history), r.illum_var(out), p};
  if (driver == Driver::Rows)
    run_rows(r, kernel, w, h);
  else
    r.run(kernel, w, h);

  const int radius = p.spatial_variance_radius;
  const cv::Size box(2 * radius + 1, 2 * radius + 1);
  const auto box_sum = [&](const cv::Mat& src) {
    cv::Mat dst;
    cv::boxFilter(src, dst, CV_64F, box, cv::Point(-1, -1), false, cv::BORDER_CONSTANT);
    return dst;
  };
  cv::Mat sq_sum;
  const cv::Mat m1 = plane_mat(moments, 0);
  cv::sqrBoxFilter(m1, sq_sum, CV_64F, box, cv::Point(-1, -1), false, cv::BORDER_CONSTANT);
  const cv::Mat count = box_sum(cv::Mat::ones(h, w, CV_64F));
  const cv::Mat mean1 = box_sum(m1) / count, mean2 = sq_sum / count;

  // Color: 49 exact products, 48 sums, one division: gamma_49 -> 50u relative.
  // Variance: sums of m1 (49u) and of the rounded squares (50u); m2 - m1^2 <= 150u * m2 as
  // m1^2 <= m2; the boost 4/h and its product add 2u.
  PlaneCheck check("spatial variance (" + driver_name(device, driver) + ")", w, h, radius);
  for (int c = 0; c < 3; ++c) {
    const cv::Mat want = box_sum(plane_mat(acc, c)) / count;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const double v = want.at<double>(y, x);
        check.add(x, y, c, out.at(x, y, c), v, 50 * kU * v);
      }
  }
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double a = mean1.at<double>(y, x), b = mean2.at<double>(y, x);
      const double boost = 4.0 / history.at(x, y, 0);
      const double want = std::max(0.0, b - a * a) * boost;
      check.add(x, y, 3, out.at(x, y, 3), want, 152 * kU * b * boost);
    }
  check.require();
  coverage.add(check);
}

void spatial_variance_equals_box(const TestDevice& device) {
  Coverage coverage;
  uint32_t seed = 700;
  for (const Size2 s : check_sizes()) {
    const size_t n = static_cast<size_t>(s.w) * s.h;
    const Frame frame = random_frame(s.w, s.h, ++seed);
    Image acc(s.w, s.h, 4), moments(s.w, s.h, 2), history(s.w, s.h, 1);
    fill_uniform(acc, 0.05f, 3.f, ++seed);
    const std::vector<float> m1 = uniform_values(n, 0.05f, 3.f, ++seed);
    std::mt19937 rng(++seed);
    std::uniform_int_distribution<int> young(1, 3);  // history < 4: the spatial estimate
    for (size_t i = 0; i < n; ++i) {
      moments.plane(0)[i] = m1[i];
      moments.plane(1)[i] = m1[i] * m1[i];  // a first frame's moments: E[l^2] = l^2
      history.plane(0)[i] = static_cast<float>(young(rng));
    }
    for (const Driver driver : drivers(device))
      check_spatial_variance(device, driver, frame, acc, moments, history, coverage);
  }
  coverage.require();
}

}  // namespace

SVGF_OPENCV_CHECK("opencv 4a: moments and variance of a static sequence equal meanStdDev",
                  "[moments]", static_sequence_equals_meanstddev)
SVGF_OPENCV_CHECK("opencv 4b: the unit-weight spatial variance equals boxFilter and sqrBoxFilter",
                  "[moments]", spatial_variance_equals_box)
SVGF_OPENCV_CHECK("opencv 5: luminance equals transform with the Rec. 709 coefficients",
                  "[luminance]", luminance_equals_transform)

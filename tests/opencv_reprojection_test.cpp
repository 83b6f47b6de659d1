// OpenCV check 3 (docs/opencv-checks.md): the reprojection stage's bilinear history read, with
// every tap passing the consistency tests, equals cv::remap (INTER_LINEAR, BORDER_CONSTANT 0)
// divided by the remap of a ones mask, which reproduces the project's border rule (taps outside
// the previous image skipped, the bilinear weights renormalized).
//
// cv::remap rounds each coordinate to 1/32 pixel (INTER_BITS = 5). Two variants:
//   grid motion (multiples of 1/32): remap is exact bilinear; the tolerance is float rounding;
//   arbitrary motion: the 1/64-pixel coordinate error adds at most G/32, G the largest forward
//   difference of the image around the tap cell (the bilinear interpolant's slope bound).
#include <cmath>
#include <limits>
#include <string>

#include <catch2/catch.hpp>
#include <opencv2/imgproc.hpp>

#include "methods/svgf/reproject.h"
#include "opencv_support.h"
#include "synthetic_sequence.h"

using namespace svgf;
using namespace svgf::cvtest;

namespace {

// Float rounding of the history read: up to 4 positive products and 3 sums (gamma_4), one
// division by the exact weight sum: 5u. 7u leaves room for OpenCV's double arithmetic and its
// float tap weights (exact on the 1/32 grid, within u elsewhere).
constexpr double kBilinearTol = 7 * kU;
// Pixels whose in-image bilinear weight is below this are left out: the stage switches to its
// 3x3 fallback below 0.01, and remap's quantized weight may differ from the exact one by 1/32.
constexpr double kMinWeight = 0.05;
// History length 2^24 with cap 2^25 and alpha = 0: the new sample enters with weight
// 1 / 2^24 exactly, so the output is h + (c - h) * 2^-24, h the history read.
constexpr float kLongHistory = 16777216.f;
constexpr double kBlend = 1.0 / 16777216.0;
constexpr double kMaxMotion = 3.5;

// Rec. 709 luminance, written out here (not core's), for the moments' blend term.
double luminance709(double r, double g, double b) { return 0.2126 * r + 0.7152 * g + 0.0722 * b; }

// A smooth random field: a sum of a few random plane waves (wavelengths 12-40 px) around
// `mean`, plus 1% white noise. Keeps G, and so the arbitrary-motion tolerance, small.
void fill_smooth(float* out, int w, int h, float mean, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  double kx[4], ky[4], ph[4], amp[4];
  for (int t = 0; t < 4; ++t) {
    const double len = 12.0 + 28.0 * u01(rng), ang = 6.2831853 * u01(rng);
    kx[t] = 6.2831853 / len * std::cos(ang);
    ky[t] = 6.2831853 / len * std::sin(ang);
    ph[t] = 6.2831853 * u01(rng);
    amp[t] = 0.1 * mean * (0.5 + u01(rng));
  }
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double v = mean * (1.0 + 0.01 * (u01(rng) - 0.5));
      for (int t = 0; t < 4; ++t) v += amp[t] * std::sin(kx[t] * x + ky[t] * y + ph[t]);
      out[y * w + x] = static_cast<float>(v);
    }
}

// Largest |forward difference| between in-image neighbours of the 4x4 block around the tap
// cell (x0, y0): bounds the slope of the (renormalized) bilinear interpolant wherever the
// exact and the 1/32-rounded coordinates can lie.
double local_slope(const cv::Mat& f, int x0, int y0) {
  double g = 0;
  for (int y = std::max(0, y0 - 1); y <= std::min(f.rows - 1, y0 + 2); ++y)
    for (int x = std::max(0, x0 - 1); x <= std::min(f.cols - 1, x0 + 2); ++x) {
      if (x + 1 < f.cols && x + 1 <= x0 + 2)
        g = std::max(g, std::fabs(f.at<double>(y, x + 1) - f.at<double>(y, x)));
      if (y + 1 < f.rows && y + 1 <= y0 + 2)
        g = std::max(g, std::fabs(f.at<double>(y + 1, x) - f.at<double>(y, x)));
    }
  return g;
}

// Exact (double) in-image bilinear weight at p: what the stage renormalizes by.
double inside_weight(double px, double py, int w, int h) {
  const double x0 = std::floor(px), y0 = std::floor(py), fx = px - x0, fy = py - y0;
  const auto in = [](double v, int n) { return v >= 0 && v < n; };
  const double wx = (in(x0, w) ? 1 - fx : 0) + (in(x0 + 1, w) ? fx : 0);
  const double wy = (in(y0, h) ? 1 - fy : 0) + (in(y0 + 1, h) ? fy : 0);
  return wx * wy;
}

// One reprojection against remap. `color`, when given, is the color history (a fixture image);
// otherwise it is made up as described below.
void check_reprojection(const TestDevice& device, bool grid_motion, int w, int h, const Image* color,
                        uint32_t seed, Coverage& coverage) {
  const size_t n = static_cast<size_t>(w) * h;
  Frame frame = consistent_frame(w, h, ++seed);
  const Frame prev = frame;  // same guides: every in-image tap is consistent

  // Motion into the previous frame, up to 3.5 px: border pixels reach outside.
  std::mt19937 rng(++seed);
  std::uniform_int_distribution<int> grid(-112, 112);  // k / 32
  std::uniform_real_distribution<float> any(-3.5f, 3.5f);
  for (size_t i = 0; i < n; ++i)
    for (int c = 0; c < 2; ++c)
      frame.motion.plane(c)[i] = grid_motion ? static_cast<float>(grid(rng)) / 32.f : any(rng);

  // History planes: 0-2 color, 3-4 moments. Grid motion: the synthetic scene's noisy color
  // (sharp edges, multiplicative noise) and white-noise moments; arbitrary motion: smooth
  // fields so the slope bound is small.
  Image history(w, h, 5);
  if (color) {
    std::copy(color->data().begin(), color->data().end(), history.plane(0));
    const std::vector<float> m = uniform_values(2 * n, 0.05f, 2.f, ++seed);
    std::copy(m.begin(), m.end(), history.plane(3));
  } else if (grid_motion) {
    test::SyntheticScene scene;
    scene.width = w;
    scene.height = h;
    scene.seed = seed;
    const Frame f = scene.frame(3);
    std::copy(f.color.data().begin(), f.color.data().end(), history.plane(0));
    const std::vector<float> m = uniform_values(2 * n, 0.05f, 2.f, ++seed);
    std::copy(m.begin(), m.end(), history.plane(3));
  } else {
    for (int c = 0; c < 5; ++c) fill_smooth(history.plane(c), w, h, 0.5f + 0.3f * c, ++seed);
  }
  Image prev_length(w, h, 1, kLongHistory);
  Image illum(w, h, 3);
  fill_uniform(illum, 0.05f, 3.f, ++seed);

  SvgfParams p = svgf_preset("falcor");  // no anti-lag: the blend alone
  p.alpha = 0.f;
  p.moments_alpha = 0.f;
  p.history_cap = 1 << 25;
  Image acc(w, h, 4, -1.f), moments(w, h, 2, -1.f), length(w, h, 1, -1.f);
  StageRunner r(device);
  ReprojectKernel k;
  k.guides = r.guides(frame);
  k.prev_guides = r.guides(prev);
  k.illumination = r.rgb(static_cast<const Image&>(illum));
  k.prev_color = r.rgb(static_cast<const Image&>(history));
  k.prev_moment1 = r.plane(static_cast<const Image&>(history), 3);
  k.prev_moment2 = r.plane(static_cast<const Image&>(history), 4);
  k.prev_history = r.plane(static_cast<const Image&>(prev_length));
  k.has_history = true;
  k.accumulated = r.illum_var(acc);
  k.moment1 = r.plane(moments, 0);
  k.moment2 = r.plane(moments, 1);
  k.history = r.plane(length);
  k.params = p;
  r.run(k, w, h);

  // Maps: the very float coordinates the stage computes, x + motion.
  cv::Mat map_x(h, w, CV_32F), map_y(h, w, CV_32F);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      map_x.at<float>(y, x) = static_cast<float>(x) + frame.motion.at(x, y, 0);
      map_y.at<float>(y, x) = static_cast<float>(y) + frame.motion.at(x, y, 1);
    }
  const auto remap = [&](const cv::Mat& src) {
    cv::Mat dst;
    cv::remap(src, dst, map_x, map_y, cv::INTER_LINEAR, cv::BORDER_CONSTANT, cv::Scalar(0));
    return dst;
  };
  const cv::Mat mask = remap(cv::Mat::ones(h, w, CV_64F));
  cv::Mat want[5], plane[5];
  for (int c = 0; c < 5; ++c) {
    plane[c] = plane_mat(history, c);
    want[c] = remap(plane[c]) / mask;  // 0/0 where nothing is inside: left out below
  }

  PlaneCheck check(std::string(grid_motion ? "reproject, 1/32-grid motion (" :
                                             "reproject, arbitrary motion (") +
                       device.name() + ")",
                   w, h, static_cast<int>(std::ceil(kMaxMotion)) + 1);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double px = map_x.at<float>(y, x), py = map_y.at<float>(y, x);
      if (mask.at<double>(y, x) < kMinWeight || inside_weight(px, py, w, h) < kMinWeight) {
        check.skip();
        continue;
      }
      // The premise of the blend bound: the stage kept the history, length 2^24.
      check.add(x, y, 5, length.at(x, y, 0), kLongHistory, 0.0);
      const int x0 = static_cast<int>(std::floor(px)), y0 = static_cast<int>(std::floor(py));
      const double l = luminance709(illum.at(x, y, 0), illum.at(x, y, 1), illum.at(x, y, 2));
      for (int c = 0; c < 5; ++c) {
        const double v = want[c].at<double>(y, x);
        // The new sample's 2^-24 share is added exactly; the float rounding of that tiny
        // term (a few u of it) is covered by the last summand.
        const double sample = c < 3 ? illum.at(x, y, c) : (c == 3 ? l : l * l);
        const double blended = v + (sample - v) * kBlend;
        double tol = kBilinearTol * std::fabs(v) +
                     16 * kU * kBlend * (std::fabs(sample) + std::fabs(v));
        if (!grid_motion) tol += local_slope(plane[c], x0, y0) / 32.0;
        const double got = c < 3 ? acc.at(x, y, c) : moments.at(x, y, c - 3);
        check.add(x, y, c, got, blended, tol);
      }
    }
  check.require();
  coverage.add(check);
}

void reprojection_equals_remap(const TestDevice& device, bool grid_motion) {
  Coverage coverage;
  uint32_t seed = grid_motion ? 300 : 400;
  for (const Size2 s : check_sizes()) {
    check_reprojection(device, grid_motion, s.w, s.h, nullptr, seed, coverage);
    seed += 100;
  }
  // Fixture colors: exact check on the 1/32 grid (their sharp edges make the slope bound loose).
  if (grid_motion)
    for (const Frame& f : fixture_frames()) {
      check_reprojection(device, true, f.width(), f.height(), &f.color, seed, coverage);
      seed += 100;
    }
  coverage.require();
}

void reprojection_grid(const TestDevice& b) { reprojection_equals_remap(b, true); }
void reprojection_any(const TestDevice& b) { reprojection_equals_remap(b, false); }

}  // namespace

SVGF_OPENCV_CHECK("opencv 3a: bilinear reprojection equals remap on the 1/32 grid",
                  "[reproject]", reprojection_grid)
SVGF_OPENCV_CHECK("opencv 3b: bilinear reprojection equals remap within its 1/32 px rounding",
                  "[reproject]", reprojection_any)

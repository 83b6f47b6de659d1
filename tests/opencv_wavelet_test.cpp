// OpenCV check 10 (docs/opencv-checks.md): a pass of the CIS 565 wavelet filter with every
// edge-stopping weight forced to 1 is the binomial kernel of its size, dilated by 2^pass
// (cv::sepFilter2D), under the project's border rule (out-of-image taps skipped, weights
// renormalized: filter(data) / filter(ones) with BORDER_CONSTANT). OpenCV runs in double.
#include <limits>
#include <string>
#include <utility>

#include <catch2/catch.hpp>
#include <opencv2/imgproc.hpp>

#include "methods/wavelet/atrous.h"
#include "opencv_support.h"

using namespace svgf;
using namespace svgf::cvtest;

namespace {

// Row `size - 1` of Pascal's triangle over 2^(size - 1), written out here (not taken from
// methods/wavelet/atrous.h), taps `step` apart.
cv::Mat binomial_dilated(int size, int step) {
  cv::Mat k = cv::Mat::zeros((size - 1) * step + 1, 1, CV_64F);
  double c = 1;
  for (int t = 0; t < size; ++t) {
    k.at<double>(t * step) = c / std::pow(2.0, size - 1);
    c = c * (size - 1 - t) / (t + 1);
  }
  return k;
}

void wavelet_unit_weights(const TestDevice& device) {
  Coverage coverage;
  uint32_t seed = 300;
  for (const Size2 s : check_sizes())
    for (int size : {3, 5, 7, 9})
      for (int level = 0; level <= 3; ++level) {
        const int w = s.w, h = s.h, step = 1 << level;
        const Frame frame = random_frame(w, h, ++seed);  // depth > 0, normals near +z
        Image in(w, h, 3), luma(w, h, 1), dev(w, h, 1), out(w, h, 3, -1.f);
        fill_uniform(in, 0.05f, 4.f, ++seed);
        fill_uniform(luma, 0.f, 2.f, ++seed);
        fill_uniform(dev, 0.01f, 1.f, ++seed);
        // 1 / (sigma_Z + eps) = 0 and sigma_L = Inf: no depth or luma term; sigma_N = 0:
        // normal term pow(cos, 0) = 1. Every weight is exactly 1.
        StageRunner r(device);
        using Power = NormalPower<ExactArith>;
        r.run(WaveletIteration<ExactArith, Power>{r.guides(frame), r.rgb(std::as_const(in)),
                                                  r.rgb(out), r.plane(std::as_const(luma)),
                                                  r.plane(std::as_const(dev)), step, size, 0.f,
                                                  std::numeric_limits<float>::infinity(), 0.01f,
                                                  Power::of(0.f)},
              w, h, "wavelet unit weights");
        const cv::Mat k = binomial_dilated(size, step);
        cv::Mat norm;
        cv::sepFilter2D(cv::Mat::ones(h, w, CV_64F), norm, CV_64F, k, k, cv::Point(-1, -1), 0,
                        cv::BORDER_CONSTANT);
        // size^2 positive terms: one rounding per product and sum, one for the division.
        const double tol = (size * size + 3) * kU;
        PlaneCheck check("wavelet " + std::to_string(size) + "x" + std::to_string(size) +
                             " level " + std::to_string(level) + " (" + device.name() + ")",
                         w, h, (size / 2) * step);
        for (int c = 0; c < 3; ++c) {
          cv::Mat filtered;
          cv::sepFilter2D(plane_mat(in, c), filtered, CV_64F, k, k, cv::Point(-1, -1), 0,
                          cv::BORDER_CONSTANT);
          const cv::Mat want = filtered / norm;
          for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
              const double v = want.at<double>(y, x);
              check.add(x, y, c, out.at(x, y, c), v, tol * v);
            }
        }
        check.require();
        coverage.add(check);
      }
  coverage.require();
}

}  // namespace

SVGF_OPENCV_CHECK("opencv 10: a wavelet pass with unit weights equals the dilated binomial "
                  "sepFilter2D, every kernel size",
                  "[wavelet]", wavelet_unit_weights)

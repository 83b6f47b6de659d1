// OpenCV check 9 (docs/opencv-checks.md): the Gaussian baseline's two passes against
// cv::sepFilter2D with cv::getGaussianKernel, in double. The project's border rule (taps outside
// skipped, weights renormalized) is OpenCV's filter(data) / filter(ones) with BORDER_CONSTANT.
// The kernel weights are OpenCV's own (getGaussianKernel normalizes them; the ratio does not
// depend on that), so the check shares nothing with methods/gaussian/ but the formula's name.
#include <string>

#include <catch2/catch.hpp>
#include <opencv2/imgproc.hpp>

#include "methods/gaussian/blur.h"
#include "methods/gaussian/params.h"
#include "opencv_support.h"

using namespace svgf;
using namespace svgf::cvtest;

namespace {

// Each weight det_exp (2 ulp), 2r+1 products and sums in float, one division; twice (two
// passes, the second on the first's rounded output). For r <= 9: gamma_(2 * 22) plus the
// exp error, rounded up to 64u.
constexpr double kGaussianTol = 64 * kU;

void check_gaussian(const TestDevice& device) {
  Coverage coverage;
  for (const auto& [sigma, radius] : {std::pair<float, int>{2.f, 0}, {1.f, 3}, {3.f, 9}}) {
    for (Size2 s : check_sizes()) {
      const int w = s.w, h = s.h;
      GaussianParams gp;
      gp.sigma = sigma;
      gp.radius = radius;
      const int r = gp.effective_radius();
      Image in(w, h, 3), mid(w, h, 3, -1.f), out(w, h, 3, -1.f);
      fill_uniform(in, 0.f, 3.f, 91u + static_cast<uint32_t>(w));
      StageRunner run(device);
      GaussianPass<> pass{w, h, run.rgb(static_cast<const Image&>(in)), run.rgb(mid), 1, 0, r,
                          -1.f / (2.f * sigma * sigma)};
      run.run(pass, w, h);
      pass.in = run.rgb(static_cast<const Image&>(mid));
      pass.out = run.rgb(out);
      pass.dx = 0;
      pass.dy = 1;
      run.run(pass, w, h);

      const cv::Mat k = cv::getGaussianKernel(2 * r + 1, sigma, CV_64F);
      auto filter = [&](const cv::Mat& src) {
        cv::Mat dst;
        cv::sepFilter2D(src, dst, CV_64F, k, k, cv::Point(-1, -1), 0, cv::BORDER_CONSTANT);
        return dst;
      };
      const cv::Mat norm = filter(cv::Mat::ones(h, w, CV_64F));
      PlaneCheck check("gaussian sigma " + std::to_string(sigma) + " r " + std::to_string(r) +
                           " (" + device.name() + ")",
                       w, h, r);
      for (int c = 0; c < 3; ++c) {
        const cv::Mat want = filter(plane_mat(in, c)) / norm;
        for (int y = 0; y < h; ++y)
          for (int x = 0; x < w; ++x) {
            const double v = want.at<double>(y, x);
            check.add(x, y, c, out.at(x, y, c), v, kGaussianTol * v + 1e-30);
          }
      }
      check.require();
      coverage.add(check);
    }
  }
  coverage.require();
}

}  // namespace

SVGF_OPENCV_CHECK("opencv 9: the Gaussian baseline equals cv::sepFilter2D(getGaussianKernel)",
                  "[gaussian]", check_gaussian)

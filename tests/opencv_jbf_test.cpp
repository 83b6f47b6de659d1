// OpenCV check 7 (docs/opencv-checks.md): the joint bilateral filter's full-window pass
// (methods/jbf/filter.h) against cv::ximgproc::jointBilateralFilter where the two mean the same
// thing: flat guides (normals +z, positions on the plane z = 0: the normal and plane terms are
// exactly 0), a gray image as its own guide (OpenCV weighs colors by the L1 distance over the
// channels, |c_i - c_j|_1 = 3 |d| for gray, the JBF by the Euclidean one, |c_i - c_j|^2 = 3 d^2:
// the same weight when sigma_color = sigma_cv / sqrt(3)), and interior pixels only (OpenCV pads
// the border, the JBF skips outside taps). OpenCV's support is a disc of radius d / 2, the JBF's
// a square: with sigma_space 1.5 and radius 10 the corner taps outside the disc weigh below
// exp(-101 / 4.5) = 2e-10. OpenCV interpolates its range weight in a 4096-bin table (float
// images): the tolerance is 1e-5 relative.
#include <cmath>
#include <string>
#include <utility>

#include <catch2/catch.hpp>
#include <opencv2/ximgproc/edge_filter.hpp>

#include "methods/jbf/filter.h"
#include "opencv_support.h"

using namespace svgf;
using namespace svgf::cvtest;

namespace {

void jbf_equals_joint_bilateral(const TestDevice& device) {
  constexpr int kRadius = 10;
  constexpr double kSigmaSpace = 1.5, kSigmaColorCv = 0.35;
  for (const Size2 s : {Size2{257, 89}, Size2{64, 48}}) {
    const int w = s.w, h = s.h;
    Frame frame = consistent_frame(w, h, 400u + static_cast<uint32_t>(w));
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        frame.normal.at(x, y, 0) = frame.normal.at(x, y, 1) = 0.f;
        frame.normal.at(x, y, 2) = 1.f;
        frame.position.at(x, y, 0) = 0.1f * x;
        frame.position.at(x, y, 1) = 0.1f * y;
        frame.position.at(x, y, 2) = 0.f;
      }
    // Gray noise with some structure: smooth ramps plus uniform noise, values in [0, 1].
    const std::vector<float> noise = uniform_values(frame.color.pixel_count(), 0.f, 0.5f, 17u);
    Image gray(w, h, 3), out(w, h, 3, -1.f);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const float v = 0.25f * (1.f + std::sin(0.1f * x) * std::cos(0.07f * y)) + noise[y * w + x];
        for (int c = 0; c < 3; ++c) gray.at(x, y, c) = v;
      }
    JbfParams p;
    p.radius = kRadius;
    p.sigma_coord = static_cast<float>(kSigmaSpace);
    p.sigma_color = static_cast<float>(kSigmaColorCv / std::sqrt(3.0));
    StageRunner r(device);
    r.run(JbfPass<ExactArith>{r.guides(frame), r.rgb(std::as_const(frame.position)),
                              r.rgb(std::as_const(gray)), r.rgb(out), kRadius, 1, false,
                              JbfScales::of(p)},
          w, h, "jbf full window");

    cv::Mat src = rgb_mat(gray, 0, CV_32F), dst;
    cv::ximgproc::jointBilateralFilter(src, src, dst, 2 * kRadius + 1, kSigmaColorCv, kSigmaSpace,
                                       cv::BORDER_REFLECT_101);
    PlaneCheck check("jbf full window (" + device.name() + ")", w, h, kRadius);
    for (int y = kRadius; y < h - kRadius; ++y)
      for (int x = kRadius; x < w - kRadius; ++x)
        for (int c = 0; c < 3; ++c) {
          const double want = dst.at<cv::Vec3f>(y, x)[c];
          check.add(x, y, c, out.at(x, y, c), want, 1e-5 * std::fabs(want) + 1e-7);
        }
    INFO(check.summary());
    REQUIRE(check.interior().count > 0);
    check.require();
  }
}

}  // namespace

SVGF_OPENCV_CHECK("opencv 7: the JBF's full window equals ximgproc::jointBilateralFilter on flat "
                  "guides and a gray image",
                  "[jbf]", jbf_equals_joint_bilateral)

#include "bench/baselines.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#if defined(SVGF_BENCH_HAVE_OPENCV)
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/photo.hpp>
#include <opencv2/ximgproc/edge_filter.hpp>
#endif

namespace svgf::bench {

std::string Baseline::label() const {
  std::ostringstream s;
  s << name;
  if (name == "cv-gaussian") s << " s" << p1;
  if (name == "cv-bilateral" || name == "cv-joint-bilateral") s << " d" << p1 << " c" << p2;
  if (name == "cv-nlmeans") s << " h" << p1;
  return s.str();
}

bool is_baseline(const std::string& method) { return method.rfind("cv-", 0) == 0; }

std::string baseline_names() {
  std::vector<std::string> seen;
  std::string names;
  for (const Baseline& b : default_baselines())
    if (std::find(seen.begin(), seen.end(), b.name) == seen.end()) {
      seen.push_back(b.name);
      names += (names.empty() ? "" : ", ") + b.name;
    }
  return names;
}

std::vector<Baseline> default_baselines() {
  return {
      {"cv-gaussian", 1.0, 0, 0},
      {"cv-gaussian", 3.0, 0, 0},
      // Color sigmas in linear radiance for the HDR color, in albedo units for the guide.
      {"cv-bilateral", 9, 0.5, 4.0},
      {"cv-joint-bilateral", 9, 0.1, 4.0},
      // On 8-bit Reinhard-mapped color (fastNlMeansDenoisingColored takes 8-bit only).
      {"cv-nlmeans", 10, 10, 21},
  };
}

Baseline baseline_by_name(const std::string& name) {
  for (const Baseline& b : default_baselines())
    if (b.name == name) return b;
  throw std::invalid_argument("unknown baseline '" + name + "' (known: " + baseline_names() + ")");
}

#if defined(SVGF_BENCH_HAVE_OPENCV)

bool baselines_available() { return true; }

namespace {

float sanitized(float v) { return v >= 0.f && std::isfinite(v) ? v : 0.f; }

cv::Mat to_mat(const Image& im, bool sanitize) {
  cv::Mat m(im.height(), im.width(), CV_32FC3);
  const size_t n = im.pixel_count();
  const float* r = im.plane(0);
  const float* g = im.plane(1);
  const float* b = im.plane(2);
  float* d = m.ptr<float>();
  for (size_t i = 0; i < n; ++i) {
    d[3 * i + 0] = sanitize ? sanitized(r[i]) : r[i];
    d[3 * i + 1] = sanitize ? sanitized(g[i]) : g[i];
    d[3 * i + 2] = sanitize ? sanitized(b[i]) : b[i];
  }
  return m;
}

void from_mat(const cv::Mat& m, Image& out) {
  out = Image(m.cols, m.rows, 3);
  const size_t n = out.pixel_count();
  const float* s = m.ptr<float>();
  for (int c = 0; c < 3; ++c) {
    float* d = out.plane(c);
    for (size_t i = 0; i < n; ++i) d[i] = s[3 * i + c];
  }
}

// NL-means takes 8 bits: Reinhard x / (1 + x) to [0, 255] and back (inverse y / (1 - y), with
// y kept below 1 so the brightest code stays finite).
cv::Mat to_8bit(const cv::Mat& hdr) {
  cv::Mat ldr(hdr.size(), CV_8UC3);
  const size_t n = hdr.total() * 3;
  const float* s = hdr.ptr<float>();
  uint8_t* d = ldr.ptr<uint8_t>();
  for (size_t i = 0; i < n; ++i)
    d[i] = static_cast<uint8_t>(std::lround(255.f * (s[i] / (1.f + s[i]))));
  return ldr;
}

cv::Mat from_8bit(const cv::Mat& ldr) {
  cv::Mat hdr(ldr.size(), CV_32FC3);
  const size_t n = ldr.total() * 3;
  const uint8_t* s = ldr.ptr<uint8_t>();
  float* d = hdr.ptr<float>();
  for (size_t i = 0; i < n; ++i) {
    const float y = std::min(static_cast<float>(s[i]), 254.5f) / 255.f;
    d[i] = y / (1.f - y);
  }
  return hdr;
}

}  // namespace

void run_baseline(const Baseline& b, const Frame& in, Image& out) {
  const cv::Mat src = to_mat(in.color, true);
  cv::Mat dst;
  if (b.name == "cv-gaussian") {
    cv::GaussianBlur(src, dst, cv::Size(0, 0), b.p1);
  } else if (b.name == "cv-bilateral") {
    cv::bilateralFilter(src, dst, static_cast<int>(b.p1), b.p2, b.p3);
  } else if (b.name == "cv-joint-bilateral") {
    cv::ximgproc::jointBilateralFilter(to_mat(in.albedo, true), src, dst, static_cast<int>(b.p1),
                                       b.p2, b.p3);
  } else if (b.name == "cv-nlmeans") {
    cv::Mat ldr;
    cv::fastNlMeansDenoisingColored(to_8bit(src), ldr, static_cast<float>(b.p1),
                                    static_cast<float>(b.p2), 7, static_cast<int>(b.p3));
    dst = from_8bit(ldr);
  } else {
    throw std::invalid_argument("unknown baseline '" + b.name + "'");
  }
  from_mat(dst, out);
}

void set_baseline_threads(int threads) { cv::setNumThreads(threads > 0 ? threads : -1); }

#else

bool baselines_available() { return false; }

void run_baseline(const Baseline& b, const Frame&, Image&) {
  throw std::runtime_error("baseline '" + b.name + "': this build has no OpenCV");
}

void set_baseline_threads(int) {}

#endif

}  // namespace svgf::bench

#pragma once
// Shared pieces of the OpenCV cross-checks (docs/opencv-checks.md): Image <-> cv::Mat
// conversion, a per-pixel comparison that tallies edge and interior pixels separately, seeded
// random guides, and the drivers a check runs a stage through (tests/test_device.h runs it on
// each backend).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include <catch2/catch.hpp>
#include <opencv2/core.hpp>

#include "methods/svgf/atrous.h"
#include "pipeline/make_denoiser.h"
#include "core/frame.h"
#include "core/image.h"
#include "methods/svgf/variance.h"
#include "core/views.h"
#include "io/sequence.h"
#include "kernels_cpu/svgf_rows.h"
#include "kernels_cpu/parallel_for.h"
#include "opencv_probe.h"
#include "test_device.h"

namespace svgf::cvtest {

// Unit roundoff of float with round-to-nearest: every tolerance is a count of these.
constexpr double kU = 1.0 / 16777216.0;  // 2^-24

// Image sizes every backend check runs on: odd, even, tiny (wider kernels than the image) and
// the 257x89.
struct Size2 {
  int w, h;
};
inline const std::vector<Size2>& check_sizes() {
  static const std::vector<Size2> sizes = {{257, 89}, {64, 48}, {31, 17}, {7, 5}};
  return sizes;
}

// ---------------------------------------------------------------- Image <-> cv::Mat

// Channel c as a CV_64F matrix (float -> double is exact, so OpenCV then works in double).
inline cv::Mat plane_mat(const Image& im, int c) {
  cv::Mat m(im.height(), im.width(), CV_64F);
  for (int y = 0; y < im.height(); ++y)
    for (int x = 0; x < im.width(); ++x) m.at<double>(y, x) = im.at(x, y, c);
  return m;
}

// Channels first..first+2 interleaved, in R, G, B order (not OpenCV's BGR: no cv function used
// here cares about the order except cv::transform, whose coefficients are given in R, G, B).
inline cv::Mat rgb_mat(const Image& im, int first = 0, int depth = CV_64F) {
  cv::Mat m(im.height(), im.width(), CV_64FC3);
  for (int y = 0; y < im.height(); ++y)
    for (int x = 0; x < im.width(); ++x)
      m.at<cv::Vec3d>(y, x) = cv::Vec3d(im.at(x, y, first), im.at(x, y, first + 1),
                                        im.at(x, y, first + 2));
  if (depth == CV_64F) return m;
  cv::Mat out;
  m.convertTo(out, depth);
  return out;
}

// ---------------------------------------------------------------- comparison

// Compares computed values with OpenCV's pixel by pixel, each against its own tolerance.
// Pixels within `border` of an image edge (where some taps fall outside) count as edge pixels,
// the rest as interior, so a test can show it exercised both.
class PlaneCheck {
 public:
  struct Tally {
    size_t count = 0;
    double max_error = 0;   // largest |got - want|
    double max_ratio = 0;   // largest |got - want| / tolerance
  };

  PlaneCheck(std::string what, int width, int height, int border)
      : what_(std::move(what)), w_(width), h_(height), border_(border) {}

  void add(int x, int y, int c, double got, double want, double tol) {
    const double err = std::fabs(got - want);
    const bool edge = x < border_ || y < border_ || x >= w_ - border_ || y >= h_ - border_;
    Tally& t = edge ? edge_ : interior_;
    ++t.count;
    if (!(err <= tol)) {  // NaN fails too
      if (bad_ < 5)
        first_bad_ << "\n    (" << x << "," << y << ") ch " << c << ": got " << got << " want "
                   << want << " |diff| " << err << " tol " << tol;
      ++bad_;
    }
    t.max_error = std::max(t.max_error, err);
    if (tol > 0) t.max_ratio = std::max(t.max_ratio, err / tol);
  }
  void skip() { ++skipped_; }

  const Tally& edge() const { return edge_; }
  const Tally& interior() const { return interior_; }
  size_t bad() const { return bad_; }

  std::string summary() const {
    std::ostringstream s;
    s << what_ << " " << w_ << "x" << h_ << ": " << edge_.count << " edge values (max err "
      << edge_.max_error << ", " << edge_.max_ratio << " of tol), " << interior_.count
      << " interior (max err " << interior_.max_error << ", " << interior_.max_ratio
      << " of tol)";
    if (skipped_) s << ", " << skipped_ << " skipped";
    if (bad_) s << "; " << bad_ << " OUTSIDE tolerance:" << first_bad_.str();
    return s.str();
  }

  void require() const {
    INFO(summary());
    REQUIRE(bad_ == 0);
  }

 private:
  std::string what_;
  int w_, h_, border_;
  Tally edge_, interior_;
  size_t bad_ = 0, skipped_ = 0;
  std::ostringstream first_bad_;
};

// Edge and interior pixels compared over a whole test (over all sizes): both must be non-zero.
struct Coverage {
  size_t edge = 0, interior = 0;
  double worst_ratio = 0;  // largest error / tolerance seen
  void add(const PlaneCheck& c) {
    edge += c.edge().count;
    interior += c.interior().count;
    worst_ratio = std::max({worst_ratio, c.edge().max_ratio, c.interior().max_ratio});
  }
  void require() const {
    INFO("compared " << edge << " edge and " << interior << " interior values; worst error "
                     << worst_ratio << " of its tolerance");
    REQUIRE(edge > 0);
    REQUIRE(interior > 0);
  }
};

// ---------------------------------------------------------------- data

inline std::vector<float> uniform_values(size_t n, float lo, float hi, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> d(lo, hi);
  std::vector<float> v(n);
  for (float& x : v) x = d(rng);
  return v;
}

inline void fill_uniform(Image& im, float lo, float hi, uint32_t seed) {
  im.data() = uniform_values(im.data().size(), lo, hi, seed);
}

// A frame with random guides: depth in [1, 5] (a surface everywhere), unit normals within 10
// degrees of +z, random depth gradients and mesh ids, zero motion; color and albedo random.
inline Frame random_frame(int w, int h, uint32_t seed) {
  Frame f;
  f.allocate(w, h);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u01(0.f, 1.f);
  for (size_t i = 0; i < f.color.pixel_count(); ++i) {
    f.depth.plane(0)[i] = 1.f + 4.f * u01(rng);
    f.depth_gradient.plane(0)[i] = 0.2f * (u01(rng) - 0.5f);
    f.depth_gradient.plane(1)[i] = 0.2f * (u01(rng) - 0.5f);
    const float nx = 0.17f * (u01(rng) - 0.5f), ny = 0.17f * (u01(rng) - 0.5f);
    const float len = std::sqrt(nx * nx + ny * ny + 1.f);
    f.normal.plane(0)[i] = nx / len;
    f.normal.plane(1)[i] = ny / len;
    f.normal.plane(2)[i] = 1.f / len;
    f.mesh_id[i] = 1u + static_cast<uint32_t>(u01(rng) * 3.f);
    for (int c = 0; c < 3; ++c) {
      f.color.plane(c)[i] = 0.05f + 3.f * u01(rng);
      f.albedo.plane(c)[i] = 0.1f + 0.9f * u01(rng);
    }
  }
  return f;
}

// Random guides that pass every reprojection test between this frame and itself (or a copy):
// one mesh, depth within 2.5% (the tolerance is 3%), normals within 14 degrees of each other
// (cos >= 0.97 > 0.9).
inline Frame consistent_frame(int w, int h, uint32_t seed) {
  Frame f = random_frame(w, h, seed);
  const std::vector<float> depth = uniform_values(f.color.pixel_count(), 2.f, 2.05f, seed + 7);
  std::copy(depth.begin(), depth.end(), f.depth.plane(0));
  std::fill(f.mesh_id.begin(), f.mesh_id.end(), 1u);
  return f;
}

// The committed fixture sequences: folders under fixtures/ holding a manifest.json. Hidden
// folders and io::SequenceWriter's "<name>.tmp-<pid>" ones (being written) are not counted.
struct FixtureScan {
  std::string root;
  int folders = 0;                     // candidate sequence folders
  std::vector<std::string> sequences;  // those with a manifest, sorted
};
inline FixtureScan scan_fixtures() {
  namespace fs = std::filesystem;
  FixtureScan scan;
  // SVGF_FIXTURES_DIR (as for svgf_gpu_tests) lets a copied binary find them elsewhere.
  const char* env = std::getenv("SVGF_FIXTURES_DIR");
  const fs::path root = env ? fs::path(env) : fs::path(SVGF_SOURCE_DIR) / "fixtures";
  scan.root = root.string();
  if (!fs::is_directory(root)) return scan;
  for (const auto& e : fs::directory_iterator(root)) {
    const std::string name = e.path().filename().string();
    if (!e.is_directory() || name.empty() || name[0] == '.' ||
        name.find(".tmp-") != std::string::npos)
      continue;
    ++scan.folders;
    if (fs::exists(e.path() / "manifest.json")) scan.sequences.push_back(e.path().string());
  }
  std::sort(scan.sequences.begin(), scan.sequences.end());
  return scan;
}

// First frame of every fixture sequence, color made finite and non-negative (the pipeline's
// own bad-sample rule), for the checks that run on fixture images as well as random ones.
// Empty until fixtures exist; a broken fixture throws.
inline const std::vector<Frame>& fixture_frames() {
  static const std::vector<Frame> frames = [] {
    std::vector<Frame> out;
    for (const std::string& dir : scan_fixtures().sequences) {
      const io::Sequence seq(dir);
      if (seq.size() == 0) continue;
      out.push_back(seq.read(0));
      for (float& v : out.back().color.data())
        if (!(v >= 0.f && std::isfinite(v))) v = 0.f;
    }
    return out;
  }();
  return frames;
}

// ---------------------------------------------------------------- backends

// Each check is one body run on the CPU and on CUDA exact (tests/test_device.h); the checks are
// of exact arithmetic, and fast mode is held to exact mode's results by the stage tests.
using test::StageRunner;
using test::TestDevice;

// How a wide stage is driven: the per-pixel kernel (the CPU loop, or the CUDA launch) or the CPU
// engine's row drivers. The CPU variant of a check runs both, the CUDA variant the one.
enum class Driver { PerPixel, Rows };
inline std::vector<Driver> drivers(const TestDevice& d) {
  if (!d.cuda()) return {Driver::PerPixel, Driver::Rows};
  return {Driver::PerPixel};
}
inline std::string driver_name(const TestDevice& d, Driver driver) {
  return d.name() + (driver == Driver::Rows ? " rows" : "");
}
// The two wide stages through the CPU engine's row-vectorized drivers (kernels_cpu/svgf_rows.h).
inline void run_rows(StageRunner& r, const AtrousKernel& k, int w, int h) {
  REQUIRE_FALSE(r.device().cuda());
  cpu::run_atrous_rows(k, w, h);
}
inline void run_rows(StageRunner& r, const VarianceKernel& k, int w, int h) {
  REQUIRE_FALSE(r.device().cuda());
  cpu::run_variance_rows(k, w, h);
}

}  // namespace svgf::cvtest

// Registers a check written as `void f(const TestDevice&)` for the CPU and CUDA exact.
#define SVGF_OPENCV_CHECK(name, tags, function) SVGF_BACKEND_TEST(name, "[opencv]" tags, function)

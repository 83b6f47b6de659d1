#pragma once
// Shared test helpers: seeded random data (never zeros), synthetic frames, and comparisons that
// print the first few differing pixels with both values.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/frame.h"
#include "core/image.h"

namespace svgf::test {

inline constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
inline constexpr float kInf = std::numeric_limits<float>::infinity();

inline void fill_uniform(Image& im, float lo, float hi, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> d(lo, hi);
  for (float& v : im.data()) v = d(rng);
}

// Every channel of pixel (x, y) of a 3-channel image set to v.
inline void set_gray(Image& im, int x, int y, float v) {
  for (int c = 0; c < 3; ++c) im.at(x, y, c) = v;
}

// A flat, camera-facing wall at depth `depth` with normal +z, mesh 1, albedo `albedo`.
inline Frame flat_frame(int w, int h, float depth = 2.f, float albedo = 0.5f) {
  Frame f;
  f.allocate(w, h);
  for (size_t i = 0; i < f.color.pixel_count(); ++i) {
    f.depth.plane(0)[i] = depth;
    f.normal.plane(2)[i] = 1.f;
    for (int c = 0; c < 3; ++c) f.albedo.plane(c)[i] = albedo;
    f.mesh_id[i] = 1;
  }
  return f;
}

// Bitwise comparison of two images; on mismatch, fails with the first `show` differing pixels.
inline void require_identical(const Image& a, const Image& b, const std::string& what,
                              int show = 5) {
  REQUIRE(a.width() == b.width());
  REQUIRE(a.height() == b.height());
  REQUIRE(a.channels() == b.channels());
  size_t bad = 0;
  std::ostringstream msg;
  for (int c = 0; c < a.channels(); ++c)
    for (int y = 0; y < a.height(); ++y)
      for (int x = 0; x < a.width(); ++x) {
        const float va = a.at(x, y, c), vb = b.at(x, y, c);
        if (std::memcmp(&va, &vb, sizeof va) != 0) {
          if (static_cast<int>(bad) < show)
            msg << "  (" << x << "," << y << ") channel " << c << ": " << va << " vs " << vb
                << "\n";
          ++bad;
        }
      }
  INFO(what << ": " << bad << " differing values\n" << msg.str());
  REQUIRE(bad == 0);
}

// Largest |a-b| / max(|b|, floor) over all values.
inline double max_relative_difference(const Image& a, const Image& b, double floor = 1e-6) {
  double worst = 0;
  for (size_t i = 0; i < a.data().size(); ++i) {
    const double d = std::fabs(double(a.data()[i]) - double(b.data()[i])) /
                     std::max(std::fabs(double(b.data()[i])), floor);
    worst = std::max(worst, d);
  }
  return worst;
}

}  // namespace svgf::test

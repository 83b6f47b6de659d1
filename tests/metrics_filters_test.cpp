// The separable filter behind FLIP and SSIM (metrics/separable_filter.h) gives the bits of the
// naive per-pixel loops it replaced, kept here as the oracle, for both border rules, on odd sizes
// including images narrower and shorter than the kernel radius.
#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

#include <catch2/catch.hpp>

#include "metrics/separable_filter.h"

using namespace svgf::metrics;

namespace {

// The loops metrics/flip.cpp (clamp) and metrics/ssim.cpp (reflect101) used before: per pixel,
// s = 0 then s += k[d] * v for d from -r to r.
std::vector<double> oracle(const std::vector<double>& src, int w, int h,
                           const std::vector<double>& kx, const std::vector<double>& ky,
                           FilterBorder border) {
  const int rx = static_cast<int>(kx.size() / 2), ry = static_cast<int>(ky.size() / 2);
  std::vector<double> tmp(src.size()), out(src.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double s = 0;
      for (int d = -rx; d <= rx; ++d)
        s += kx[d + rx] * src[static_cast<size_t>(y) * w + border_index(x + d, w, border)];
      tmp[static_cast<size_t>(y) * w + x] = s;
    }
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double s = 0;
      for (int d = -ry; d <= ry; ++d)
        s += ky[d + ry] * tmp[static_cast<size_t>(border_index(y + d, h, border)) * w + x];
      out[static_cast<size_t>(y) * w + x] = s;
    }
  return out;
}

std::vector<double> random_values(std::mt19937& rng, size_t n, double lo, double hi) {
  std::uniform_real_distribution<double> u(lo, hi);
  std::vector<double> v(n);
  for (double& x : v) x = u(rng);
  return v;
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

}  // namespace

TEST_CASE("border_index clamps or mirrors without repeating the edge", "[metrics][filter]") {
  CHECK(border_index(-2, 5, FilterBorder::clamp) == 0);
  CHECK(border_index(6, 5, FilterBorder::clamp) == 4);
  CHECK(border_index(-2, 5, FilterBorder::reflect101) == 2);
  CHECK(border_index(6, 5, FilterBorder::reflect101) == 2);
  CHECK(border_index(-7, 3, FilterBorder::reflect101) == 1);  // folded twice
  CHECK(border_index(4, 1, FilterBorder::reflect101) == 0);
}

TEST_CASE("separable_convolve gives the naive loops' bits", "[metrics][filter]") {
  std::mt19937 rng(20261129);
  const int sizes[][2] = {{1, 1}, {3, 2}, {2, 7}, {9, 4}, {11, 11}, {12, 21}, {23, 13}, {97, 61}};
  // Radii of SSIM (5), FLIP's feature (9) and CSF (10) kernels at 67 ppd, and odd others.
  const int radii[][2] = {{5, 5}, {9, 9}, {10, 10}, {1, 3}, {0, 2}};
  for (FilterBorder border : {FilterBorder::clamp, FilterBorder::reflect101})
    for (const auto& size : sizes)
      for (const auto& radius : radii) {
        const int w = size[0], h = size[1];
        const std::vector<double> src = random_values(rng, static_cast<size_t>(w) * h, -1.0, 2.0);
        const std::vector<double> kx = random_values(rng, 2 * radius[0] + 1, -0.5, 1.0);
        const std::vector<double> ky = random_values(rng, 2 * radius[1] + 1, -0.5, 1.0);
        std::vector<double> out(3, 42.0);  // a stale, wrongly sized buffer is overwritten
        separable_convolve(src, w, h, kx, ky, border, out);
        INFO("border " << static_cast<int>(border) << ", " << w << "x" << h << ", radii "
                       << radius[0] << "," << radius[1]);
        CHECK(same_bits(out, oracle(src, w, h, kx, ky, border)));
      }
}

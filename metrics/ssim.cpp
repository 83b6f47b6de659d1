#include "metrics/ssim.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace svgf::metrics {
namespace {

constexpr int kRadius = 5;  // 11x11 window
constexpr double kSigma = 1.5;
constexpr double kC1 = 0.01 * 0.01;  // (K1 L)^2 with L = 1
constexpr double kC2 = 0.03 * 0.03;  // (K2 L)^2

double clamp01(double v) { return std::isnan(v) ? 0.0 : std::min(1.0, std::max(0.0, v)); }

// Mirror index without repeating the edge (…2 1 | 0 1 2 … n-1 | n-2 …), folded as often as a
// window wider than the image needs.
int reflect101(int p, int n) {
  if (n == 1) return 0;
  while (p < 0 || p >= n) p = p < 0 ? -p : 2 * (n - 1) - p;
  return p;
}

std::vector<double> gaussian_window() {
  std::vector<double> k(2 * kRadius + 1);
  double sum = 0;
  for (int i = -kRadius; i <= kRadius; ++i)
    sum += k[i + kRadius] = std::exp(-double(i * i) / (2.0 * kSigma * kSigma));
  for (double& v : k) v /= sum;
  return k;
}

// Separable Gaussian blur in double, rows then columns.
std::vector<double> blur(const std::vector<double>& src, int w, int h,
                         const std::vector<double>& k) {
  std::vector<double> tmp(src.size()), out(src.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double s = 0;
      for (int d = -kRadius; d <= kRadius; ++d)
        s += k[d + kRadius] * src[static_cast<size_t>(y) * w + reflect101(x + d, w)];
      tmp[static_cast<size_t>(y) * w + x] = s;
    }
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double s = 0;
      for (int d = -kRadius; d <= kRadius; ++d)
        s += k[d + kRadius] * tmp[static_cast<size_t>(reflect101(y + d, h)) * w + x];
      out[static_cast<size_t>(y) * w + x] = s;
    }
  return out;
}

// SSIM map of channel c in double; the mean is taken from these, not from the float map.
std::vector<double> channel_map(const Image& test, const Image& reference, int c,
                                const std::vector<double>& k) {
  const int w = test.width(), h = test.height();
  const size_t n = test.pixel_count();
  std::vector<double> a(n), b(n), aa(n), bb(n), ab(n);
  for (size_t i = 0; i < n; ++i) {
    a[i] = clamp01(test.plane(c)[i]);
    b[i] = clamp01(reference.plane(c)[i]);
    aa[i] = a[i] * a[i];
    bb[i] = b[i] * b[i];
    ab[i] = a[i] * b[i];
  }
  const std::vector<double> mu_a = blur(a, w, h, k), mu_b = blur(b, w, h, k);
  const std::vector<double> e_aa = blur(aa, w, h, k), e_bb = blur(bb, w, h, k),
                            e_ab = blur(ab, w, h, k);
  std::vector<double> map(n);
  for (size_t i = 0; i < n; ++i) {
    const double var_a = e_aa[i] - mu_a[i] * mu_a[i];
    const double var_b = e_bb[i] - mu_b[i] * mu_b[i];
    const double cov = e_ab[i] - mu_a[i] * mu_b[i];
    const double num = (2.0 * mu_a[i] * mu_b[i] + kC1) * (2.0 * cov + kC2);
    const double den = (mu_a[i] * mu_a[i] + mu_b[i] * mu_b[i] + kC1) * (var_a + var_b + kC2);
    map[i] = num / den;
  }
  return map;
}

void check_inputs(const Image& test, const Image& reference) {
  if (test.width() != reference.width() || test.height() != reference.height() ||
      test.channels() < 3 || reference.channels() < 3 || test.empty())
    throw std::invalid_argument("ssim: images differ in size or have fewer than 3 channels");
}

}  // namespace

Image ssim_map(const Image& test, const Image& reference) {
  check_inputs(test, reference);
  const std::vector<double> k = gaussian_window();
  Image out(test.width(), test.height(), 3);
  for (int c = 0; c < 3; ++c) {
    const std::vector<double> map = channel_map(test, reference, c, k);
    for (size_t i = 0; i < map.size(); ++i) out.plane(c)[i] = static_cast<float>(map[i]);
  }
  return out;
}

double ssim(const Image& test, const Image& reference) {
  check_inputs(test, reference);
  const std::vector<double> k = gaussian_window();
  double total = 0;
  for (int c = 0; c < 3; ++c) {
    const std::vector<double> map = channel_map(test, reference, c, k);
    double sum = 0;
    for (double v : map) sum += v;
    total += sum / static_cast<double>(map.size());
  }
  return total / 3.0;
}

}  // namespace svgf::metrics

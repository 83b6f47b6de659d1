#include "metrics/ssim.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "metrics/display_range.h"
#include "metrics/separable_filter.h"

namespace svgf::metrics {
namespace {

constexpr int kRadius = 5;  // 11x11 window
constexpr double kSigma = 1.5;
constexpr double kC1 = 0.01 * 0.01;  // (K1 L)^2 with L = 1
constexpr double kC2 = 0.03 * 0.03;  // (K2 L)^2

std::vector<double> gaussian_window() {
  std::vector<double> k(2 * kRadius + 1);
  double sum = 0;
  for (int i = -kRadius; i <= kRadius; ++i)
    sum += k[i + kRadius] = std::exp(-double(i * i) / (2.0 * kSigma * kSigma));
  for (double& v : k) v /= sum;
  return k;
}

// SSIM map of channel c in double; the mean is taken from these, not from the float map.
std::vector<double> channel_map(const Image& test, const Image& reference, int c,
                                const std::vector<double>& k) {
  const int w = test.width(), h = test.height();
  const size_t n = test.pixel_count();
  // Planes reused per thread: fresh ones per call would be mmap'ed and page-faulted anew.
  thread_local std::vector<double> a, b, aa, bb, ab, mu_a, mu_b, e_aa, e_bb, e_ab;
  for (auto* plane : {&a, &b, &aa, &bb, &ab}) plane->resize(n);
  for (size_t i = 0; i < n; ++i) {
    a[i] = clamp01(test.plane(c)[i]);
    b[i] = clamp01(reference.plane(c)[i]);
    aa[i] = a[i] * a[i];
    bb[i] = b[i] * b[i];
    ab[i] = a[i] * b[i];
  }
  separable_convolve(a, w, h, k, k, FilterBorder::reflect101, mu_a);
  separable_convolve(b, w, h, k, k, FilterBorder::reflect101, mu_b);
  separable_convolve(aa, w, h, k, k, FilterBorder::reflect101, e_aa);
  separable_convolve(bb, w, h, k, k, FilterBorder::reflect101, e_bb);
  separable_convolve(ab, w, h, k, k, FilterBorder::reflect101, e_ab);
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

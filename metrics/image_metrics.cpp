#include "metrics/image_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "metrics/display_range.h"

namespace svgf::metrics {
namespace {

void check_same_size(const Image& a, const Image& b) {
  if (a.width() != b.width() || a.height() != b.height() || a.channels() < 3 ||
      b.channels() < 3)
    throw std::invalid_argument("metrics: images differ in size or have fewer than 3 channels");
}

}  // namespace

double mse_clamped(const Image& test, const Image& reference) {
  check_same_size(test, reference);
  double sum = 0;
  for (int c = 0; c < 3; ++c) {
    const float* t = test.plane(c);
    const float* r = reference.plane(c);
    for (size_t i = 0; i < test.pixel_count(); ++i) {
      const double d = clamp01(t[i]) - clamp01(r[i]);
      sum += d * d;
    }
  }
  return sum / (3.0 * static_cast<double>(test.pixel_count()));
}

double psnr(const Image& test, const Image& reference) {
  const double mse = mse_clamped(test, reference);
  return mse == 0 ? std::numeric_limits<double>::infinity() : 10.0 * std::log10(1.0 / mse);
}

double relmse(const Image& test, const Image& reference) {
  check_same_size(test, reference);
  double sum = 0;
  for (int c = 0; c < 3; ++c) {
    const float* t = test.plane(c);
    const float* r = reference.plane(c);
    for (size_t i = 0; i < test.pixel_count(); ++i) {
      const double d = double(t[i]) - double(r[i]);
      sum += d * d / (double(r[i]) * double(r[i]) + 0.01);
    }
  }
  return sum / (3.0 * static_cast<double>(test.pixel_count()));
}

}  // namespace svgf::metrics

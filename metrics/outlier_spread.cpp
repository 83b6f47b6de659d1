#include "metrics/outlier_spread.h"

#include <algorithm>
#include <cstdlib>
#include <stdexcept>

namespace svgf::metrics {

double pixel_relative_error(const Image& test, const Image& reference, size_t i) {
  double sum = 0;
  for (int c = 0; c < 3; ++c) {
    const double t = test.plane(c)[i], r = reference.plane(c)[i];
    sum += (t - r) * (t - r) / (r * r + 0.01);
  }
  return sum / 3.0;
}

OutlierSpread outlier_spread(const Image& with_outlier, const Image& clean,
                             const Image& reference, int x, int y, double factor, double floor) {
  for (const Image* im : {&with_outlier, &clean})
    if (im->width() != reference.width() || im->height() != reference.height() ||
        im->channels() < 3 || reference.channels() < 3)
      throw std::invalid_argument(
          "outlier_spread: images of different sizes or fewer than 3 channels");
  OutlierSpread s;
  const int w = reference.width(), h = reference.height();
  for (int py = 0; py < h; ++py)
    for (int px = 0; px < w; ++px) {
      const size_t i = static_cast<size_t>(py) * w + px;
      const double e = pixel_relative_error(with_outlier, reference, i);
      if (!(e > factor * pixel_relative_error(clean, reference, i) && e >= floor)) continue;
      ++s.pixels;
      s.radius = std::max(s.radius, std::max(std::abs(px - x), std::abs(py - y)));
    }
  return s;
}

}  // namespace svgf::metrics

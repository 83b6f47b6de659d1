#pragma once
// How far one outlier sample (a firefly) spreads through a denoiser (issue 13; docs/metrics.md,
// "Outlier spread"): the same sequence is denoised twice, clean and with the outlier, and the
// two outputs' per-pixel errors against the reference are compared.
#include <cstddef>

#include "core/image.h"

namespace svgf::metrics {

// Per-pixel relative squared error, mean over RGB: (t - r)^2 / (r^2 + 0.01), the summand of
// relMSE (image_metrics.h), on unclamped values.
double pixel_relative_error(const Image& test, const Image& reference, size_t pixel);

struct OutlierSpread {
  size_t pixels = 0;  // pixels the outlier made worse
  int radius = -1;    // the largest Chebyshev distance of one from (x, y); -1: none
};

// Pixels where the outlier run's error exceeds `factor` times the clean run's and at least
// `floor` (so that a pixel whose error the outlier moved from 1e-9 to 3e-9 is not counted).
OutlierSpread outlier_spread(const Image& with_outlier, const Image& clean,
                             const Image& reference, int x, int y, double factor = 2.0,
                             double floor = 1e-3);

}  // namespace svgf::metrics

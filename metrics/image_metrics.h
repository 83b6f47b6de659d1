#pragma once
// Image quality against a reference (docs/metrics.md gives each definition).
#include "core/image.h"

namespace svgf::metrics {

// Mean squared error over all pixels and RGB channels, values clamped to [0, 1] first.
double mse_clamped(const Image& test, const Image& reference);
// PSNR in dB with peak 1 on clamped values: 10 log10(1 / mse_clamped). Identical images: +Inf.
double psnr(const Image& test, const Image& reference);
// Relative MSE (Rousselle et al. 2011): mean over pixels and channels of
// (t - r)^2 / (r^2 + 0.01), on unclamped linear HDR values.
double relmse(const Image& test, const Image& reference);

}  // namespace svgf::metrics

#pragma once
// Structural similarity (Wang et al. 2004) against a reference; docs/metrics.md gives the
// definition, including the border rule.
#include "core/image.h"

namespace svgf::metrics {

// Per-pixel SSIM of each of the first three channels (3 channels, same size as the inputs):
// 11x11 Gaussian window (sigma 1.5), K1 = 0.01, K2 = 0.03, dynamic range L = 1, on values
// clamped to [0, 1] (NaN counts as 0). The window is completed past the image edge by mirroring
// without repeating the edge pixel (OpenCV's BORDER_REFLECT_101).
Image ssim_map(const Image& test, const Image& reference);
// Mean of ssim_map over all pixels, then over the three channels. 1 for identical images.
double ssim(const Image& test, const Image& reference);

}  // namespace svgf::metrics

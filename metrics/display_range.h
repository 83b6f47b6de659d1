#pragma once
// A value clamped into the display range [0, 1], NaN read as 0: what the image metrics compare
// (MSE/PSNR, SSIM, FLIP and the detail measure are defined on display-referred values; a NaN
// counts as black, not as a poisoned sum).
#include <algorithm>
#include <cmath>

namespace svgf::metrics {

inline double clamp01(double v) { return std::isnan(v) ? 0.0 : std::min(1.0, std::max(0.0, v)); }

}  // namespace svgf::metrics

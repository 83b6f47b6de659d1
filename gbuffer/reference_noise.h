#pragma once
#include <limits>

namespace svgf::gbuffer {

// How far one frame's reference is from the true image, as the mean squared error PSNR measures
// (values clamped to [0, 1], mean over pixels and RGB), estimated from the reference's own
// samples: its two halves, samples [0, n1) and [n1, n) with n1 = n/2, are independent estimates
// a and b, so E[(a - b)^2] n1 (n - n1) / n^2 is the variance of their mean, the reference
// (exact where the clamp does not act). A method's MSE against the reference is its MSE against
// the true image plus this (independent noise), so quality reports subtract it
// (bench/eval_quality.cpp). NaN without a reference of at least 2 samples.
// Where a half is above 1 the clamp cuts its difference and the estimate comes out low (against
// two references rendered with two seeds, `svgf-fixtures reference-noise`: within 0.1 dB where
// under 3% of the estimate comes from such values, 0.65 and 1.5 dB low at 20% and 32%), so
// `clamped_share` says how much of it does.
struct ReferenceNoise {
  double mse = std::numeric_limits<double>::quiet_NaN();
  // Standard error of `mse` from the spread of the per-value estimates (pixels independent).
  double standard_error = std::numeric_limits<double>::quiet_NaN();
  // The part of `mse` from channel values where a half is above 1, over `mse` (0 to 1).
  double clamped_share = std::numeric_limits<double>::quiet_NaN();
};

}  // namespace svgf::gbuffer

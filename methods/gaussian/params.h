#pragma once
// The Gaussian blur baseline: the simple filter the CIS 565 CUDA denoiser compares its
// edge-avoiding a-trous filter against. No guides, no history: it shows what edge-stopping and
// temporal accumulation buy.
#include <cmath>
#include <stdexcept>
#include <string>

namespace svgf {

struct GaussianParams {
  // Standard deviation in pixels. 2 px: about the spread of SVGF's first two a-trous
  // iterations (B3 spline at steps 1 and 2), so the baseline blurs as far as SVGF's finest
  // scales reach. A choice of this project, not a number from CIS 565, whose comparison varies
  // the filter size.
  float sigma = 2.f;
  // Taps either side; 0: ceil(3 sigma), which keeps all but 0.3% of the kernel's weight.
  int radius = 0;

  int effective_radius() const {
    return radius > 0 ? radius : static_cast<int>(std::ceil(3.f * sigma));
  }
  // std::invalid_argument naming the parameter.
  void validate() const {
    // Below 1e-3 px the kernel is a copy, and far below, 2 sigma^2 underflows to 0 and the
    // centre weight exp(-0 / 0) is NaN.
    if (!(sigma >= 1e-3f && sigma <= 256.f))
      throw std::invalid_argument("gaussian: --sigma must be in [0.001, 256], got " +
                                  std::to_string(sigma));
    if (radius < 0 || radius > 1024)
      throw std::invalid_argument("gaussian: --radius must be in [0, 1024], got " +
                                  std::to_string(radius));
  }
};

}  // namespace svgf

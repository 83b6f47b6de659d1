#pragma once
// The CIS 565 edge-avoiding a-trous wavelet filter (UPenn CIS 565 Project 4, after Dammertz et
// al. 2010, "Edge-Avoiding A-Trous Wavelet Transform for fast Global Illumination Filtering"),
// in the form of Alex Fu's CIS 565 denoiser (github.com/IwakuraRein/Nagi, README and
// src/gui/gui.hpp; docs/wavelet.md): a single-frame filter, no history.
#include <cmath>
#include <stdexcept>
#include <string>

namespace svgf {

struct WaveletParams {
  // Passes, with dilation 1, 2, 4, 8: CIS 565's default filter size 80 = 5 * 2^4 px.
  int iterations = 4;
  // Taps per axis: 3, 5, 7 or 9, binomial weights (5: the B3 spline of Dammertz et al.). The
  // CIS 565 kernel-size study compares these.
  int kernel_size = 5;
  // W_Z = exp(-|Z_p - Z_q| / (sigma_depth + epsilon)), Z the view depth (Nagi: sigma_Z 1).
  float sigma_depth = 1.f;
  // W_N = saturate(N_p . N_q)^sigma_normal (Nagi: sigma_N 64).
  float sigma_normal = 64.f;
  // W_L = exp(-|L_p - L_q| / (sigma_luma * Dev_p + epsilon)) (Nagi: sigma_L 4).
  float sigma_luma = 4.f;
  // Dev's lower clamp, the denominators' guard and the albedo guard of the demodulation
  // color / (albedo + epsilon) (Nagi's VAR_EPSILON, 0.01).
  float epsilon = 0.01f;

  int radius() const { return kernel_size / 2; }
  // std::invalid_argument naming the flag.
  void validate() const {
    auto fail = [](const std::string& what) { throw std::invalid_argument("wavelet: " + what); };
    if (iterations < 0 || iterations > 12)
      fail("--iterations must be in [0, 12], got " + std::to_string(iterations));
    if (kernel_size != 3 && kernel_size != 5 && kernel_size != 7 && kernel_size != 9)
      fail("--kernel-size must be 3, 5, 7 or 9, got " + std::to_string(kernel_size));
    auto finite_positive = [](float v) { return std::isfinite(v) && v > 0.f; };
    if (!finite_positive(sigma_depth))
      fail("--sigma-depth must be finite and > 0, got " + std::to_string(sigma_depth));
    if (!(std::isfinite(sigma_normal) && sigma_normal >= 0.f))
      fail("--sigma-normal must be finite and >= 0, got " + std::to_string(sigma_normal));
    if (!finite_positive(sigma_luma))
      fail("--sigma-luma must be finite and > 0, got " + std::to_string(sigma_luma));
    if (!(finite_positive(epsilon) && epsilon <= 1.f))
      fail("--epsilon must be in (0, 1], got " + std::to_string(epsilon));
  }
};

}  // namespace svgf

#pragma once
// Wavelet stages 1 and 5: demodulation by the albedo and its inverse. The filter works on
// color / (albedo + epsilon) (CIS 565, Nagi), so texture survives; the emitted part of the
// color is taken out first and added back after, as SVGF does, so lights are not spread. The
// luma the luminance weight compares is taken once, from the demodulated noisy color, with
// Rec. 601 weights (0.299, 0.587, 0.114) as in Nagi.
#include "core/views.h"

namespace svgf {

SVGF_HD float rec601_luma(Vec3 c) { return 0.299f * c.x + 0.587f * c.y + 0.114f * c.z; }

// albedo + epsilon, with a negative or NaN albedo taken as 0 (max_f drops NaN).
SVGF_HD Vec3 wavelet_albedo(Vec3 albedo, float epsilon) {
  return max_v(albedo, 0.f) + make_vec3(epsilon, epsilon, epsilon);
}

// The color is sanitized already (core/sanitize.h, the backend's first stage).
struct WaveletDemodulateKernel {
  int width = 0;
  ConstRgbView color;
  ConstRgbView albedo;
  ConstRgbView emission;  // optional
  RgbView illumination;
  float* luma = nullptr;
  float epsilon = 0.01f;
  SVGF_HD void operator()(int x, int y) const {
    const int i = y * width + x;
    const Vec3 v = max_v(color.load(i) - emission.load_or_zero(i), 0.f) /
                   wavelet_albedo(albedo.load(i), epsilon);
    illumination.store(i, v);
    luma[i] = rec601_luma(v);
  }
};

// filtered * (albedo + epsilon) + emission, as it stores.
struct WaveletRemodulateSink {
  ConstRgbView albedo;
  ConstRgbView emission;  // optional
  RgbView output;
  float epsilon = 0.01f;
  SVGF_HD void store(int i, Vec3 v) const {
    output.store(i, v * wavelet_albedo(albedo.load(i), epsilon) + emission.load_or_zero(i));
  }
};

}  // namespace svgf

#pragma once
// Preview tonemap: exposure, Reinhard x/(1+x) per channel, sRGB transfer curve, 8 bits.
// Previews only; the EXR output stays linear HDR.
#include <cstdint>

#include "core/det_math.h"
#include "core/views.h"

namespace svgf {

SVGF_HD float srgb_encode(float linear) {
  return linear <= 0.0031308f ? 12.92f * linear
                              : 1.055f * det_pow(linear, 1.f / 2.4f) - 0.055f;
}

SVGF_HD uint8_t tonemap_channel(float v, float exposure) {
  const float e = min_f(max_f(0.f, v * exposure), 1e30f);  // NaN -> 0, Inf -> white
  const float mapped = srgb_encode(e / (1.f + e));
  const float q = floorf(mapped * 255.f + 0.5f);
  return static_cast<uint8_t>(min_f(max_f(q, 0.f), 255.f));
}

struct TonemapKernel {
  int width = 0;
  ConstRgbView color;
  uint8_t* rgb8 = nullptr;  // interleaved RGB, 3 bytes per pixel
  float exposure = 1.f;

  SVGF_HD void operator()(int x, int y) const {
    const int i = y * width + x;
    rgb8[3 * i + 0] = tonemap_channel(color.r[i], exposure);
    rgb8[3 * i + 1] = tonemap_channel(color.g[i], exposure);
    rgb8[3 * i + 2] = tonemap_channel(color.b[i], exposure);
  }
};

}  // namespace svgf

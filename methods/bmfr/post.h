#pragma once
// BMFR stage 4: post-accumulation (paper Sec. 4.3) and remodulation. The regression's output is
// blended with the previous accumulated output through the pre-accumulation's reprojection (its
// accepted taps and weights) by max(1 / n, post_alpha), n this pixel's history length; the
// result is the next frame's history and, times the albedo plus the emission, the output.
#include "core/modulation.h"
#include "core/views.h"
#include "methods/bmfr/accumulate.h"

namespace svgf {

struct BmfrPostAccumulate {
  int width = 0, height = 0;
  ConstRgbView filtered;
  BmfrReprojectionView reprojection;
  const float* length = nullptr;  // this frame's history length
  ConstRgbView prev_accumulated;
  RgbView accumulated;
  ConstRgbView albedo, emission;  // emission optional
  RgbView output;
  bool has_history = false;
  float alpha = 0.1f;
  float albedo_epsilon = 1e-3f;

  SVGF_HD void operator()(int x, int y) const {
    const int i = y * width + x;
    const Vec3 f = filtered.load(i);
    Vec3 result = f;
    const int accepted = has_history ? static_cast<int>(reprojection.accept[i]) : 0;
    if (accepted != 0) {
      const BilinearTaps taps = BilinearTaps::at(reprojection.prev_x[i], reprojection.prev_y[i]);
      float total = 0.f;
      Vec3 prev = make_vec3(0.f, 0.f, 0.f);
      for (int k = 0; k < 4; ++k) {
        if (!(accepted & (1 << k))) continue;
        const float w = taps.weight(k);
        total = total + w;
        prev = prev + prev_accumulated.load(taps.y(k) * width + taps.x(k)) * w;
      }
      if (total > 0.f) {
        const float a = max_f(1.f / length[i], alpha);
        result = f * a + (prev / total) * (1.f - a);
      }
    }
    accumulated.store(i, result);
    output.store(i, remodulated(result, albedo.load(i), emission.load_or_zero(i), albedo_epsilon));
  }
};

}  // namespace svgf

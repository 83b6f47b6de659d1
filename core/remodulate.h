#pragma once
// Final stage: remodulate. Multiplies the filtered illumination by the same guarded albedo that
// demodulate divided by, restoring texture.
#include "core/demodulate.h"

namespace svgf {

struct RemodulateKernel {
  int width = 0;
  ConstRgbView illumination;
  ConstRgbView albedo;
  RgbView output;
  float albedo_epsilon = 1e-3f;

  SVGF_HD void operator()(int x, int y) const {
    const int i = y * width + x;
    output.store(i, illumination.load(i) * guarded_albedo(albedo.load(i), albedo_epsilon));
  }
};

}  // namespace svgf

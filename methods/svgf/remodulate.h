#pragma once
// Final stage: remodulate. Multiplies the filtered illumination by the same guarded albedo that
// demodulate divided by, restoring texture, and adds the emission back.
#include "methods/svgf/demodulate.h"

namespace svgf {

SVGF_HD Vec3 remodulated(Vec3 illumination, Vec3 albedo, Vec3 emission, float albedo_epsilon) {
  return illumination * guarded_albedo(albedo, albedo_epsilon) + emission;
}

struct RemodulateKernel {
  int width = 0;
  ConstRgbView illumination;
  ConstRgbView albedo;
  ConstRgbView emission;  // optional
  RgbView output;
  float albedo_epsilon = 1e-3f;

  SVGF_HD void operator()(int x, int y) const {
    const int i = y * width + x;
    output.store(i, remodulated(illumination.load(i), albedo.load(i), emission.load_or_zero(i),
                                albedo_epsilon));
  }
};

}  // namespace svgf

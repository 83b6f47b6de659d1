#pragma once
// Stage 1: demodulate. Takes the emitted part out of the noisy color and divides the albedo
// out of the rest, so that the filters smooth reflected illumination only: texture detail
// survives (paper Sec. 4), and light sources, which are noise-free and far brighter than what
// surrounds them, are not spread onto their neighbours (Falcor's SVGF does the same). Bad
// samples never reach it: the backend's sanitize stage (core/sanitize.h) runs first.
#include "core/hd.h"
#include "methods/svgf/params.h"
#include "core/views.h"

namespace svgf {

// Albedo clamped from below (NaN albedo clamps too, since max_f drops NaN).
SVGF_HD Vec3 guarded_albedo(Vec3 albedo, float epsilon) { return max_v(albedo, epsilon); }

// Reflected illumination: (color - emission) / albedo. The
// difference is clamped at 0 because rounding in the renderer may leave it a hair negative.
SVGF_HD Vec3 demodulated(Vec3 color, Vec3 emission, Vec3 albedo, float albedo_epsilon) {
  return max_v(color - emission, 0.f) / guarded_albedo(albedo, albedo_epsilon);
}

struct DemodulateKernel {
  int width = 0;
  ConstRgbView color;
  ConstRgbView albedo;
  ConstRgbView emission;  // optional: no planes means no emitters
  RgbView illumination;
  float albedo_epsilon = 1e-3f;

  SVGF_HD void operator()(int x, int y) const {
    const int i = y * width + x;
    illumination.store(i, demodulated(color.load(i), emission.load_or_zero(i), albedo.load(i),
                                      albedo_epsilon));
  }
};

}  // namespace svgf

#pragma once
// Stage 1: demodulate (core/modulation.h has the formula and why). Bad samples never reach
// it: the backend's sanitize stage (core/sanitize.h) runs first.
#include "core/hd.h"
#include "core/modulation.h"
#include "methods/svgf/params.h"
#include "core/views.h"

namespace svgf {

struct DemodulateKernel {
  int width = 0;
  ConstRgbView color;
  ConstRgbView albedo;
  ConstRgbView emission;  // optional: no planes means no emitters
  RgbView illumination;
  float albedo_epsilon = 1e-3f;

  SVGF_HD void operator()(int x, int y) const {
    const int i = y * width + x;
    illumination.store(i, at(i));
  }
  // Pixel i's illumination.
  SVGF_HD Vec3 at(int i) const {
    return demodulated(color.load(i), emission.load_or_zero(i), albedo.load(i), albedo_epsilon);
  }
};

}  // namespace svgf

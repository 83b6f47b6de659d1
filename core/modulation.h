#pragma once
// Demodulation by the albedo, shared by the methods that filter reflected illumination (SVGF,
// BMFR): the emitted part of the color is taken out and the albedo divided out of the rest,
// so the filters smooth illumination only (texture survives, paper Sec. 4 of SVGF) and light
// sources, noise-free and far brighter than their surroundings, are not spread (Falcor's SVGF
// does the same). remodulated() is its inverse.
#include "core/hd.h"
#include "core/vec.h"

namespace svgf {

// Albedo clamped from below (NaN albedo clamps too, since max_f drops NaN).
SVGF_HD Vec3 guarded_albedo(Vec3 albedo, float epsilon) { return max_v(albedo, epsilon); }

// Reflected illumination: (color - emission) / albedo. The difference is clamped at 0 because
// rounding in the renderer may leave it a hair negative.
SVGF_HD Vec3 demodulated(Vec3 color, Vec3 emission, Vec3 albedo, float albedo_epsilon) {
  return max_v(color - emission, 0.f) / guarded_albedo(albedo, albedo_epsilon);
}

// Multiplies by the same guarded albedo that demodulated() divided by and adds the emission.
SVGF_HD Vec3 remodulated(Vec3 illumination, Vec3 albedo, Vec3 emission, float albedo_epsilon) {
  return illumination * guarded_albedo(albedo, albedo_epsilon) + emission;
}

}  // namespace svgf

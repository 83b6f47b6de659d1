#pragma once
// Final stage: remodulate. Multiplies the filtered illumination by the same guarded albedo that
// demodulate divided by, restoring texture, and adds the emission back.
#include "core/copy.h"
#include "core/sink.h"
#include "methods/svgf/demodulate.h"

namespace svgf {

// Remodulates as it stores: what the remodulate stage writes into, and what the fused pipeline's
// last a-trous iteration stores into directly (fast mode).
struct RemodulateSink {
  ConstRgbView albedo;
  ConstRgbView emission;  // optional
  RgbView output;
  float albedo_epsilon = 1e-3f;
  SVGF_HD void store(int i, Vec3 illumination) const {
    output.store(i, remodulated(illumination, albedo.load(i), emission.load_or_zero(i),
                                albedo_epsilon));
  }
  SVGF_HD void store(int i, ColorVar v) const { store(i, v.color); }

  // Its inputs fetched ahead (core/sink.h).
  struct Inputs {
    Vec3 albedo, emission;
  };
  SVGF_HD Inputs inputs(int i) const { return {albedo.load(i), emission.load_or_zero(i)}; }
  SVGF_HD void store(const Inputs& in, int i, ColorVar v) const {
    output.store(i, remodulated(v.color, in.albedo, in.emission, albedo_epsilon));
  }
};

// The stage on its own: RemodulateKernel{width, illumination, {albedo, emission, output, eps}}.
using RemodulateKernel = ForwardKernel<ConstRgbView, RemodulateSink>;

}  // namespace svgf

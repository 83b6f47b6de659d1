#pragma once
// What each pipeline stage must move and compute per pixel: the one place the benchmark's
// bandwidth, roofline floor and docs/benchmarks.md numbers come from. stage_cost.cpp lists, per
// kernel, the planes it reads and writes (4-byte floats or mesh ids) and a hand count of its
// floating-point operations.
#include <string>

#include "core/denoiser.h"
#include "core/params.h"
#include "core/stage_times.h"

namespace svgf::bench {

struct StageCost {
  double read = 0;     // bytes read from memory per pixel, each plane once
  double written = 0;  // bytes written per pixel, each plane once
  double ops = 0;      // floating-point operations per pixel on the steady-state path
  std::string planes;  // which planes, for the docs
  double bytes() const { return read + written; }
};

// Cost of `stage` in one frame, all a-trous iterations together for Stage::Atrous. Upload and
// Download give the bytes crossing the host link (their ops are 0). Fast mode (CUDA) fuses
// stages: demodulate + reproject run as one kernel, timed and counted as Demodulate (Reproject
// is then empty); feedback and remodulate ride on the a-trous iterations. `emission`: the frames
// carry the optional emission planes, which demodulate subtracts and remodulate adds back.
// `surface_fraction`: the share of pixels with a surface; background pixels (no surface) skip
// the history, the edge-stopping taps and the planes those read, and cost much less.
StageCost stage_cost(Mode mode, Stage stage, const SvgfParams& p, bool emission,
                     double surface_fraction);

// Sum over the filtering stages (transfers excluded).
StageCost frame_cost(Mode mode, const SvgfParams& p, bool emission, double surface_fraction);

}  // namespace svgf::bench

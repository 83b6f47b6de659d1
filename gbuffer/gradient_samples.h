#pragma once
// A-SVGF gradient samples (Schied et al. 2018, "Gradient Estimation for Real-Time Adaptive
// Temporal Filtering", section 4): per 3x3 stratum of the previous frame one camera sample is
// carried with its object into this frame and shaded again with the same random numbers, so the
// difference of the two luminances is the temporal change of the shading alone, free of noise.
// The frame's `gradient` channel (docs/frame-format.md, docs/gbuffer.md).
#include <cstdint>

#include "core/image.h"
#include "gbuffer/frame_scene.h"
#include "gbuffer/renderer.h"

namespace svgf::gbuffer {

// A sample's reprojected hit must lie within this relative distance of what the current camera
// sees in its direction; otherwise it is hidden at this frame and dropped.
inline constexpr float kGradientVisibilityTolerance = 1e-3f;

// The 3-channel gradient image of `current` (previous luminance, current luminance, mask) with
// samples from `previous`, which must be the frame before it (same size). Deterministic for any
// thread count. Adds the rays it traces to `rays`.
Image gradient_samples(const FrameScene& previous, const FrameScene& current,
                       const RenderSettings& settings, uint64_t& rays);

// The pixel of stratum (sx, sy) that frame `frame` lends to the gradient, and the priority
// (lower wins) when two samples land in the same stratum of the next frame.
struct StratumPick {
  int x = 0, y = 0;
  uint32_t priority = 0;
};
StratumPick pick_in_stratum(uint64_t seed, int frame, int sx, int sy, int width, int height);

}  // namespace svgf::gbuffer

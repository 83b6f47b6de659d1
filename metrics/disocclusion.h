#pragma once
// The pixels a frame shows without history: where a moving object uncovered what was behind it
// (issue 13, disocclusion trail; docs/metrics.md, "Disocclusion").
#include <cstdint>
#include <vector>

#include "core/image.h"
#include "metrics/lighting_change.h"

namespace svgf::metrics {

// Surface pixels (mesh id != 0) of the current frame whose motion vector (prev = (x, y) +
// motion, rounded to the nearest pixel) lands off the image or on a pixel that showed another
// mesh in the previous frame. An object's leading edge, which its motion carries back onto the
// object, is not in it; the wall it uncovered, whose motion is 0 and whose pixel showed the
// object, is.
PixelMask disoccluded_pixels(const std::vector<uint32_t>& mesh_previous,
                             const std::vector<uint32_t>& mesh_current, const Image& motion);

}  // namespace svgf::metrics

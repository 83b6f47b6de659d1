#pragma once
// A frame's inputs as a backend holds them for the filters: views into host memory (the CPU
// reads the Frame in place) or device memory (the CUDA backend's upload). Every method reads
// its inputs through this; the previous frame's guides are kept by the backend.
#include "core/views.h"

namespace svgf {

struct FrameInputs {
  GuideView guides;
  ConstRgbView color;
  ConstRgbView albedo;
  ConstRgbView emission;  // no planes when the frame has no emission channel
  ConstRgbView position;  // world positions, for methods that ask for them (else no planes)
  // The split of color (direct + indirect), for methods that ask for it and frames that carry
  // both (else no planes).
  ConstRgbView direct;
  ConstRgbView indirect;
};

}  // namespace svgf

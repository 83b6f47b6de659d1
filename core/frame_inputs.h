#pragma once
// A frame's inputs as a backend holds them for the filters: views into host memory (the CPU
// reads the Frame in place) or device memory (the CUDA backend's upload). Every method reads
// its inputs through this; the previous frame's guides are kept by the backend.
#include "core/sanitize.h"
#include "core/views.h"

namespace svgf {

// A-SVGF's gradient samples (Frame::gradient), three planes of the frame's size: the previous
// and the current luminance of the one re-shaded sample of each stratum, and its mask (1 at the
// pixel that holds the sample, else 0). Not sanitized: the gradient stage ignores a sample whose
// luminances are not radiance (methods/svgf/gradient.h).
struct GradientSampleView {
  const float* previous = nullptr;
  const float* current = nullptr;
  const float* mask = nullptr;
  SVGF_HD bool present() const { return mask != nullptr; }
};

struct FrameInputs {
  GuideView guides;
  ConstRgbView color;
  ConstRgbView albedo;
  ConstRgbView emission;  // no planes when the frame has no emission channel
  ConstRgbView position;  // world positions, for methods that ask for them (else no planes)
  GradientSampleView gradient;  // no planes when the frame has no gradient samples
  // The split of color (direct + indirect), for methods that ask for it and frames that carry
  // both (else no planes).
  ConstRgbView direct;
  ConstRgbView indirect;
  // Where the method let the backend leave the sanitize stage to it (a backend that stores the
  // inputs in planes of its own: CUDA): the rule in place over the planes above, not yet run.
  // The method runs it (run_tallying, stage kSanitizeStage) before any stage reads the inputs,
  // or fuses it into its first pixel kernel (methods/svgf/pipeline.h).
  bool sanitize_pending = false;
  SanitizeInputs sanitize;
};

}  // namespace svgf

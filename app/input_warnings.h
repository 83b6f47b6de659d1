#pragma once
// Input that reads and validates fine but silently defeats the filters (issue 16's traps). Each
// warning has a kind (for counting over a run) and a sentence that says what to do.
#include <string>
#include <vector>

#include "core/frame.h"

namespace svgf::app {

struct InputWarning {
  std::string kind;  // "no-surface", "constant-albedo", "zero-motion"
  std::string text;
};

// The warnings of frame `f`; `previous_camera`: the camera of the frame before it in the
// sequence (whether the camera moved), or null.
std::vector<InputWarning> input_warnings(const Frame& f, const Camera* previous_camera);

}  // namespace svgf::app

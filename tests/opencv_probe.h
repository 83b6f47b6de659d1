#pragma once
// A pixel kernel around core's 3x3 variance prefilter, which no stage kernel exposes on its own
// (the a-trous stage only uses it inside its luminance sigma). It lets the prefilter check run
// on both backends (the generic launcher runs it on the GPU like any kernel).
#include "methods/svgf/atrous.h"
#include "core/views.h"

namespace svgf::cvtest {

struct PrefilterProbe {
  GuideView guides;
  const float* variance = nullptr;
  float* out = nullptr;

  SVGF_HD void operator()(int x, int y) const {
    out[guides.index(x, y)] = prefiltered_variance(guides, variance, x, y);
  }
};

}  // namespace svgf::cvtest

#pragma once
// The split frame's last stage (issue 12, item 2; docs/svgf.md: Direct and indirect): the
// indirect signal's remodulated result added, in place, to the direct's, which carries the
// emission. An indirect part that is exactly 0 leaves the direct's bits: x + 0 is x for every
// x the remodulation produces (never -0, since the illumination is clamped at +0).
#include "core/hd.h"
#include "core/views.h"

namespace svgf {

struct SplitSumKernel {
  int width = 0;
  ConstRgbView indirect;  // remodulated, no emission
  RgbView output;         // in: the direct's remodulated result; out: the sum
  SVGF_HD void operator()(int x, int y) const {
    const int i = y * width + x;
    output.store(i, output.load(i) + indirect.load(i));
  }
};

}  // namespace svgf

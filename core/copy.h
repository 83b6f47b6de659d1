#pragma once
// Small pixel kernels that move data, so a pipeline can copy and repack buffers without knowing
// where they live.
#include "core/views.h"

namespace svgf {

// Each pixel of `src` (anything with load(i)) into `sink` (anything with store(i, value)): a
// copy between storage layouts, or into a sink that computes on the way (a remodulation).
template <class Src, class Sink>
struct ForwardKernel {
  int width = 0;
  Src src;
  Sink sink;
  SVGF_HD void operator()(int x, int y) const {
    const int i = y * width + x;
    sink.store(i, src.load(i));
  }
};

// A plane-by-plane copy of three planes: CopyRgbKernel{width, src, dst}.
using CopyRgbKernel = ForwardKernel<ConstRgbView, RgbView>;

// Depth and normal of the guides packed as one Packed4 per pixel (PackedGuides' storage).
struct PackGuidesKernel {
  GuideView guides;
  Packed4* out = nullptr;
  SVGF_HD void operator()(int x, int y) const {
    const int i = guides.index(x, y);
    Packed4 p;
    p.x = guides.depth[i];
    p.y = guides.normal.r[i];
    p.z = guides.normal.g[i];
    p.w = guides.normal.b[i];
    out[i] = p;
  }
};

}  // namespace svgf

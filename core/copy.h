#pragma once
// Plane copy as a pixel kernel, so the pipeline can move buffers without knowing where they live.
#include "core/views.h"

namespace svgf {

struct CopyRgbKernel {
  int width = 0;
  ConstRgbView src;
  RgbView dst;
  SVGF_HD void operator()(int x, int y) const {
    const int i = y * width + x;
    dst.store(i, src.load(i));
  }
};

}  // namespace svgf

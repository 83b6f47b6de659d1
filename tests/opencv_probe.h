#pragma once
// A pixel kernel around core's 3x3 variance prefilter, which no stage kernel exposes on its own
// (the a-trous stage only uses it inside its luminance sigma). It lets the prefilter check run
// on both backends; opencv_cuda_probe.cu launches it on the GPU.
#include "core/atrous.h"
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

#if defined(SVGF_HAVE_CUDA)
// Launches the probe over width x height; views must hold device pointers. Throws CudaError.
void run_probe_cuda(const PrefilterProbe& probe, int width, int height);
#endif

}  // namespace svgf::cvtest

// GPU launch of the prefilter probe (opencv_probe.h). Compiled with --fmad=false, like the
// backend's exact mode, so the probe evaluates the same expression tree as the CPU.
#include "kernels_cuda/cuda_check.h"
#include "opencv_probe.h"

namespace svgf::cvtest {

__global__ void prefilter_probe_kernel(PrefilterProbe probe, int width, int height) {
  const int x = static_cast<int>(blockIdx.x * blockDim.x + threadIdx.x);
  const int y = static_cast<int>(blockIdx.y * blockDim.y + threadIdx.y);
  if (x < width && y < height) probe(x, y);
}

void run_probe_cuda(const PrefilterProbe& probe, int width, int height) {
  const dim3 block(16, 8);
  const dim3 grid((width + 15) / 16, (height + 7) / 8);
  prefilter_probe_kernel<<<grid, block>>>(probe, width, height);
  SVGF_CUDA_CHECK(cudaGetLastError(), "prefilter_probe_kernel launch");
  SVGF_CUDA_CHECK(cudaDeviceSynchronize(), "prefilter_probe_kernel");
}

}  // namespace svgf::cvtest

// Is there a CUDA device this build can run on? Asked by Backend::Auto and before a CUDA
// denoiser is made, so that a missing device, an old driver or a GPU the fatbinary has no code
// for is a sentence, not a failed launch later.
#include <string>

#include <cuda_runtime.h>

#include "kernels_cuda/cuda_denoisers.h"

namespace svgf::cuda {
namespace {

__global__ void probe_kernel() {}

std::string describe(cudaError_t e) {
  return std::string(cudaGetErrorName(e)) + ": " + cudaGetErrorString(e);
}

}  // namespace

bool device_available(std::string* why_not) {
  int count = 0;
  cudaError_t e = cudaGetDeviceCount(&count);
  if (e != cudaSuccess || count == 0) {
    (void)cudaGetLastError();
    if (why_not)
      *why_not = e != cudaSuccess ? "no usable CUDA device (" + describe(e) + ")"
                                  : std::string("no CUDA device present");
    return false;
  }
  int device = 0;
  e = cudaGetDevice(&device);
  cudaFuncAttributes attributes;
  // Loads this build's device code: fails when the fatbinary has neither machine code nor PTX
  // the driver can compile for this GPU.
  if (e == cudaSuccess) e = cudaFuncGetAttributes(&attributes, probe_kernel);
  if (e != cudaSuccess) {
    (void)cudaGetLastError();
    cudaDeviceProp prop{};
    const bool named = cudaGetDeviceProperties(&prop, device) == cudaSuccess;
    (void)cudaGetLastError();
    if (why_not)
      *why_not = "CUDA device " + std::to_string(device) +
                 (named ? " (" + std::string(prop.name) + ", sm_" + std::to_string(prop.major) +
                              std::to_string(prop.minor) + ")"
                        : std::string()) +
                 " cannot run this build's kernels (" + describe(e) +
                 "); rebuild with CMAKE_CUDA_ARCHITECTURES covering it";
    return false;
  }
  return true;
}

}  // namespace svgf::cuda

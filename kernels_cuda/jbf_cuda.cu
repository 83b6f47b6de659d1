// The joint bilateral filter's CUDA instantiation (methods/jbf/denoiser.h over the CUDA
// backend).
#include "kernels_cuda/cuda_backend.h"
#include "kernels_cuda/cuda_denoisers.h"
#include "kernels_cuda/cuda_launch.cuh"
#include "methods/jbf/denoiser.h"

namespace svgf::cuda {

std::unique_ptr<Denoiser> make_jbf_denoiser(const JbfParams& params, const EngineConfig& config) {
  std::string why;
  if (!device_available(&why)) throw std::runtime_error("backend cuda: " + why);
  return std::make_unique<JbfDenoiser<CudaBackend>>(params, config);
}

}  // namespace svgf::cuda

// The Gaussian baseline's CUDA instantiation (methods/gaussian/denoiser.h over the CUDA backend).
#include "kernels_cuda/cuda_backend.h"
#include "kernels_cuda/cuda_denoisers.h"
#include "kernels_cuda/cuda_launch.cuh"
#include "methods/gaussian/denoiser.h"

namespace svgf::cuda {

std::unique_ptr<Denoiser> make_gaussian_denoiser(const GaussianParams& params,
                                                 const EngineConfig& config) {
  std::string why;
  if (!device_available(&why)) throw std::runtime_error("backend cuda: " + why);
  return std::make_unique<GaussianDenoiser<CudaBackend>>(params, config);
}

}  // namespace svgf::cuda

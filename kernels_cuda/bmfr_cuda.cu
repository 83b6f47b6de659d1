// BMFR's CUDA instantiation: the denoiser written once (methods/bmfr/denoiser.h) over the CUDA
// backend; its pixel kernels through the generic launcher and its regression as a block kernel
// (one thread block per image block, kernels_cuda/cuda_block.cuh).
#include "kernels_cuda/cuda_backend.h"
#include "kernels_cuda/cuda_denoisers.h"
#include "kernels_cuda/cuda_launch.cuh"
#include "methods/bmfr/denoiser.h"

namespace svgf::cuda {

std::unique_ptr<Denoiser> make_bmfr_denoiser(const BmfrParams& params, const EngineConfig& config) {
  std::string why;
  if (!device_available(&why)) throw std::runtime_error("backend cuda: " + why);
  return std::make_unique<BmfrDenoiser<CudaBackend>>(params, config);
}

}  // namespace svgf::cuda

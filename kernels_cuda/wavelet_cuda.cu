// The CIS 565 wavelet filter's CUDA instantiation (methods/wavelet/denoiser.h over the CUDA
// backend).
#include "kernels_cuda/cuda_backend.h"
#include "kernels_cuda/cuda_denoisers.h"
#include "kernels_cuda/cuda_launch.cuh"
#include "methods/wavelet/denoiser.h"

namespace svgf::cuda {

std::unique_ptr<Denoiser> make_wavelet_denoiser(const WaveletParams& params,
                                                const EngineConfig& config) {
  std::string why;
  if (!device_available(&why)) throw std::runtime_error("backend cuda: " + why);
  return std::make_unique<WaveletDenoiser<CudaBackend>>(params, config);
}

}  // namespace svgf::cuda

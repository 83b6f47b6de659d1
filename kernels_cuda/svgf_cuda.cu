// SVGF's CUDA instantiation: the denoiser written once (methods/svgf/denoiser.h) over the CUDA
// backend. Every kernel its pipeline runs, exact and fast, is instantiated here through the
// generic launcher (cuda_launch.cuh), compiled with the exact flags (kernels_cuda/CMakeLists.txt).
#include "kernels_cuda/cuda_backend.h"
#include "kernels_cuda/cuda_denoisers.h"
#include "kernels_cuda/cuda_launch.cuh"
#include "methods/svgf/denoiser.h"

namespace svgf::cuda {

std::unique_ptr<Denoiser> make_svgf_denoiser(const SvgfParams& params, const EngineConfig& config) {
  std::string why;
  if (!device_available(&why)) throw std::runtime_error("backend cuda: " + why);
  return std::make_unique<SvgfDenoiser<CudaBackend>>(params, config);
}

}  // namespace svgf::cuda

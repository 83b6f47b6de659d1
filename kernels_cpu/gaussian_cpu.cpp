#include "kernels_cpu/gaussian_cpu.h"

#include "kernels_cpu/cpu_backend.h"
#include "methods/gaussian/denoiser.h"

namespace svgf::cpu {

std::unique_ptr<Denoiser> make_gaussian_denoiser(const GaussianParams& params,
                                                 const EngineConfig& config) {
  return std::make_unique<GaussianDenoiser<CpuBackend>>(params, config);
}

}  // namespace svgf::cpu

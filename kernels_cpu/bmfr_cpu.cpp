#include "kernels_cpu/bmfr_cpu.h"

#include "kernels_cpu/cpu_backend.h"
#include "methods/bmfr/denoiser.h"

namespace svgf::cpu {

std::unique_ptr<Denoiser> make_bmfr_denoiser(const BmfrParams& params, const EngineConfig& config) {
  return std::make_unique<BmfrDenoiser<CpuBackend>>(params, config);
}

}  // namespace svgf::cpu

// SVGF's CPU instantiation: the denoiser written once (methods/svgf/denoiser.h) over the CPU
// backend, with the vectorized row drivers for its two wide stages (svgf_rows.h).
#include "kernels_cpu/svgf_cpu.h"

#include "kernels_cpu/cpu_backend.h"
#include "kernels_cpu/svgf_rows.h"
#include "methods/svgf/denoiser.h"

namespace svgf::cpu {

std::unique_ptr<Denoiser> make_svgf_denoiser(const SvgfParams& params, const EngineConfig& config) {
  return std::make_unique<SvgfDenoiser<CpuBackend>>(params, config);
}

}  // namespace svgf::cpu

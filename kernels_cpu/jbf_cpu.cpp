#include "kernels_cpu/jbf_cpu.h"

#include "kernels_cpu/cpu_backend.h"
#include "kernels_cpu/jbf_rows.h"
#include "methods/jbf/denoiser.h"

namespace svgf::cpu {

std::unique_ptr<Denoiser> make_jbf_denoiser(const JbfParams& params, const EngineConfig& config) {
  return std::make_unique<JbfDenoiser<CpuBackend>>(params, config);
}

}  // namespace svgf::cpu

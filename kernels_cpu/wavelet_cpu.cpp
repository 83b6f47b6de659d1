#include "kernels_cpu/wavelet_cpu.h"

#include "kernels_cpu/cpu_backend.h"
#include "kernels_cpu/wavelet_rows.h"
#include "methods/wavelet/denoiser.h"

namespace svgf::cpu {

std::unique_ptr<Denoiser> make_wavelet_denoiser(const WaveletParams& params,
                                                const EngineConfig& config) {
  return std::make_unique<WaveletDenoiser<CpuBackend>>(params, config);
}

}  // namespace svgf::cpu

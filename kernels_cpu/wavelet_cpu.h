#pragma once
#include <memory>

#include "core/denoiser.h"
#include "methods/wavelet/params.h"

namespace svgf::cpu {

// The CIS 565 wavelet filter on the CPU (methods/wavelet/denoiser.h over the CPU backend).
std::unique_ptr<Denoiser> make_wavelet_denoiser(const WaveletParams& params,
                                                const EngineConfig& config);

}  // namespace svgf::cpu

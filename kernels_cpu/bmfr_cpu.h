#pragma once
#include <memory>

#include "core/denoiser.h"
#include "methods/bmfr/params.h"

namespace svgf::cpu {

// BMFR (Koskela et al. 2019) on the CPU (methods/bmfr/denoiser.h over the CPU backend).
std::unique_ptr<Denoiser> make_bmfr_denoiser(const BmfrParams& params, const EngineConfig& config);

}  // namespace svgf::cpu

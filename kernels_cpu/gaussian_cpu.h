#pragma once
#include <memory>

#include "core/denoiser.h"
#include "methods/gaussian/params.h"

namespace svgf::cpu {

// The Gaussian baseline on the CPU (methods/gaussian/denoiser.h over the CPU backend).
std::unique_ptr<Denoiser> make_gaussian_denoiser(const GaussianParams& params,
                                                 const EngineConfig& config);

}  // namespace svgf::cpu

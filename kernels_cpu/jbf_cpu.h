#pragma once
#include <memory>

#include "core/denoiser.h"
#include "methods/jbf/params.h"

namespace svgf::cpu {

// The joint bilateral filter (GAMES202) on the CPU (methods/jbf/denoiser.h over the CPU backend).
std::unique_ptr<Denoiser> make_jbf_denoiser(const JbfParams& params, const EngineConfig& config);

}  // namespace svgf::cpu

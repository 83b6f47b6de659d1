#pragma once
#include <memory>

#include "core/denoiser.h"
#include "methods/svgf/params.h"

namespace svgf::cpu {

// SVGF on the CPU: methods/svgf/denoiser.h over the CPU backend (TBB). Exact mode only.
std::unique_ptr<Denoiser> make_svgf_denoiser(const SvgfParams& params, const EngineConfig& config);

}  // namespace svgf::cpu

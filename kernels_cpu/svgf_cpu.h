#pragma once
#include <memory>

#include "core/denoiser.h"

namespace svgf::cpu {

// SVGF on the CPU: core/svgf_pipeline.h driven by CpuEngine (TBB). Exact mode only.
std::unique_ptr<Denoiser> make_svgf_denoiser(const DenoiserConfig& config);

}  // namespace svgf::cpu

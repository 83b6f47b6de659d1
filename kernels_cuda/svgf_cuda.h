#pragma once
// The CUDA backend's entry points for pipeline/make_denoiser.cpp. Plain C++ header: no CUDA
// types, so host-only code can include it.
#include <memory>
#include <string>

#include "core/denoiser.h"

namespace svgf::cuda {

// True when a CUDA device is present and usable; otherwise why_not says why.
bool device_available(std::string* why_not = nullptr);
// SVGF on the GPU, exact (bitwise equal to the CPU) or fast mode.
std::unique_ptr<Denoiser> make_svgf_denoiser(const DenoiserConfig& config);

}  // namespace svgf::cuda

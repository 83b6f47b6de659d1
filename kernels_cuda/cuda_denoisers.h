#pragma once
// The CUDA backend's entry points for pipeline/make_denoiser.cpp. Plain C++ header: no CUDA
// types, so host-only code can include it.
#include <memory>
#include <string>

#include "core/denoiser.h"
#include "methods/bmfr/params.h"
#include "methods/gaussian/params.h"
#include "methods/jbf/params.h"
#include "methods/svgf/params.h"
#include "methods/wavelet/params.h"

namespace svgf::cuda {

// True when a CUDA device is present and usable; otherwise why_not says why.
bool device_available(std::string* why_not = nullptr);

// Each method's instantiation over the CUDA backend, exact (bitwise equal to the CPU) or fast.
std::unique_ptr<Denoiser> make_svgf_denoiser(const SvgfParams& params, const EngineConfig& config);
std::unique_ptr<Denoiser> make_gaussian_denoiser(const GaussianParams& params,
                                                 const EngineConfig& config);
std::unique_ptr<Denoiser> make_wavelet_denoiser(const WaveletParams& params,
                                                const EngineConfig& config);
std::unique_ptr<Denoiser> make_jbf_denoiser(const JbfParams& params, const EngineConfig& config);
std::unique_ptr<Denoiser> make_bmfr_denoiser(const BmfrParams& params, const EngineConfig& config);

}  // namespace svgf::cuda

#pragma once
// Picks a method and a backend: the one place that knows every method. A method is added here
// with its parameter struct and one line in make_denoiser (docs/architecture.md, "Adding a
// method").
#include <memory>
#include <string>

#include "core/denoiser.h"
#include "methods/bmfr/params.h"
#include "methods/gaussian/params.h"
#include "methods/jbf/params.h"
#include "methods/svgf/params.h"
#include "methods/wavelet/params.h"

namespace svgf {

// Jbf and JbfAtrous are one filter (methods/jbf/) in its two forms: the full window and the
// a-trous levels (JbfParams::levels; jbf-atrous with levels 0 takes 4).
enum class Method { Svgf, Gaussian, Wavelet, Jbf, JbfAtrous, Bmfr };

const char* to_string(Method m);
// Parse "svgf|gaussian|wavelet|jbf|jbf-atrous|bmfr"; throws std::invalid_argument naming the value and the known methods.
Method parse_method(const std::string& s);

// The engine settings every method shares, the method, and one parameter struct per method
// (only the chosen method's is read).
struct DenoiserConfig : EngineConfig {
  Method method = Method::Svgf;
  SvgfParams svgf;          // methods/svgf/params.h
  GaussianParams gaussian;  // methods/gaussian/params.h
  WaveletParams wavelet;    // methods/wavelet/params.h
  JbfParams jbf;            // methods/jbf/params.h (jbf and jbf-atrous)
  BmfrParams bmfr;          // methods/bmfr/params.h
};

// Throws std::invalid_argument for an impossible combination (fast mode on the CPU, bad
// parameters) and std::runtime_error when CUDA is asked for but absent. Backend::Auto never
// throws for lack of a device: it falls back to the CPU, and description() says which it chose.
std::unique_ptr<Denoiser> make_denoiser(const DenoiserConfig& config);

// True when this build has the CUDA backend and a CUDA device is present.
bool cuda_available(std::string* why_not = nullptr);

}  // namespace svgf

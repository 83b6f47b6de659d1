// The factory behind the one Denoiser interface: picks the method's instantiation on the
// requested backend. The CUDA backend is linked only when the build has it (SVGF_HAVE_CUDA).
#include "pipeline/make_denoiser.h"

#include <stdexcept>
#include <string>

#include "kernels_cpu/bmfr_cpu.h"
#include "kernels_cpu/gaussian_cpu.h"
#include "kernels_cpu/jbf_cpu.h"
#include "kernels_cpu/svgf_cpu.h"
#include "kernels_cpu/wavelet_cpu.h"
#if defined(SVGF_HAVE_CUDA)
#include "kernels_cuda/cuda_denoisers.h"
#endif

namespace svgf {

const char* to_string(Method m) {
  switch (m) {
    case Method::Svgf: return "svgf";
    case Method::Gaussian: return "gaussian";
    case Method::Wavelet: return "wavelet";
    case Method::Jbf: return "jbf";
    case Method::JbfAtrous: return "jbf-atrous";
    case Method::Bmfr: return "bmfr";
  }
  return "?";
}
const char* to_string(Backend b) {
  switch (b) {
    case Backend::Cpu: return "cpu";
    case Backend::Cuda: return "cuda";
    case Backend::Auto: return "auto";
  }
  return "?";
}
const char* to_string(Mode m) { return m == Mode::Exact ? "exact" : "fast"; }

Method parse_method(const std::string& s) {
  if (s == "svgf") return Method::Svgf;
  if (s == "gaussian") return Method::Gaussian;
  if (s == "wavelet") return Method::Wavelet;
  if (s == "jbf") return Method::Jbf;
  if (s == "jbf-atrous") return Method::JbfAtrous;
  if (s == "bmfr") return Method::Bmfr;
  throw std::invalid_argument("unknown method '" + s +
                              "' (known: svgf, gaussian, wavelet, jbf, jbf-atrous, bmfr)");
}
Backend parse_backend(const std::string& s) {
  if (s == "cpu") return Backend::Cpu;
  if (s == "cuda") return Backend::Cuda;
  if (s == "auto") return Backend::Auto;
  throw std::invalid_argument("unknown backend '" + s + "' (known: cpu, cuda, auto)");
}
Mode parse_mode(const std::string& s) {
  if (s == "exact") return Mode::Exact;
  if (s == "fast") return Mode::Fast;
  throw std::invalid_argument("unknown mode '" + s + "' (known: exact, fast)");
}

bool cuda_available(std::string* why_not) {
#if defined(SVGF_HAVE_CUDA)
  return cuda::device_available(why_not);
#else
  if (why_not) *why_not = "this build has no CUDA backend (nvcc was not found at configure time)";
  return false;
#endif
}

std::unique_ptr<Denoiser> make_denoiser(const DenoiserConfig& config) {
  DenoiserConfig c = config;
  if (c.backend == Backend::Auto) {
    c.backend = cuda_available() ? Backend::Cuda : Backend::Cpu;
    // Fast mode is a GPU mode; on the CPU fallback the exact pipeline is what exists.
    if (c.backend == Backend::Cpu) c.mode = Mode::Exact;
  }
  // jbf-atrous is the joint bilateral filter in its a-trous form (JbfParams::levels > 0).
  if (c.method == Method::JbfAtrous && c.jbf.levels <= 0) c.jbf.levels = 4;
  if (c.method == Method::Jbf) c.jbf.levels = 0;
  const EngineConfig& e = c;
  if (c.backend == Backend::Cuda) {
    std::string why;
    if (!cuda_available(&why)) throw std::runtime_error("backend cuda: " + why);
#if defined(SVGF_HAVE_CUDA)
    switch (c.method) {
      case Method::Svgf: return cuda::make_svgf_denoiser(c.svgf, e);
      case Method::Gaussian: return cuda::make_gaussian_denoiser(c.gaussian, e);
      case Method::Wavelet: return cuda::make_wavelet_denoiser(c.wavelet, e);
      case Method::Jbf:
      case Method::JbfAtrous: return cuda::make_jbf_denoiser(c.jbf, e);
      case Method::Bmfr: return cuda::make_bmfr_denoiser(c.bmfr, e);
    }
#endif
  }
  switch (c.method) {
    case Method::Svgf: return cpu::make_svgf_denoiser(c.svgf, e);
    case Method::Gaussian: return cpu::make_gaussian_denoiser(c.gaussian, e);
    case Method::Wavelet: return cpu::make_wavelet_denoiser(c.wavelet, e);
    case Method::Jbf:
    case Method::JbfAtrous: return cpu::make_jbf_denoiser(c.jbf, e);
    case Method::Bmfr: return cpu::make_bmfr_denoiser(c.bmfr, e);
  }
  throw std::invalid_argument("make_denoiser: unknown method");
}

}  // namespace svgf

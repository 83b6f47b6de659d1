// The factory behind the one Denoiser interface: picks the method's implementation on the
// requested backend. The CUDA backend is linked only when the build has it (SVGF_HAVE_CUDA).
#include <stdexcept>
#include <string>

#include "core/denoiser.h"
#include "kernels_cpu/svgf_cpu.h"
#if defined(SVGF_HAVE_CUDA)
#include "kernels_cuda/svgf_cuda.h"
#endif

namespace svgf {

const char* to_string(Method m) {
  switch (m) {
    case Method::Svgf: return "svgf";
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
  throw std::invalid_argument("unknown method '" + s + "' (known: svgf)");
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
  if (c.backend == Backend::Cuda) {
#if defined(SVGF_HAVE_CUDA)
    std::string why;
    if (!cuda::device_available(&why)) throw std::runtime_error("backend cuda: " + why);
    return cuda::make_svgf_denoiser(c);
#else
    std::string why;
    cuda_available(&why);
    throw std::runtime_error("backend cuda: " + why);
#endif
  }
  return cpu::make_svgf_denoiser(c);
}

}  // namespace svgf

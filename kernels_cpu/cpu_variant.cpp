// The run-time pick of a CPU kernel variant (cpu_variant.h), and the entry points the rest of
// the program calls (the factories of <method>_cpu.h, the row drivers of <method>_rows.h),
// forwarding to the picked variant. Compiled for the baseline x86-64, like every caller.
#include "kernels_cpu/cpu_variant.h"

#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include "kernels_cpu/bmfr_cpu.h"
#include "kernels_cpu/gaussian_cpu.h"
#include "kernels_cpu/jbf_cpu.h"
#include "kernels_cpu/sanitize_rows.h"
#include "kernels_cpu/svgf_cpu.h"
#include "kernels_cpu/svgf_rows.h"
#include "kernels_cpu/wavelet_cpu.h"

// Each variant's one exported function (variant_entry.cpp), listed by the build.
#define SVGF_CPU_VARIANT(entry) extern "C" const svgf::cpu::CpuVariant* entry();
#include "cpu_variant_list.inc"
#undef SVGF_CPU_VARIANT

namespace svgf::cpu {
namespace {

constexpr const char* kEnvironment = "SVGF_CPU_ISA";

// Whether the CPU (and the OS: AVX state saved) has a feature variant_entry.cpp may list.
bool cpu_has(const char* feature) {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_cpu_init();
  struct Check {
    const char* name;
    bool present;
  };
  const Check checks[] = {{"sse3", __builtin_cpu_supports("sse3") != 0},
                          {"ssse3", __builtin_cpu_supports("ssse3") != 0},
                          {"sse4.1", __builtin_cpu_supports("sse4.1") != 0},
                          {"sse4.2", __builtin_cpu_supports("sse4.2") != 0},
                          {"popcnt", __builtin_cpu_supports("popcnt") != 0},
                          {"avx", __builtin_cpu_supports("avx") != 0},
                          {"avx2", __builtin_cpu_supports("avx2") != 0},
                          {"fma", __builtin_cpu_supports("fma") != 0},
                          {"bmi", __builtin_cpu_supports("bmi") != 0},
                          {"bmi2", __builtin_cpu_supports("bmi2") != 0},
                          {"avx512f", __builtin_cpu_supports("avx512f") != 0},
                          {"avx512bw", __builtin_cpu_supports("avx512bw") != 0},
                          {"avx512cd", __builtin_cpu_supports("avx512cd") != 0},
                          {"avx512dq", __builtin_cpu_supports("avx512dq") != 0},
                          {"avx512vl", __builtin_cpu_supports("avx512vl") != 0}};
  for (const Check& c : checks)
    if (std::strcmp(c.name, feature) == 0) return c.present;
  return false;  // a feature this list does not know: not assumed present
#else
  (void)feature;
  return false;
#endif
}

// GCC 12 also checks a whole x86-64 level as -march defines it (CMPXCHG16B, MOVBE, F16C, ...
// included, which the list above leaves out).
bool cpu_has_level(const std::string& id) {
#if (defined(__x86_64__) || defined(__i386__)) && defined(__GNUC__) && !defined(__clang__) && \
    __GNUC__ >= 12
  if (id == "v2") return __builtin_cpu_supports("x86-64-v2") != 0;
  if (id == "v3") return __builtin_cpu_supports("x86-64-v3") != 0;
  if (id == "v4") return __builtin_cpu_supports("x86-64-v4") != 0;
#else
  (void)id;
#endif
  return true;
}

std::string known_names() {
  std::string s = "auto";
  for (const CpuVariant* v : built_variants()) s += std::string(", ") + v->id;
  return s;
}

std::string names_running_here() {
  std::string s;
  for (const CpuVariant* v : built_variants())
    if (runs_here(*v)) s += (s.empty() ? "" : ", ") + std::string(v->name);
  return s.empty() ? "none" : s;
}

}  // namespace

const std::vector<const CpuVariant*>& built_variants() {
  static const std::vector<const CpuVariant*> variants = {
#define SVGF_CPU_VARIANT(entry) entry(),
#include "cpu_variant_list.inc"
#undef SVGF_CPU_VARIANT
  };
  return variants;
}

bool runs_here(const CpuVariant& v, std::string* why_not) {
  std::string missing;
  for (const char* const* f = v.needs; *f != nullptr; ++f)
    if (!cpu_has(*f)) missing += (missing.empty() ? "" : ", ") + std::string(*f);
  if (missing.empty() && !cpu_has_level(v.id)) missing = "part of the level (cx16, movbe, f16c, ...)";
  if (why_not) *why_not = missing.empty() ? "" : "this CPU lacks " + missing;
  return missing.empty();
}

const CpuVariant& pick_variant(const std::string& request) {
  std::string asked = request, source = "cpu_isa";
  if (asked.empty()) {
    const char* env = std::getenv(kEnvironment);
    asked = env != nullptr && *env != '\0' ? env : "auto";
    source = kEnvironment;
  }
  const auto& variants = built_variants();
  if (asked == "auto") {
    for (auto it = variants.rbegin(); it != variants.rend(); ++it)
      if (runs_here(**it)) return **it;
    std::string why;
    runs_here(*variants.front(), &why);
    throw std::runtime_error(std::string("no CPU kernel variant of this build runs on this CPU: ") +
                             variants.front()->name + ": " + why);
  }
  const bool known = asked == "v2" || asked == "v3" || asked == "v4" || asked == "custom";
  for (const CpuVariant* v : variants)
    if (asked == v->id) {
      std::string why;
      if (!runs_here(*v, &why))
        throw std::runtime_error(source + "=" + asked + ": the " + v->name +
                                 " CPU kernels cannot run here: " + why +
                                 " (it runs: " + names_running_here() + ")");
      return *v;
    }
  if (known)
    throw std::runtime_error(source + "=" + asked + ": this build has no such CPU kernel variant "
                             "(built: " + known_names() + "; SVGF_CPU_ISAS at configure time)");
  throw std::invalid_argument(source + "=" + asked + ": unknown CPU kernel variant (known: " +
                              known_names() + ")");
}

// The entry points of <method>_cpu.h and <method>_rows.h for callers outside the variants.
// Each variant defines the same names for its own calls; they are local to its object.
std::unique_ptr<Denoiser> make_svgf_denoiser(const SvgfParams& params, const EngineConfig& config) {
  return pick_variant(config.cpu_isa).make_svgf(params, config);
}
std::unique_ptr<Denoiser> make_gaussian_denoiser(const GaussianParams& params,
                                                 const EngineConfig& config) {
  return pick_variant(config.cpu_isa).make_gaussian(params, config);
}
std::unique_ptr<Denoiser> make_wavelet_denoiser(const WaveletParams& params,
                                                const EngineConfig& config) {
  return pick_variant(config.cpu_isa).make_wavelet(params, config);
}
std::unique_ptr<Denoiser> make_jbf_denoiser(const JbfParams& params, const EngineConfig& config) {
  return pick_variant(config.cpu_isa).make_jbf(params, config);
}
std::unique_ptr<Denoiser> make_bmfr_denoiser(const BmfrParams& params, const EngineConfig& config) {
  return pick_variant(config.cpu_isa).make_bmfr(params, config);
}
void run_atrous_rows(const AtrousKernel& kernel, int width, int height,
                     const AtrousRowOutputs& outputs) {
  pick_variant("").atrous_rows(kernel, width, height, outputs);
}
void run_variance_rows(const VarianceKernel& kernel, int width, int height) {
  pick_variant("").variance_rows(kernel, width, height);
}
void run_reproject_rows(const ReprojectKernel& kernel, int width, int height) {
  pick_variant("").reproject_rows(kernel, width, height);
}
void run_gradient_samples_rows(const GradientSamplesKernel& kernel, int strata_width,
                               int strata_height) {
  pick_variant("").gradient_samples_rows(kernel, strata_width, strata_height);
}
void run_gradient_atrous_rows(const GradientAtrousKernel& kernel, int strata_width,
                              int strata_height) {
  pick_variant("").gradient_atrous_rows(kernel, strata_width, strata_height);
}
void run_gradient_lambda_rows(const GradientLambdaKernel& kernel, int strata_width,
                              int strata_height) {
  pick_variant("").gradient_lambda_rows(kernel, strata_width, strata_height);
}
void run_wavelet_rows(const WaveletExactIteration& kernel, int width, int height) {
  pick_variant("").wavelet_rows(kernel, width, height);
}
void run_jbf_rows(const JbfPass<ExactArith>& kernel, int width, int height) {
  pick_variant("").jbf_rows(kernel, width, height);
}
Tallies run_sanitize_rows(const SanitizeInputs& kernel, int width, int height) {
  return pick_variant("").sanitize_rows(kernel, width, height);
}

}  // namespace svgf::cpu

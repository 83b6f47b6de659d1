#pragma once
// The CPU kernels are built once per x86-64 level (x86-64-v2, -v3, -v4: kernels_cpu/
// CMakeLists.txt) and one variant is picked at run time: the widest this CPU runs, unless
// EngineConfig::cpu_isa or the environment variable SVGF_CPU_ISA asks for another
// (docs/architecture.md, "One binary for every x86-64"). The factories (svgf_cpu.h, ...) and
// the row drivers (svgf_rows.h, ...) called from outside go through the variant picked here.
#include <memory>
#include <string>
#include <vector>

#include "core/denoiser.h"
#include "core/sanitize.h"
#include "core/tallies.h"
#include "kernels_cpu/jbf_rows.h"
#include "kernels_cpu/wavelet_rows.h"
#include "methods/bmfr/params.h"
#include "methods/gaussian/params.h"
#include "methods/jbf/params.h"
#include "methods/svgf/atrous.h"
#include "methods/svgf/gradient.h"
#include "methods/svgf/params.h"
#include "methods/svgf/reproject.h"
#include "methods/svgf/variance.h"
#include "methods/wavelet/params.h"

namespace svgf::cpu {

struct AtrousRowOutputs;  // kernels_cpu/svgf_rows.h

// One variant's entry points (kernels_cpu/variant_entry.cpp): what the rest of the program may
// call in it.
struct CpuVariant {
  const char* id;    // "v2", "v3", "v4"; "custom" for a build with SVGF_CPU_ARCH_FLAGS
  const char* name;  // "x86-64-v3", as descriptions and reports print it
  // The CPU features its code needs, from the compiler's own macros (__AVX2__ -> "avx2", ...),
  // ending with nullptr.
  const char* const* needs;
  std::unique_ptr<Denoiser> (*make_svgf)(const SvgfParams&, const EngineConfig&);
  std::unique_ptr<Denoiser> (*make_gaussian)(const GaussianParams&, const EngineConfig&);
  std::unique_ptr<Denoiser> (*make_wavelet)(const WaveletParams&, const EngineConfig&);
  std::unique_ptr<Denoiser> (*make_jbf)(const JbfParams&, const EngineConfig&);
  std::unique_ptr<Denoiser> (*make_bmfr)(const BmfrParams&, const EngineConfig&);
  void (*atrous_rows)(const AtrousKernel&, int, int, const AtrousRowOutputs&);
  void (*variance_rows)(const VarianceKernel&, int, int);
  void (*reproject_rows)(const ReprojectKernel&, int, int);
  void (*gradient_samples_rows)(const GradientSamplesKernel&, int, int);
  void (*gradient_atrous_rows)(const GradientAtrousKernel&, int, int);
  void (*gradient_lambda_rows)(const GradientLambdaKernel&, int, int);
  void (*wavelet_rows)(const WaveletExactIteration&, int, int);
  void (*jbf_rows)(const JbfPass<ExactArith>&, int, int);
  Tallies (*sanitize_rows)(const SanitizeInputs&, int, int);
};

// The variants this build has, narrowest first.
const std::vector<const CpuVariant*>& built_variants();

// Whether this CPU runs `v`; if not, why_not names the missing features.
bool runs_here(const CpuVariant& v, std::string* why_not = nullptr);

// The variant a request picks. "auto": the widest built variant this CPU runs; "v2", "v3",
// "v4", "custom": that one; "" (EngineConfig's default): SVGF_CPU_ISA if set, else auto.
// Throws std::invalid_argument for an unknown name, std::runtime_error for a variant this
// build lacks or this CPU cannot run (naming the missing features).
const CpuVariant& pick_variant(const std::string& request);

}  // namespace svgf::cpu

// One instruction-set variant's entry point, compiled into each variant with its flags. The
// function SVGF_CPU_VARIANT_ENTRY (svgf_cpu_variant_v3, ...) is the only global symbol the
// variant's object keeps (kernels_cpu/CMakeLists.txt): every name below binds to this
// variant's own copy.
#include "kernels_cpu/bmfr_cpu.h"
#include "kernels_cpu/cpu_variant.h"
#include "kernels_cpu/gaussian_cpu.h"
#include "kernels_cpu/jbf_cpu.h"
#include "kernels_cpu/sanitize_rows.h"
#include "kernels_cpu/svgf_cpu.h"
#include "kernels_cpu/svgf_rows.h"
#include "kernels_cpu/wavelet_cpu.h"

namespace svgf::cpu {
namespace {

// What this variant's code needs of the CPU, as the compiler sees it; cpu_variant.cpp checks
// each by name.
const char* const kNeeds[] = {
#if defined(__SSE3__)
    "sse3",
#endif
#if defined(__SSSE3__)
    "ssse3",
#endif
#if defined(__SSE4_1__)
    "sse4.1",
#endif
#if defined(__SSE4_2__)
    "sse4.2",
#endif
#if defined(__POPCNT__)
    "popcnt",
#endif
#if defined(__AVX__)
    "avx",
#endif
#if defined(__AVX2__)
    "avx2",
#endif
#if defined(__FMA__)
    "fma",
#endif
#if defined(__BMI__)
    "bmi",
#endif
#if defined(__BMI2__)
    "bmi2",
#endif
#if defined(__AVX512F__)
    "avx512f",
#endif
#if defined(__AVX512BW__)
    "avx512bw",
#endif
#if defined(__AVX512CD__)
    "avx512cd",
#endif
#if defined(__AVX512DQ__)
    "avx512dq",
#endif
#if defined(__AVX512VL__)
    "avx512vl",
#endif
    nullptr};

const CpuVariant kVariant = {SVGF_CPU_VARIANT_ID,       SVGF_CPU_VARIANT_NAME,
                             kNeeds,                    make_svgf_denoiser,
                             make_gaussian_denoiser,    make_wavelet_denoiser,
                             make_jbf_denoiser,         make_bmfr_denoiser,
                             run_atrous_rows,           run_variance_rows,
                             run_reproject_rows,        run_gradient_samples_rows,
                             run_gradient_atrous_rows,  run_gradient_lambda_rows,
                             run_wavelet_rows,          run_jbf_rows,
                             run_sanitize_rows};

}  // namespace
}  // namespace svgf::cpu

extern "C" const svgf::cpu::CpuVariant* SVGF_CPU_VARIANT_ENTRY() { return &svgf::cpu::kVariant; }

#pragma once
// SVGF_HD marks a function that runs on both sides: __host__ __device__ under nvcc, nothing
// under a plain C++ compiler. Every per-pixel function in core/ carries it, so the CPU and the
// CUDA drivers call the very same code (the pbrt-v4 PBRT_CPU_GPU idea).
#if defined(__CUDACC__)
#define SVGF_HD __host__ __device__ __forceinline__
#else
#define SVGF_HD inline
#endif

// SVGF_HD for the small parts of the shared math that the CPU's vector loops must inline (the
// device side inlines every SVGF_HD function): the exp and its wrappers in core/arith.h. GCC
// inlines by a size budget, and when det_exp's polynomial lost a step its heuristics left
// ExactArith::exp_neg_sum a call in the gradient a-trous row (nine unrolled taps), which then
// stayed scalar: 1.6 -> 5.8 ms at 720p on a Zen 5 VM.
#if defined(__CUDACC__)
#define SVGF_HD_INLINE SVGF_HD
#else
#define SVGF_HD_INLINE inline __attribute__((always_inline))
#endif

// Before an SVGF_HD template that calls what it is given (a lambda, a Block): instantiated with
// host-only arguments, nvcc would warn that device code calls host code, for instantiations
// that are never compiled for the device.
#if defined(__CUDACC__)
#define SVGF_HD_TEMPLATE _Pragma("nv_exec_check_disable")
#else
#define SVGF_HD_TEMPLATE
#endif

// Before a loop of constant trip count whose body indexes a small local array: unrolled on the
// device, the array stays in registers instead of the stack.
#if defined(__CUDA_ARCH__)
#define SVGF_UNROLL _Pragma("unroll")
#else
#define SVGF_UNROLL
#endif

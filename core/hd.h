#pragma once
// SVGF_HD marks a function that runs on both sides: __host__ __device__ under nvcc, nothing
// under a plain C++ compiler. Every per-pixel function in core/ carries it, so the CPU and the
// CUDA drivers call the very same code (the pbrt-v4 PBRT_CPU_GPU idea).
#if defined(__CUDACC__)
#define SVGF_HD __host__ __device__ __forceinline__
#else
#define SVGF_HD inline
#endif

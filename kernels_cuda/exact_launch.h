#pragma once
// Stream-ordered launches of the core/ pixel kernels, compiled once, in exact mode, in
// exact_kernels.cu. Host-compilable: the engine, the stage runner and the denoiser are plain
// C++ and reach the GPU only through these. Each throws CudaError naming the kernel when the
// launch is refused.
#include <cuda_runtime_api.h>

#include "kernels_cuda/stage_runner.h"

namespace svgf::cuda {

// `count` (device memory) is incremented by the number of pixels whose sample was replaced.
void launch(const DemodulateKernel& k, int width, int height, LaunchShape shape,
            cudaStream_t stream, unsigned long long* count);
void launch(const ReprojectKernel& k, int width, int height, LaunchShape shape,
            cudaStream_t stream);
void launch(const VarianceKernel& k, int width, int height, LaunchShape shape,
            cudaStream_t stream);
void launch(const AtrousKernel& k, int width, int height, LaunchShape shape, cudaStream_t stream);
void launch(const RemodulateKernel& k, int width, int height, LaunchShape shape,
            cudaStream_t stream);
void launch(const TonemapKernel& k, int width, int height, LaunchShape shape,
            cudaStream_t stream);
void launch(const CopyRgbKernel& k, int width, int height, LaunchShape shape,
            cudaStream_t stream);

// Demodulate then reproject, per pixel, in one launch (exact flags: the history decisions of
// fast mode stay those of exact mode), also packing each pixel's depth and normal as one float4
// (`packed_guides`, 4 floats a pixel, 16-byte aligned) for the fast filters.
void launch_demodulate_reproject(const DemodulateKernel& demodulate,
                                 const ReprojectKernel& reproject, float* packed_guides,
                                 LaunchShape shape, cudaStream_t stream,
                                 unsigned long long* count);

// The name each kernel goes by in error messages.
inline const char* kernel_name(const DemodulateKernel&) { return "demodulate"; }
inline const char* kernel_name(const ReprojectKernel&) { return "reproject"; }
inline const char* kernel_name(const VarianceKernel&) { return "variance"; }
inline const char* kernel_name(const AtrousKernel&) { return "atrous"; }
inline const char* kernel_name(const RemodulateKernel&) { return "remodulate"; }
inline const char* kernel_name(const TonemapKernel&) { return "tonemap"; }
inline const char* kernel_name(const CopyRgbKernel&) { return "copy_rgb"; }

}  // namespace svgf::cuda

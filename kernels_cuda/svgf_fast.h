#pragma once
// Fast mode (svgf_fast.cu, built with --use_fast_math): the same data flow as
// core/svgf_pipeline.h with fused launches, packed buffers and hardware intrinsics. Not bitwise
// equal to the CPU; its tolerance against exact mode is in docs/cuda.md and tests/gpu_test.cpp.
// Host-compilable.
#include "core/params.h"
#include "core/svgf_pipeline.h"
#include "kernels_cuda/cuda_engine.h"

namespace svgf::cuda::fast {

// Device scratch fast mode needs on top of SvgfFrameBuffers; every pointer 16-byte aligned.
struct FastBuffers {
  float* packed[2] = {nullptr, nullptr};  // 4 floats a pixel: r, g, b, variance (a-trous ping-pong)
  float* guides = nullptr;                // 4 floats a pixel: depth, normal x, y, z
};

// One frame, enqueued on engine.stream(): fills the same outputs as run_svgf_frame (output,
// next history, illumination, accumulated); b.filtered is not used.
void run_frame(CudaEngine& engine, const SvgfFrameBuffers& b, const FastBuffers& f,
               const SvgfParams& p, bool has_history);

}  // namespace svgf::cuda::fast

#pragma once
// The one generic launcher: any pixel kernel (a struct with SVGF_HD operator()(x, y)) becomes a
// CUDA launch, one thread per pixel. Included only by .cu files: the file that instantiates a
// method (kernels_cuda/<method>_cuda.cu) instantiates every kernel its pipeline runs, and a test
// compiled by nvcc can run any single kernel. Compiled with the exact flags
// (kernels_cuda/CMakeLists.txt): each float operation rounds as on the CPU; fast mode's
// arithmetic is chosen explicitly by its functors (core/arith.h), not by compiler flags.
#include <cstdint>
#include <string>
#include <type_traits>

#include <cuda_runtime.h>

#include "core/rare_path.h"
#include "kernels_cuda/cuda_block.cuh"
#include "kernels_cuda/cuda_check.h"
#include "kernels_cuda/cuda_engine.h"
#include "kernels_cuda/device_array.h"
#include "kernels_cuda/launch_config.h"
#include "kernels_cuda/pixel_kernels.cuh"

namespace svgf::cuda {

// The kernel struct travels by value as a launch parameter (a few hundred bytes of views and
// parameters, well under the 4 KB limit).
template <class K>
__global__ void pixel_kernel(const K k, int width, int height) {
  const int x = device::pixel_x();
  const int y = device::pixel_y();
  if (x < width && y < height) k(x, y);
}

// For kernels that ask for a register cap (K::kMaxRegisters > 0): more threads resident an SM
// where registers limit them, at the price of what the compiler then spills (the exact a-trous,
// methods/svgf/flavors.h). The same code, so the same bits.
template <class K, class = void>
struct RegisterCap : std::integral_constant<int, 0> {};
template <class K>
struct RegisterCap<K, std::void_t<decltype(K::kMaxRegisters)>>
    : std::integral_constant<int, K::kMaxRegisters> {};

template <class K, int kRegisters>
__global__ void __maxnreg__(kRegisters) capped_pixel_kernel(const K k, int width, int height) {
  const int x = device::pixel_x();
  const int y = device::pixel_y();
  if (x < width && y < height) k(x, y);
}

// For kernels with a rare path (core/rare_path.h): every thread tries the common path; the
// block's rare pixels are listed in shared memory (rare_pixels: one int per thread of the block)
// and taken by the block's first threads, so the expensive path fills whole warps.
template <class K>
__global__ void compacting_pixel_kernel(const K k, int width, int height) {
  extern __shared__ int rare_pixels[];
  __shared__ int rare_count;
  const int t = static_cast<int>(threadIdx.y * blockDim.x + threadIdx.x);
  if (t == 0) rare_count = 0;
  __syncthreads();
  const int x = device::pixel_x();
  const int y = device::pixel_y();
  if (x < width && y < height && !k.common_path(x, y)) rare_pixels[atomicAdd(&rare_count, 1)] = t;
  __syncthreads();
  if (t < rare_count) {
    const int s = rare_pixels[t];
    const int bx = static_cast<int>(blockDim.x);
    k.rare_path(static_cast<int>(blockIdx.x) * bx + s % bx,
                static_cast<int>(blockIdx.y * blockDim.y) + s / bx);
  }
}

// For kernels returning bool: counts the pixels that returned true.
template <class K>
__global__ void counting_pixel_kernel(const K k, int width, int height,
                                      unsigned long long* count) {
  const int x = device::pixel_x();
  const int y = device::pixel_y();
  const bool flag = x < width && y < height && k(x, y);
  device::count_block(flag, count);
}

// For kernels returning a bit mask: per-bit counts into counts[0 .. kTallyBits).
template <class K>
__global__ void tallying_pixel_kernel(const K k, int width, int height,
                                      unsigned long long* counts) {
  const int x = device::pixel_x();
  const int y = device::pixel_y();
  const uint32_t mask = x < width && y < height ? k(x, y) : 0u;
  device::tally_block(mask, counts);
}

// Stream-ordered launch; `count` (device memory) set: a counting kernel (bool: one count;
// uint32_t: kTallyBits counts). Throws CudaError
// naming `what` when the launch is refused.
template <class K>
void launch(const K& k, int width, int height, LaunchShape shape, cudaStream_t stream,
            const char* what, unsigned long long* count = nullptr) {
  if (width <= 0 || height <= 0) return;
  const LaunchGeometry g = launch_geometry(width, height, shape);
  if constexpr (std::is_same_v<decltype(k(0, 0)), uint32_t>) {
    if (count) {
      tallying_pixel_kernel<K><<<g.grid, g.block, 0, stream>>>(k, width, height, count);
      check_launch(what, g);
      return;
    }
  }
  if constexpr (std::is_same_v<decltype(k(0, 0)), bool>) {
    if (count) {
      counting_pixel_kernel<K><<<g.grid, g.block, 0, stream>>>(k, width, height, count);
      check_launch(what, g);
      return;
    }
  }
  if constexpr (HasRarePath<K>::value) {
    const size_t list_bytes = sizeof(int) * g.block.x * g.block.y;
    compacting_pixel_kernel<K><<<g.grid, g.block, list_bytes, stream>>>(k, width, height);
  } else if constexpr (RegisterCap<K>::value > 0) {
    capped_pixel_kernel<K, RegisterCap<K>::value><<<g.grid, g.block, 0, stream>>>(k, width, height);
  } else {
    pixel_kernel<K><<<g.grid, g.block, 0, stream>>>(k, width, height);
  }
  check_launch(what, g);
}

// A block kernel (core/block_reduce.h): one thread block of block::kThreads per block, its
// scratch and the reductions' warp totals in dynamic shared memory (beyond the 48 KB default:
// the kernel is allowed what it needs first).
template <class K>
void launch_blocks(const K& k, int blocks, cudaStream_t stream, const char* what) {
  if (blocks <= 0) return;
  constexpr size_t kBytes = (K::kScratchFloats + CudaBlock::kReductionFloats) * sizeof(float);
  static_assert(kBytes <= 227 * 1024, "a block's scratch must fit the shared memory of sm_90");
  SVGF_CUDA_CHECK(cudaFuncSetAttribute(block_kernel<K>, cudaFuncAttributeMaxDynamicSharedMemorySize,
                                       static_cast<int>(kBytes)),
                  std::string("shared memory for kernel '") + what + "'");
  LaunchGeometry g;
  g.grid = dim3(static_cast<unsigned>(blocks));
  g.block = dim3(block::kThreads);
  block_kernel<K><<<g.grid, g.block, kBytes, stream>>>(k);
  check_launch(what, g);
}

template <class Kernel>
void CudaEngine::run_blocks(const char* stage, const Kernel& kernel, int blocks) {
  mark(stage);
  launch_blocks(kernel, blocks, stream_, stage);
}

template <class Kernel>
void CudaEngine::run(const char* stage, const Kernel& kernel, int width, int height) {
  mark(stage);
  launch(kernel, width, height, shape_, stream_, stage);
}

template <class Kernel>
void CudaEngine::run_tallying(const char* stage, const Kernel& kernel, int width, int height) {
  static_assert(std::is_same_v<decltype(kernel(0, 0)), uint32_t>, "a tallying kernel returns a mask");
  mark(stage);
  launch(kernel, width, height, shape_, stream_, stage, counter_.get());
}

// One kernel on the default stream, waited for: for tests and tools. Views inside the kernel
// must point to device memory. A counting kernel (returning bool) returns the count, any other
// 0. Throws CudaError naming `what` on a refused launch or a fault while running.
template <class K>
int64_t run(const K& k, int width, int height, LaunchShape shape = {},
            const char* what = "kernel") {
  const auto wait = [&] {
    SVGF_CUDA_CHECK(cudaStreamSynchronize(nullptr),
                    std::string("kernel '") + what + "' execution");
  };
  if constexpr (!std::is_same_v<decltype(k(0, 0)), bool>) {
    launch(k, width, height, shape, nullptr, what);
    wait();
    return 0;
  } else {
    DeviceArray<unsigned long long> count(1);
    SVGF_CUDA_CHECK(cudaMemsetAsync(count.get(), 0, sizeof(unsigned long long), nullptr),
                    "cudaMemset of a counter");
    launch(k, width, height, shape, nullptr, what, count.get());
    wait();
    unsigned long long n = 0;
    count.download(&n, 1);
    return static_cast<int64_t>(n);
  }
}

// One block kernel on the default stream, waited for: for tests.
template <class K>
void run_blocks(const K& k, int blocks, const char* what = "block kernel") {
  launch_blocks(k, blocks, nullptr, what);
  SVGF_CUDA_CHECK(cudaStreamSynchronize(nullptr),
                  std::string("kernel '") + what + "' execution");
}

}  // namespace svgf::cuda

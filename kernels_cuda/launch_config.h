#pragma once
// Grid geometry and launch checking shared by the exact and the fast kernels. Host-compilable.
#include <stdexcept>
#include <string>

#include <cuda_runtime_api.h>

#include "kernels_cuda/cuda_check.h"
#include "kernels_cuda/launch_shape.h"

namespace svgf::cuda {

// One thread per pixel: a 2-D grid of block_x x block_y blocks covering width x height.
struct LaunchGeometry {
  dim3 grid;
  dim3 block;
};

inline LaunchGeometry launch_geometry(int width, int height, LaunchShape shape) {
  if (shape.block_x < 1 || shape.block_y < 1)
    throw std::invalid_argument("CUDA block shape " + std::to_string(shape.block_x) + "x" +
                                std::to_string(shape.block_y) + " is empty");
  LaunchGeometry g;
  g.block = dim3(static_cast<unsigned>(shape.block_x), static_cast<unsigned>(shape.block_y));
  g.grid = dim3(static_cast<unsigned>((width + shape.block_x - 1) / shape.block_x),
                static_cast<unsigned>((height + shape.block_y - 1) / shape.block_y));
  return g;
}

// Right after a launch: a refused launch (bad configuration, no kernel image for this GPU) is
// raised here as a CudaError naming the kernel. Faults while the kernel runs surface at the
// next synchronization.
inline void check_launch(const char* kernel, const LaunchGeometry& g) {
  const cudaError_t e = cudaGetLastError();
  if (e != cudaSuccess)
    throw CudaError(std::string("kernel '") + kernel + "' (grid " + std::to_string(g.grid.x) +
                        "x" + std::to_string(g.grid.y) + ", block " + std::to_string(g.block.x) +
                        "x" + std::to_string(g.block.y) + ")",
                    e);
}

}  // namespace svgf::cuda

#pragma once
// Threads per block of the CUDA launches; any shape gives the same bits. Host-compilable.
namespace svgf::cuda {

struct LaunchShape {
  int block_x = 16;
  int block_y = 8;
};

}  // namespace svgf::cuda

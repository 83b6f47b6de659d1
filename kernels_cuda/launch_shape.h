#pragma once
// Threads per block of the CUDA launches; any shape gives the same bits. Host-compilable.
namespace svgf::cuda {

// The default, 32x8: among 16x8, 32x8, 64x2 and 128x1 at 1080p on the H100 the fastest in
// exact mode and within 2.4% of the fastest in fast mode; 16x8 was 2-4% slower in every case
// (docs/cuda.md, "Launch shape").
struct LaunchShape {
  int block_x = 32;
  int block_y = 8;
};

}  // namespace svgf::cuda

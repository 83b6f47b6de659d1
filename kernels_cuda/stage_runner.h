#pragma once
// Any single stage on the GPU, with the same kernel struct the CPU runs through
// cpu::for_each_pixel: the views inside must point to device memory (see DeviceArray). Each
// call launches, synchronizes, and throws CudaError naming the kernel on failure. Host-compilable.
#include <cstdint>

#include "core/atrous.h"
#include "core/copy.h"
#include "core/demodulate.h"
#include "core/remodulate.h"
#include "core/reproject.h"
#include "core/tonemap.h"
#include "core/variance.h"

namespace svgf::cuda {

// Threads per block; any shape must give the same bits.
struct LaunchShape {
  int block_x = 16;
  int block_y = 8;
};

int64_t run(const DemodulateKernel& k, int width, int height, LaunchShape shape = {});  // count
void run(const ReprojectKernel& k, int width, int height, LaunchShape shape = {});
void run(const VarianceKernel& k, int width, int height, LaunchShape shape = {});
void run(const AtrousKernel& k, int width, int height, LaunchShape shape = {});
void run(const RemodulateKernel& k, int width, int height, LaunchShape shape = {});
void run(const TonemapKernel& k, int width, int height, LaunchShape shape = {});
void run(const CopyRgbKernel& k, int width, int height, LaunchShape shape = {});

}  // namespace svgf::cuda

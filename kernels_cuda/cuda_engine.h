#pragma once
// The CUDA engine: every stage is a launch on the denoiser's stream, bracketed by CUDA events
// for the per-stage times. Nothing waits until end_frame(), which synchronizes once, reads the
// times and the tallies, and raises any fault of the frame's kernels as a
// CudaError naming their stages. Host-compilable; run() and run_tallying() are templates
// defined in kernels_cuda/cuda_launch.cuh, so the kernels a method's pipeline runs are
// instantiated by the .cu file that instantiates the method (no list of kernels anywhere).
#include <cstdint>
#include <string>
#include <vector>

#include "core/stage_times.h"
#include "core/tallies.h"
#include "kernels_cuda/cuda_handles.h"
#include "kernels_cuda/device_array.h"
#include "kernels_cuda/launch_shape.h"

namespace svgf::cuda {

class CudaEngine {
 public:
  explicit CudaEngine(LaunchShape shape);

  template <class Kernel>
  void run(const char* stage, const Kernel& kernel, int width, int height);
  // A block kernel (core/block_reduce.h) over `blocks` blocks.
  template <class Kernel>
  void run_blocks(const char* stage, const Kernel& kernel, int blocks);
  // For kernels returning a bit mask: per-bit pixel counts, in tallies() after end_frame().
  template <class Kernel>
  void run_tallying(const char* stage, const Kernel& kernel, int width, int height);

  // Per-frame bookkeeping. begin_frame() zeroes the tallies; mark() records an event: the work
  // enqueued from here to the next mark is `stage`.
  void begin_frame();
  void mark(const char* stage);
  void end_frame();

  cudaStream_t stream() const { return stream_.get(); }
  LaunchShape shape() const { return shape_; }
  const StageTimes& times() const { return times_; }
  const Tallies& tallies() const { return tallies_; }

 private:
  LaunchShape shape_;
  Stream stream_;
  DeviceArray<unsigned long long> counter_;
  PinnedBuffer<unsigned long long> counter_host_;
  std::vector<Event> events_;  // grows to the most marks a frame has needed
  std::vector<const char*> marks_;
  StageTimes times_;
  Tallies tallies_;
};

}  // namespace svgf::cuda

#pragma once
// The CUDA engine: every stage is a launch on the frame's stream, bracketed by CUDA events for
// the per-stage times. A frame runs on the engine's own stream (the host path) or on the
// caller's (the device path, Denoiser::denoise_device). Nothing waits until the frame's end:
// end_frame() synchronizes once, reads the times and the tallies, and raises any fault of the
// frame's kernels as a CudaError naming their stages; end_frame_async() only records the end,
// and the times and tallies are read when first asked for. Host-compilable; run() and
// run_tallying() are templates defined in kernels_cuda/cuda_launch.cuh, so the kernels a
// method's pipeline runs are instantiated by the .cu file that instantiates the method (no list
// of kernels anywhere).
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
  // For kernels returning a bit mask: per-bit pixel counts, in tallies() after the frame.
  template <class Kernel>
  void run_tallying(const char* stage, const Kernel& kernel, int width, int height);

  // Per-frame bookkeeping. begin_frame() zeroes the tallies and makes `stream` the frame's (the
  // engine's own by default). Frames share the history, so a frame on another stream than the
  // last one first waits for the last one's end, on the GPU (cudaStreamWaitEvent): never the
  // host. A frame whose times were never read is forgotten. mark() records an event: the work
  // enqueued from here to the next mark is `stage`.
  void begin_frame();
  void begin_frame(cudaStream_t stream);
  void mark(const char* stage);
  void end_frame();
  void end_frame_async();
  // Whether the last frame ended without waiting and its times are not read yet.
  bool frame_pending() const { return pending_; }
  // Waits for the last frame's work (its end event, not the stream), raising its faults.
  void wait_frame() const;

  cudaStream_t stream() const { return stream_; }
  cudaStream_t own_stream() const { return own_stream_.get(); }
  LaunchShape shape() const { return shape_; }
  // Wait for a pending frame first.
  const StageTimes& times() const;
  const Tallies& tallies() const;

 private:
  void record_end();
  void read_results() const;

  LaunchShape shape_;
  Stream own_stream_;
  cudaStream_t stream_;      // the current frame's
  cudaStream_t last_stream_;  // the stream the last frame ended on
  bool ended_ = false;        // a frame has ended (frame_end_ is recorded)
  mutable bool pending_ = false;
  DeviceArray<unsigned long long> counter_;
  PinnedBuffer<unsigned long long> counter_host_;
  std::vector<Event> events_;  // grows to the most marks a frame has needed
  Event frame_end_;
  std::vector<const char*> marks_;
  mutable StageTimes times_;
  mutable Tallies tallies_;
};

}  // namespace svgf::cuda

#pragma once
// The CUDA device as the benchmark reports it: identity, and the two ceilings the floor
// analysis divides by (device-to-device copy bandwidth, FP32 instruction rate), measured.
// Plain C++ header; without CUDA in the build every function reports "no device".
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "core/denoiser.h"
#include "core/frame.h"

namespace svgf::bench {

struct DeviceInfo {
  bool present = false;
  std::string why_absent;
  std::string name;
  int driver_version = 0;  // e.g. 13000 for 13.0
  int runtime_version = 0;
  int compute_major = 0, compute_minor = 0;
  int sms = 0;
  int clock_khz = 0;  // peak SM clock
  int memory_clock_khz = 0;
  int memory_bus_bits = 0;
  int l2_bytes = 0;
  size_t memory_bytes = 0;
  // Measured (measure_ceilings): bytes read + bytes written per second.
  double memcpy_gbs = 0;       // cudaMemcpyAsync device to device, 1 GiB
  double copy_kernel_gbs = 0;  // a float4 grid-stride copy kernel, 1 GiB
  double fp32_ops_per_s = 0;   // FP32 instructions per second (an FMA counts one)
};

// Identity only (cheap).
DeviceInfo query_device();
// Fills the measured fields (a second or two of device time).
void measure_ceilings(DeviceInfo& info);
// Device memory in use on the current device (total - free), 0 without a device.
size_t device_used_bytes();

// The device path (Denoiser::denoise_device), as a renderer whose G-buffer is on the GPU uses
// it: the distinct frames copied once into device memory (planar), then `warmup` + `count`
// frames denoised where they lie, on a stream of the bench's, `before(m, k)` called before
// frame m (frame k of the set; the runner's resets). Per timed frame, host clock: `call_ms`,
// the denoise_device call (enqueueing only), and `done_ms`, from the call to the stream
// synchronized (the frame's work done). Empty without a device.
struct DevicePathTimes {
  std::vector<double> call_ms, done_ms;
};
DevicePathTimes time_device_path(Denoiser& denoiser, const std::vector<Frame>& frames, int warmup,
                                 int count, const std::function<void(int, int)>& before);

}  // namespace svgf::bench

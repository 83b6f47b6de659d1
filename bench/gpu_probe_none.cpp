// bench/gpu_probe.h for builds without CUDA: no device.
#include "bench/gpu_probe.h"

namespace svgf::bench {

DeviceInfo query_device() {
  DeviceInfo d;
  d.why_absent = "this build has no CUDA backend";
  return d;
}
void measure_ceilings(DeviceInfo&) {}
size_t device_used_bytes() { return 0; }
DevicePathTimes time_device_path(Denoiser&, const std::vector<Frame>&, int, int,
                                 const std::function<void(int, int)>&) {
  return {};
}

}  // namespace svgf::bench

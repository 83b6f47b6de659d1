#pragma once
// The host side of a frame's upload and download: copying the frame's planes into the pinned
// staging buffer (and the output out of it) on the host's cores. One thread moved a 1080p
// frame's planes (up to 21 of 8 MB) in about 28 ms, nine times the PCIe upload that follows
// (docs/benchmarks.md, "frame wall"). A copy moves bytes: the result is the same at any thread
// count.
#include <cstddef>
#include <memory>
#include <vector>

namespace svgf::cuda {

struct HostCopy {
  void* dst;
  const void* src;
  size_t bytes;
};

class HostStaging {
 public:
  // threads: as EngineConfig::threads (0: all cores).
  explicit HostStaging(int threads);
  ~HostStaging();
  HostStaging(const HostStaging&) = delete;
  HostStaging& operator=(const HostStaging&) = delete;

  void add(void* dst, const void* src, size_t bytes) { copies_.push_back({dst, src, bytes}); }
  // Runs every copy added since the last run, in 1 MiB pieces spread over the threads; returns
  // when all are done.
  void run();

 private:
  struct Arena;
  std::unique_ptr<Arena> arena_;
  std::vector<HostCopy> copies_;
};

}  // namespace svgf::cuda

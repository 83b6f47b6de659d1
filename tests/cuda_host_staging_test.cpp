// The CUDA backend's host staging copy (kernels_cuda/host_staging.h): every byte of every copy
// arrives, nothing outside the destinations is written, at any thread count. Runs on the CPU:
// no device is needed.
#include <cstdint>
#include <algorithm>
#include <vector>

#include <catch2/catch.hpp>

#include "kernels_cuda/host_staging.h"

TEST_CASE("cuda host staging: pieces of every size arrive whole, nothing else is written",
          "[cuda][staging]") {
  constexpr size_t MiB = size_t(1) << 20;
  // Sizes around the 1 MiB piece: empty, a byte, just under, just over, several pieces.
  const std::vector<size_t> sizes = {0, 1, MiB - 1, MiB, MiB + 1, 3 * MiB + MiB / 2, 4096};
  size_t total = 0;
  for (size_t s : sizes) total += s;
  std::vector<uint8_t> src(total);
  for (size_t i = 0; i < total; ++i) src[i] = static_cast<uint8_t>((i * 2654435761u) >> 13);
  constexpr size_t kGuard = 64;  // untouched bytes between destinations
  for (int threads : {1, 2, 5, 0}) {
    std::vector<uint8_t> dst(total + kGuard * (sizes.size() + 1), 0xAB);
    svgf::cuda::HostStaging staging(threads);
    size_t from = 0, to = kGuard;
    for (size_t s : sizes) {
      staging.add(dst.data() + to, src.data() + from, s);
      from += s;
      to += s + kGuard;
    }
    staging.run();
    from = 0;
    to = 0;
    size_t wrong = 0, guard_written = 0;
    for (size_t s : sizes) {
      for (size_t g = 0; g < kGuard; ++g) guard_written += dst[to + g] != 0xAB;
      to += kGuard;
      for (size_t i = 0; i < s; ++i) wrong += dst[to + i] != src[from + i];
      from += s;
      to += s;
    }
    for (size_t g = 0; g < kGuard; ++g) guard_written += dst[to + g] != 0xAB;
    INFO("threads " << threads);
    CHECK(wrong == 0);
    CHECK(guard_written == 0);
    // A second run with nothing added copies nothing.
    dst.assign(dst.size(), 0xAB);
    staging.run();
    CHECK(std::count(dst.begin(), dst.end(), uint8_t(0xAB)) == static_cast<long>(dst.size()));
  }
}

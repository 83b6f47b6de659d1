#pragma once
// The CPU side of "a kernel written once": run a pixel kernel over width x height with TBB.
// Rows are split among threads; every pixel is computed by the same code whatever thread runs
// it, so the result is identical for any thread count.
#include <cstdint>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "core/tallies.h"
#include "kernels_cpu/ieee_guard.h"

namespace svgf::cpu {

constexpr int kRowsPerTask = 2;

template <class Kernel>
void for_each_pixel(int width, int height, const Kernel& kernel) {
  tbb::parallel_for(tbb::blocked_range<int>(0, height, kRowsPerTask),
                    [&](const tbb::blocked_range<int>& rows) {
                      ScopedIeeeFloat ieee;
                      for (int y = rows.begin(); y != rows.end(); ++y)
                        for (int x = 0; x < width; ++x) kernel(x, y);
                    });
}

// For kernels returning bool: how many pixels returned true (an integer sum: order-free).
template <class Kernel>
int64_t count_pixels(int width, int height, const Kernel& kernel) {
  return tbb::parallel_reduce(
      tbb::blocked_range<int>(0, height, kRowsPerTask), int64_t{0},
      [&](const tbb::blocked_range<int>& rows, int64_t count) {
        ScopedIeeeFloat ieee;
        for (int y = rows.begin(); y != rows.end(); ++y)
          for (int x = 0; x < width; ++x) count += kernel(x, y) ? 1 : 0;
        return count;
      },
      [](int64_t a, int64_t b) { return a + b; });
}

// For kernels returning a bit mask (uint32_t): how many pixels set each bit.
template <class Kernel>
Tallies tally_pixels(int width, int height, const Kernel& kernel) {
  return tbb::parallel_reduce(
      tbb::blocked_range<int>(0, height, kRowsPerTask), Tallies{},
      [&](const tbb::blocked_range<int>& rows, Tallies t) {
        ScopedIeeeFloat ieee;
        for (int y = rows.begin(); y != rows.end(); ++y)
          for (int x = 0; x < width; ++x) {
            const uint32_t mask = kernel(x, y);
            if (mask != 0u) t.add_mask(mask);
          }
        return t;
      },
      [](Tallies a, const Tallies& b) { return a += b; });
}

}  // namespace svgf::cpu

#pragma once
// The CPU engine: runs a method's pixel kernels inside the denoiser's task arena (its thread
// count) and times each stage with a steady clock. Method-neutral: a kernel runs through
// cpu::PixelDriver<Kernel>, which is for_each_pixel unless a method's CPU driver specializes it
// (kernels_cpu/svgf_rows.h: the vectorized rows of SVGF's two wide stages, same bits;
// kernels_cpu/sanitize_rows.h: the backend's input scan).
#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "core/stage_times.h"
#include "core/tallies.h"
#include "kernels_cpu/cpu_block.h"
#include "kernels_cpu/parallel_for.h"

namespace svgf::cpu {

// How the CPU runs a kernel: one call per pixel, TBB over rows; tally() for a kernel returning
// a bit mask (run_tallying).
template <class Kernel, class = void>
struct PixelDriver {
  static void run(const Kernel& kernel, int width, int height) {
    for_each_pixel(width, height, kernel);
  }
  static Tallies tally(const Kernel& kernel, int width, int height) {
    return tally_pixels(width, height, kernel);
  }
};

class CpuEngine {
 public:
  explicit CpuEngine(int threads)
      : arena_(threads > 0 ? threads : tbb::task_arena::automatic) {}

  int threads() const { return arena_.max_concurrency(); }

  template <class Kernel>
  void run(const char* stage, const Kernel& kernel, int width, int height) {
    const auto t0 = std::chrono::steady_clock::now();
    arena_.execute([&] { PixelDriver<Kernel>::run(kernel, width, height); });
    times_.add(stage, elapsed_ms(t0));
  }

  // A block kernel (core/block_reduce.h) over `blocks` blocks.
  template <class Kernel>
  void run_blocks(const char* stage, const Kernel& kernel, int blocks) {
    const auto t0 = std::chrono::steady_clock::now();
    arena_.execute([&] { for_each_block(blocks, kernel); });
    times_.add(stage, elapsed_ms(t0));
  }

  // dst[k][i] = src[k][i] for i in [0, n) and every pair of planes, on the arena's threads and
  // untimed: the backend's copies between frames (CpuBackend::finish), which on one thread
  // took 1.2 ms of a 720p frame's wall on the Zen 5 VM (docs/benchmarks.md).
  template <class T>
  void copy_planes(std::initializer_list<std::pair<const T*, T*>> planes, size_t n) {
    arena_.execute([&] {
      tbb::parallel_for(tbb::blocked_range<size_t>(0, n, kCopyChunk),
                        [&](const tbb::blocked_range<size_t>& r) {
                          for (const auto& [src, dst] : planes)
                            std::copy(src + r.begin(), src + r.end(), dst + r.begin());
                        });
    });
  }

  // For kernels returning a bit mask: per-bit pixel counts, added to tallies().
  template <class Kernel>
  void run_tallying(const char* stage, const Kernel& kernel, int width, int height) {
    const auto t0 = std::chrono::steady_clock::now();
    Tallies t;
    arena_.execute([&] { t = PixelDriver<Kernel>::tally(kernel, width, height); });
    tallies_ += t;
    times_.add(stage, elapsed_ms(t0));
  }

  // Per-frame bookkeeping: cleared by begin_frame(). The CPU's tallies are current as soon as
  // run_tallying returns; CUDA's only after the frame.
  void begin_frame() { times_.clear(); tallies_ = Tallies{}; }
  // A CPU frame is done when denoise() returns (the CUDA engine's device frames may not be).
  bool frame_pending() const { return false; }
  const StageTimes& times() const { return times_; }
  const Tallies& tallies() const { return tallies_; }

 private:
  static double elapsed_ms(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
        .count();
  }
  static constexpr size_t kCopyChunk = size_t(1) << 16;  // values of each plane a task copies
  tbb::task_arena arena_;
  StageTimes times_;
  Tallies tallies_;
};

}  // namespace svgf::cpu

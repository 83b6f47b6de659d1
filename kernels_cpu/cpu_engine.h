#pragma once
// Engine for core/svgf_pipeline.h on the CPU: runs each stage's kernel inside the denoiser's
// task arena (its thread count) and times it with a steady clock.
#include <chrono>
#include <cstdint>

#include <tbb/task_arena.h>

#include "core/stage_times.h"
#include "kernels_cpu/filter_rows.h"
#include "kernels_cpu/parallel_for.h"

namespace svgf::cpu {

class CpuEngine {
 public:
  explicit CpuEngine(int threads)
      : arena_(threads > 0 ? threads : tbb::task_arena::automatic) {}

  int threads() const { return arena_.max_concurrency(); }

  template <class Kernel>
  void run(Stage stage, const Kernel& kernel, int width, int height) {
    timed(stage, [&] { for_each_pixel(width, height, kernel); });
  }

  // The wide-neighbourhood stages take their vectorized row drivers (same bits).
  void run(Stage stage, const AtrousKernel& kernel, int width, int height) {
    timed(stage, [&] { run_atrous_rows(kernel, width, height); });
  }
  void run(Stage stage, const VarianceKernel& kernel, int width, int height) {
    timed(stage, [&] { run_variance_rows(kernel, width, height); });
  }

  template <class Kernel>
  void run_counting(Stage stage, const Kernel& kernel, int width, int height) {
    const auto t0 = std::chrono::steady_clock::now();
    int64_t n = 0;
    arena_.execute([&] { n = count_pixels(width, height, kernel); });
    counted_ += n;
    times_[stage] += elapsed_ms(t0);
  }

  // Per-frame bookkeeping: cleared by begin_frame().
  void begin_frame() { times_ = StageTimes(); counted_ = 0; }
  const StageTimes& times() const { return times_; }
  int64_t counted() const { return counted_; }

 private:
  template <class Work>
  void timed(Stage stage, const Work& work) {
    const auto t0 = std::chrono::steady_clock::now();
    arena_.execute(work);
    times_[stage] += elapsed_ms(t0);
  }
  static double elapsed_ms(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
        .count();
  }
  tbb::task_arena arena_;
  StageTimes times_;
  int64_t counted_ = 0;
};

}  // namespace svgf::cpu

#pragma once
// One benchmark configuration run over a frame set: timing (per stage and per frame, with the
// bandwidth and floor analysis) or quality (per frame against the reference). Results are JSON
// objects; docs/benchmarks.md describes their fields.
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

#include "bench/baselines.h"
#include "bench/workload.h"
#include "pipeline/make_denoiser.h"

namespace svgf::bench {

struct RunConfig {
  std::string method = "svgf";  // svgf, a baseline name, or "noisy" (the input, quality only)
  Baseline baseline;            // when method is a baseline
  DenoiserConfig denoiser;      // when method is svgf (threads also apply to baselines)
  // "svgf cuda fast it4 tap1" (+ " t2" for CPU thread counts): unique within a suite.
  std::string label() const;
  // The configuration without the thread count: what quality and timing are joined on.
  std::string key() const;
  int resolved_threads() const;  // 0 resolved to the hardware thread count
};

RunConfig svgf_config(Backend backend, Mode mode, int iterations, int feedback_tap, int threads);

// The ceilings of the machine a run's stages are compared with.
struct Ceilings {
  double copy_gbs = 0;    // bytes read + written per second of a large copy
  double ops_per_s = 0;   // floating-point operations per second; 0: unknown
  std::string copy_what;  // how copy_gbs was measured
};

struct TimingOptions {
  int warmup = 10;
  int frames = 100;
  double budget_s = 0;  // > 0: stop timing after this many seconds, once min_frames are timed
  int min_frames = 10;
};

nlohmann::json config_json(const RunConfig& c);
// Times `c` on `frames` (played cyclically; history resets at camera cuts).
nlohmann::json time_run(const RunConfig& c, const FrameSet& frames, const TimingOptions& t,
                        const Ceilings& ceilings);
// Denoises a fixture sequence once, in order, and measures every frame against its reference.
nlohmann::json quality_run(const RunConfig& c, const FrameSet& fixture);

void print_timing(const nlohmann::json& entry, std::FILE* f);
void print_quality(const nlohmann::json& entry, std::FILE* f);

}  // namespace svgf::bench

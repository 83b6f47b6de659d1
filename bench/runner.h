#pragma once
// One benchmark configuration run over a frame set: timing (per stage by the method's own stage
// names and per frame, with the bandwidth, float-rate, per-tap and floor analysis where the cost
// model counts the stage, bench/stage_cost.h) or quality (per frame against the reference).
// Results are JSON objects; docs/benchmarks.md describes their fields.
#include <array>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

#include "bench/run_config.h"
#include "bench/workload.h"

namespace svgf::bench {

// The ceilings of the machine a run's stages are compared with.
struct Ceilings {
  double copy_gbs = 0;    // bytes read + written per second of a large copy
  double ops_per_s = 0;   // floating-point operations per second; 0: unknown
  std::string copy_what;  // how copy_gbs was measured
  // The CPU's exact a-trous on a frame in the caches, ns a tap (bench/atrous_probe.h); 0: not
  // measured (a GPU run, another method's, --no-ceilings). A run's JSON has it only for SVGF on
  // the CPU.
  double resident_atrous_ns_per_tap = 0;
  // Float operations per second in dependent chains of each length of kDependentChainLengths
  // (bench/host_probe.h); 0: not measured. Measured and in the JSON where the probe above is.
  std::array<double, 3> chain_ops_per_s{};
};

struct TimingOptions {
  int warmup = 10;
  int frames = 100;
  double budget_s = 0;  // > 0: stop timing after this many seconds, once min_frames are timed
  int min_frames = 10;
};

// Times `c` on `frames` (played cyclically; history resets at camera cuts).
nlohmann::json time_run(const RunConfig& c, const FrameSet& frames, const TimingOptions& t,
                        const Ceilings& ceilings);
// Denoises a fixture sequence once, in order, and measures every frame against its reference.
nlohmann::json quality_run(const RunConfig& c, const FrameSet& fixture);

void print_timing(const nlohmann::json& entry, std::FILE* f);
// Ceilings::chain_ops_per_s as JSON: {"8": ops/s, "32": ..., "64": ...}.
nlohmann::json chain_json(const std::array<double, 3>& chain_ops_per_s);
void print_quality(const nlohmann::json& entry, std::FILE* f);

}  // namespace svgf::bench

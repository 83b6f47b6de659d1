#pragma once
// svgf_gpu_tests' run options, the tally of what was compared and the fixture list: what the
// main (tests/gpu_test_main.cpp) shares with the tests. No device code, so the main is built by
// the host compiler.
#include <cstdint>
#include <string>
#include <vector>

namespace svgf::gpu_test {

struct Options {
  bool reduced = false;  // fewer sizes and frames (compute-sanitizer runs)
  int max_frames = 0;    // per fixture sequence; 0: all
  std::string fixtures_dir;
};
Options& options();

// What the run compared, printed by main at the end (docs/cuda.md quotes it).
struct Tally {
  int64_t stage_runs = 0;       // single-stage CPU vs GPU comparisons
  int64_t stage_values = 0;     // values compared bitwise in them
  int64_t frames = 0;           // pipeline frames compared bitwise (CPU vs CUDA exact)
  int64_t frame_values = 0;
  int64_t determinism_frames = 0;
  int64_t fast_frames = 0;      // fast-mode frames checked against the tolerance
  int64_t device_frames = 0;    // frames through denoise_device compared with denoise()
  double fast_worst_relmse = 0;
  std::string fast_worst_relmse_at;
  double fast_worst_psnr_delta = 0;
  std::string fast_worst_psnr_at;
  std::vector<std::string> sequences;
};
Tally& tally();

// Fixture folders (those holding manifest.json), sorted by name.
std::vector<std::string> fixture_dirs();

}  // namespace svgf::gpu_test

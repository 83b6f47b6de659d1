#pragma once
// Filters a user might pick instead of SVGF, through OpenCV, on the same linear HDR frames:
// spatial only (no history), on the CPU. docs/benchmarks.md gives their settings.
#include <string>
#include <vector>

#include "core/frame.h"
#include "core/image.h"

namespace svgf::bench {

struct Baseline {
  std::string name;           // gaussian, bilateral, joint-bilateral, nlmeans
  double p1 = 0;              // gaussian: sigma (px); bilateral/joint: diameter; nlmeans: h
  double p2 = 0;              // bilateral/joint: sigma color; nlmeans: h color
  double p3 = 0;              // bilateral/joint: sigma space (px); nlmeans: search window
  std::string label() const;  // e.g. "gaussian s2"
};

// Whether this build has the OpenCV baselines.
bool baselines_available();
// The settings the suites and the chart use, one or two per filter.
std::vector<Baseline> default_baselines();
// Parses a --method value: "gaussian", "bilateral", "joint-bilateral", "nlmeans" with the first
// default setting; throws std::invalid_argument for other names.
Baseline baseline_by_name(const std::string& name);
bool is_baseline(const std::string& method);

// Denoises one frame (color; joint-bilateral also reads albedo as its guide) into `out`.
// Bad samples (NaN, Inf, negative) become 0 first, the rule SVGF's demodulation applies.
void run_baseline(const Baseline& b, const Frame& in, Image& out);
// OpenCV's worker threads (cv::setNumThreads); 0: OpenCV's default.
void set_baseline_threads(int threads);

}  // namespace svgf::bench

#pragma once
// Filters a user might pick instead of the project's methods, through OpenCV, on the same linear
// HDR frames: spatial only (no history), on the CPU. Their names start with "cv-", which keeps
// them apart from the project's methods (the project's own Gaussian is "gaussian", as in `svgf
// denoise`). docs/benchmarks.md gives their settings.
#include <string>
#include <vector>

#include "core/frame.h"
#include "core/image.h"

namespace svgf::bench {

struct Baseline {
  std::string name;           // cv-gaussian, cv-bilateral, cv-joint-bilateral, cv-nlmeans
  double p1 = 0;              // gaussian: sigma (px); bilateral/joint: diameter; nlmeans: h
  double p2 = 0;              // bilateral/joint: sigma color; nlmeans: h color
  double p3 = 0;              // bilateral/joint: sigma space (px); nlmeans: search window
  std::string label() const;  // e.g. "cv-gaussian s2"
};

// Whether this build has the OpenCV baselines.
bool baselines_available();
// The settings the suites and the chart use, one or two per filter.
std::vector<Baseline> default_baselines();
// Parses a --method value: "cv-gaussian", "cv-bilateral", "cv-joint-bilateral", "cv-nlmeans"
// with the first default setting; throws std::invalid_argument for other names.
Baseline baseline_by_name(const std::string& name);
bool is_baseline(const std::string& method);  // a "cv-" name
std::string baseline_names();                 // "cv-gaussian, cv-bilateral, ..."

// Denoises one frame (color; joint-bilateral also reads albedo as its guide) into `out`.
// Bad samples (NaN, Inf, negative) become 0 first, the rule SVGF's demodulation applies.
void run_baseline(const Baseline& b, const Frame& in, Image& out);
// OpenCV's worker threads (cv::setNumThreads); 0: OpenCV's default.
void set_baseline_threads(int threads);

}  // namespace svgf::bench

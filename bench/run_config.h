#pragma once
// What one benchmark run measures: a project method through make_denoiser (any method, backend,
// mode and parameters), an OpenCV baseline, or the noisy input; its key and label, which the
// results model joins timings and quality on, and its JSON.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bench/baselines.h"
#include "pipeline/make_denoiser.h"

namespace svgf::bench {

struct RunConfig {
  // A project method (parse_method's names: svgf, gaussian, wavelet, jbf, jbf-atrous, bmfr), an
  // OpenCV baseline ("cv-" names) or "noisy" (the input, quality only).
  std::string method = "svgf";
  Baseline baseline;       // when method is a baseline
  DenoiserConfig denoiser;  // a project method's settings (threads also apply to baselines)
  bool project() const { return method != "noisy" && !is_baseline(method); }
  bool cuda() const { return project() && denoiser.backend == Backend::Cuda; }
  // "svgf cuda fast it4 tap1", "wavelet cpu exact it4 k5" (+ " t2" for CPU thread counts):
  // unique within a suite. Parameters away from their defaults are part of it.
  std::string label() const;
  // The configuration without the thread count: what quality and timing are joined on.
  std::string key() const;
  int resolved_threads() const;  // 0 resolved to the hardware thread count
};

// A --method value with that method's defaults; std::invalid_argument listing the known names.
RunConfig run_config(const std::string& method);
// That method's defaults on a backend, mode and thread count (0: all).
RunConfig project_config(const std::string& method, Backend backend, Mode mode, int threads);
RunConfig svgf_config(Backend backend, Mode mode, int iterations, int feedback_tap, int threads);
// SVGF's named configurations beside the defaults (methods/svgf/params.h: svgf_preset): the
// paper's, converge, converge with the anti-lag, and the defaults with TAA.
std::vector<RunConfig> svgf_preset_configs(Backend backend, Mode mode, int threads);
// The CIS 565 wavelet filter at its defaults but for the kernel size (3, 5, 7, 9).
RunConfig wavelet_config(Backend backend, Mode mode, int kernel_size, int threads);
// The JBF at its defaults: the full window (levels 0, method jbf) or the a-trous form with
// `levels` levels (method jbf-atrous).
RunConfig jbf_config(Backend backend, Mode mode, int levels, int threads);
// BMFR at its defaults but for the rank-deficiency strategy.
RunConfig bmfr_config(Backend backend, Mode mode, BmfrRankStrategy strategy, int threads);
// The project's Gaussian blur with this sigma and radius (0: ceil(3 sigma)).
RunConfig gaussian_config(Backend backend, Mode mode, float sigma, int radius, int threads);

RunConfig baseline_config(const Baseline& b, int threads);

nlohmann::json config_json(const RunConfig& c);

}  // namespace svgf::bench

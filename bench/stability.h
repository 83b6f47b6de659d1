#pragma once
// `svgf-bench stability`: issue 13's scenario suite (docs/stability.md is its output;
// docs/benchmarks.md, "Stability suite", says how it is run). Every method of the suite runs
// over each scenario; each scenario measures one way a denoiser fails (a moving shadow erased, a
// light change followed late, a static scene that does not converge, ...) against a threshold
// from issues 12 and 13.
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "bench/run_config.h"
#include "core/frame.h"

namespace svgf::bench {

// The sizes of the scenarios the suite renders itself (the rest read the committed fixtures).
struct RenderedSizes {
  int shadow_width = 192, shadow_height = 192, shadow_frames = 8, shadow_reference_spp = 64;
  int static_size = 64, static_frames = 64, static_reference_spp = 8;
};
RenderedSizes reduced_sizes();  // the defaults: what tests/svgf_*_test.cpp render
RenderedSizes full_sizes();     // --full

struct StabilityOptions {
  std::string command;        // for the page's header
  std::string fixtures_root;  // the committed fixtures
  std::string out_md;         // '' = no page
  std::string out_json;       // '' = no JSON
  std::string cache_dir;      // rendered sequences kept between runs ('' = none)
  Backend backend = Backend::Cpu;
  int threads = 0;            // 0: all cores
  bool full = false;
  RenderedSizes sizes = reduced_sizes();
  std::vector<std::string> methods;    // stability_method_names(); empty: all
  std::vector<std::string> scenarios;  // stability_scenario_names(); empty: all
  bool quiet = false;                  // no progress on stderr
};

// One method of the suite, by its name in the tables.
struct StabilityMethod {
  std::string name;  // "svgf", "svgf falcor", "gaussian", "cv-gaussian s2", ...
  RunConfig config;
};
// svgf (the defaults) and its presets falcor, paper, converge; gaussian; wavelet; jbf;
// jbf-atrous; bmfr; and the OpenCV baselines when this build has them.
std::vector<StabilityMethod> stability_methods(Backend backend, int threads);
std::vector<std::string> stability_method_names();
std::vector<std::string> stability_scenario_names();

enum class Outcome { Pass, Fail, NotMeasured };
const char* to_string(Outcome v);

struct StabilityRow {
  std::string method;
  std::string value;  // the measured value(s), as the table shows them
  Outcome verdict = Outcome::NotMeasured;
  nlohmann::json data;  // the numbers behind `value`
};

struct ScenarioResult {
  std::string name;       // "moving-shadow", ...
  std::string title;      // "Moving shadow"
  std::string input;      // what it runs on
  std::string measure;    // what the value is
  std::string threshold;  // the bar, and whose it is
  std::string bar;        // the bar in a few words, for the table
  std::string reading;    // why methods fail it (mechanisms, not numbers)
  std::string skipped;    // non-empty: not run, and why
  std::vector<StabilityRow> rows;
  // What shows a failure on the page: frame `shown_frame` of the input, its reference and the
  // output of each of the suite's own methods that failed (-1: the scenario shows no frame).
  int shown_frame = -1;
  Image shown_input, shown_reference;
  std::vector<std::pair<std::string, Image>> shown_failures;
};

// std::invalid_argument naming an unknown method or scenario, or an output whose folder does not
// exist (checked before a run of minutes).
void check_stability_options(const StabilityOptions& options);

// Runs the scenarios; progress on stderr unless quiet. Throws std::invalid_argument for an
// unknown method or scenario name and io errors naming a bad fixture.
std::vector<ScenarioResult> run_stability(const StabilityOptions& options);

// The page (markdown) and the JSON of a run.
std::string stability_page(const StabilityOptions& options,
                           const std::vector<ScenarioResult>& results);
nlohmann::json stability_json(const StabilityOptions& options,
                              const std::vector<ScenarioResult>& results);

// The command: runs, then writes the page and the JSON atomically. 0 when it ran (failed
// thresholds are findings, not errors).
int stability_command(const StabilityOptions& options);

}  // namespace svgf::bench

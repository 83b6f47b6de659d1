#pragma once
// The predefined benchmark suites behind docs/benchmarks.md: every size, mode, iteration count,
// thread count, method, baseline and fixture the charts and tables need, in one process.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench/host_probe.h"
#include "bench/runner.h"

namespace svgf::bench {

struct SuiteOptions {
  std::string name;     // cpu, gpu
  std::string out_dir;  // <out_dir>/<name>.json (sections rerun replace their old entries)
  std::string fixtures_root;
  std::string cache_dir;  // rendered frames; empty: none
  std::string scene = "cornell-moving";
  int distinct_frames = 8;
  std::vector<std::string> sections;  // empty: all of the suite's
  std::vector<std::string> sizes;     // empty: 256, 720p, 1080p, 4k
  std::string chart_size = "720p";
  std::string iterations_size;  // empty: 720p on the CPU, 1080p on the GPU
  TimingOptions timing;
  double baseline_budget_s = 120;
  std::string command;  // how the suite was invoked, for the report
};

// Sections: cpu: sizes, chart, coverage, baselines, wavelet, jbf, bmfr, quality; gpu: sizes,
// iterations, coverage, blocks, chart, wavelet, jbf, bmfr, quality. The wavelet section is the
// CIS 565 kernel-size study (3x3 to 9x9, 4 passes) with its 9x9 comparisons (a Gaussian, a dense
// edge-stopping filter); jbf times the JBF's full window and a-trous form at the chart size
// (the GPU also at the iterations size, with 1 to 4 levels). On the CPU both run under the
// baselines' time budget. bmfr times BMFR exact with both rank strategies (GPU: fast too) at the
// chart size and at full coverage (camera-pan; CPU: chart size, 2 threads and all, with SVGF's
// default on 2 threads beside it; GPU: the iterations size).
std::vector<std::string> suite_sections(const std::string& name);
int run_suite(const SuiteOptions& options);

// Every configuration whose quality the charts show (CPU exact: CUDA exact gives the same bits),
// the noisy input first: the cpu suite's quality section and `svgf-bench quality` run these.
std::vector<RunConfig> quality_configs(int threads);

std::string now_iso();  // UTC, ISO 8601
nlohmann::json host_json(const HostInfo& h);

}  // namespace svgf::bench

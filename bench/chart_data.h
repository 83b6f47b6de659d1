#pragma once
// `svgf-bench chart-data`: suite results (cpu.json, gpu.json) in, the tables bench/chart.sh
// draws and summary.md (every table of docs/benchmarks.md) out. Results model: results.h;
// chart points: chart_points.h; writers: chart_tables.h (*.dat), summary.h (Markdown).
#include <string>

namespace svgf::bench {

// The targets file the build knows (bench/targets.json in the source tree).
const char* default_targets_path();

// Reads every suite JSON in results_dir and the targets file; writes <out_dir>/*.dat and
// <out_dir>/summary.md. quality_file (non-empty): `svgf-bench quality`'s file, whose quality
// (the evaluation set) replaces the suites' (the fixtures').
int write_chart_data(const std::string& results_dir, const std::string& out_dir,
                     const std::string& targets_path, const std::string& quality_file = "");

}  // namespace svgf::bench

#pragma once
// Turns suite results (cpu.json, gpu.json) into the whitespace-separated tables the gnuplot
// scripts in bench/chart/ draw, and summary.md: every table of docs/benchmarks.md, generated.
#include <string>

namespace svgf::bench {

// Reads every suite JSON in results_dir; writes <out_dir>/*.dat and <out_dir>/summary.md.
int write_chart_data(const std::string& results_dir, const std::string& out_dir);

}  // namespace svgf::bench

#include "bench/chart_data.h"

#include <cstdio>
#include <filesystem>

#include "bench/chart_points.h"
#include "bench/chart_tables.h"
#include "bench/results.h"
#include "bench/summary.h"
#include "bench/targets.h"

namespace fs = std::filesystem;

namespace svgf::bench {

const char* default_targets_path() { return SVGF_BENCH_TARGETS; }

int write_chart_data(const std::string& results_dir, const std::string& out_dir,
                     const std::string& targets_path, const std::string& quality_file) {
  Results r = load_results(results_dir);
  if (!quality_file.empty()) load_eval_quality(r, quality_file);
  const std::vector<TargetResult> targets = evaluate_targets(load_targets(targets_path), r);
  fs::create_directories(out_dir);
  const std::vector<Point> pts = chart_points(r);
  write_points(out_dir, pts);
  write_error_curves(out_dir, r);
  write_scaling(out_dir, r);
  write_kernel_study(out_dir, r);
  write_text_file(fs::path(out_dir) / "summary.md", summary_markdown(r, pts, targets));
  std::printf("chart-data: %zu suite(s), %zu chart points -> %s\n", r.suites.size(), pts.size(),
              out_dir.c_str());
  return 0;
}

}  // namespace svgf::bench

#pragma once
// summary.md: every table of docs/benchmarks.md, generated from the suite results.
#include <string>
#include <vector>

#include "bench/chart_points.h"
#include "bench/results.h"
#include "bench/targets.h"

namespace svgf::bench {

std::string summary_markdown(const Results& r, const std::vector<Point>& pts,
                             const std::vector<TargetResult>& targets);

}  // namespace svgf::bench

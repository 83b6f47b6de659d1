#pragma once
#include <string>
#include <vector>

namespace svgf::app {

std::string import_usage();
// `svgf import IN_DIR OUT_DIR [options]`: per-buffer image files (and GAMES202 matrices) into a
// sequence (docs/import.md). Returns the exit status: 0, 1 for bad input (nothing written),
// 130 / 143 when SIGINT / SIGTERM stopped it; usage errors throw UsageError (exit 2).
int import_command(const std::vector<std::string>& args);

}  // namespace svgf::app

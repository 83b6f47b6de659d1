#pragma once
#include <string>
#include <vector>

#include "app/usage_error.h"

namespace svgf::app {

// Adds `svgf import` to `svgf`; `status` is set when it has run.
CLI::App* add_import_command(CLI::App& svgf, int& status);
// `svgf import IN_DIR OUT_DIR [options]`: per-buffer image files (and GAMES202 matrices) into a
// sequence (docs/import.md). Returns the exit status: 0, 1 for bad input (nothing written),
// 130 / 143 when SIGINT / SIGTERM stopped it; usage errors throw UsageError (exit 2).
int import_command(const std::vector<std::string>& args);

}  // namespace svgf::app

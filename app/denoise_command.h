#pragma once
#include <string>
#include <vector>

#include "app/usage_error.h"

namespace svgf::app {

// Adds `denoise IN_DIR OUT_DIR [options]` to `svgf`; `status` is set when it has run.
CLI::App* add_denoise_command(CLI::App& svgf, int& status);
// `svgf denoise args...`; returns the exit status, 0 after --help; UsageError for a bad argument.
int denoise_command(const std::vector<std::string>& args);

}  // namespace svgf::app

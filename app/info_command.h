#pragma once
#include <string>
#include <vector>

#include "app/usage_error.h"

namespace svgf::app {

// Adds `svgf info` to `svgf`; `status` is set when it has run.
CLI::App* add_info_command(CLI::App& svgf, int& status);
// `svgf info SEQ [--json FILE]`: what a sequence holds (size, frames, channels, value ranges,
// non-finite counts) and whether its files match the manifest. Returns 0 when every frame reads
// and matches its SHA-256, 1 otherwise (each problem named: file, frame, what).
int info_command(const std::vector<std::string>& args);

}  // namespace svgf::app

#pragma once
#include <string>
#include <vector>

namespace svgf::app {

std::string denoise_usage();
// `svgf denoise IN_DIR OUT_DIR [options]`; returns the exit status.
int denoise_command(const std::vector<std::string>& args);

}  // namespace svgf::app

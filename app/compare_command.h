#pragma once
#include <string>
#include <vector>

#include "app/usage_error.h"

namespace svgf::app {

// Adds `svgf compare` to `svgf`; `status` is set when it has run.
CLI::App* add_compare_command(CLI::App& svgf, int& status);
// `svgf compare A B [--json FILE] [--diff DIR]`: PSNR, SSIM, relMSE and FLIP of A's images
// against B's, per frame and mean. Returns 0, or throws naming the file that cannot be compared.
int compare_command(const std::vector<std::string>& args);

}  // namespace svgf::app

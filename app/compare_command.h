#pragma once
#include <string>
#include <vector>

namespace svgf::app {

std::string compare_usage();
// `svgf compare A B [--json FILE] [--diff DIR]`: PSNR, SSIM, relMSE and FLIP of A's images
// against B's, per frame and mean. Returns 0, or throws naming the file that cannot be compared.
int compare_command(const std::vector<std::string>& args);

}  // namespace svgf::app

// svgf: the command-line front end. Subcommands: denoise, info, compare, import (and help).
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "app/denoise_command.h"
#include "app/info_command.h"
#include "app/compare_command.h"
#include "app/import_command.h"
#include "app/options.h"
#include "io/printable.h"

namespace {

const char* const kUsage =
    "usage: svgf <command> [options]\n"
    "\n"
    "commands:\n"
    "  denoise IN_DIR OUT_DIR   denoise a frame sequence (svgf denoise --help)\n"
    "  info SEQ                 what a sequence holds, checked against its manifest\n"
    "  compare A B              PSNR, SSIM, relMSE and FLIP of A's frames against B's\n"
    "  import IN_DIR OUT_DIR    per-buffer files (EXR, .hdr, PFM; GAMES202) into a sequence\n"
    "  help                     this text\n"
    "\n"
    "Fixtures are made and checked by svgf-fixtures.\n";

}  // namespace

int main(int argc, char** argv) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty() || args[0] == "help" || args[0] == "--help" || args[0] == "-h") {
    std::fputs(kUsage, args.empty() ? stderr : stdout);
    return args.empty() ? 2 : 0;
  }
  const std::vector<std::string> rest(args.begin() + 1, args.end());
  try {
    if (args[0] == "denoise") return svgf::app::denoise_command(rest);
    if (args[0] == "info") return svgf::app::info_command(rest);
    if (args[0] == "compare") return svgf::app::compare_command(rest);
    if (args[0] == "import") return svgf::app::import_command(rest);
    throw svgf::app::UsageError("unknown command '" + args[0] + "'");
  } catch (const svgf::app::UsageError& e) {
    std::fprintf(stderr, "svgf: %s\n%s", svgf::io::printable(e.what()).c_str(),
                 args[0] == "denoise" ? svgf::app::denoise_usage().c_str()
                 : args[0] == "info"    ? svgf::app::info_usage().c_str()
                 : args[0] == "compare" ? svgf::app::compare_usage().c_str()
                 : args[0] == "import"  ? svgf::app::import_usage().c_str()
                                        : kUsage);
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "svgf: error: %s\n", svgf::io::printable(e.what()).c_str());
    return 1;
  }
}

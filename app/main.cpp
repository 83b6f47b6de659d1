// svgf: the command-line front end. Subcommands: denoise, info, compare, import.
#include <string>
#include <vector>

#include "app/compare_command.h"
#include "app/denoise_command.h"
#include "app/import_command.h"
#include "app/info_command.h"
#include "cli/command_line.h"

int main(int argc, char** argv) {
  CLI::App app("svgf: denoise path-traced frame sequences, and inspect, compare and import them.\n"
               "Fixtures are made and checked by svgf-fixtures.",
               "svgf");
  svgf::cli::style(app);
  app.require_subcommand(1);
  int status = 0;
  svgf::app::add_denoise_command(app, status);
  svgf::app::add_info_command(app, status);
  svgf::app::add_compare_command(app, status);
  svgf::app::add_import_command(app, status);
  return svgf::cli::run_main(app, argc, argv, [&] { return status; });
}

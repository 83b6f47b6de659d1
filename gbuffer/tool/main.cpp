// svgf-fixtures: renders, verifies and lists the Embree fixture sequences (docs/gbuffer.md).
#include "cli/command_line.h"
#include "tool/commands.h"

int main(int argc, char** argv) {
  using namespace svgf::gbuffer::tool;
  CLI::App app("svgf-fixtures: renders, verifies and lists the Embree fixture sequences "
               "and renders the evaluation set (docs/gbuffer.md).",
               "svgf-fixtures");
  svgf::cli::style(app);
  app.require_subcommand(1);
  int status = 0;
  add_generate(app, status);
  add_verify(app, status);
  add_list(app, status);
  add_eval(app, status);
  add_reference_noise(app, status);
  install_interrupt_handler();
  return svgf::cli::run_main(app, argc, argv, [&] { return status; });
}

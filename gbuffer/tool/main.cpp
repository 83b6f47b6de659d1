// svgf-fixtures: renders, verifies and lists the Embree fixture sequences (docs/gbuffer.md).
#include <csignal>
#include <cstdio>
#include <exception>
#include <string>

#include "io/printable.h"
#include "tool/commands.h"

namespace {

void usage(std::FILE* out) {
  std::fprintf(out,
      "usage: svgf-fixtures generate [--scene NAME ... | --all] [--size WxH] [--frames N]\n"
      "                              [--spp N] [--reference-spp N] [--seed S] [--out DIR]\n"
      "                              [--split] [--threads N]\n"
      "       svgf-fixtures verify [DIR ...] [--frames K] [--skip-reference]\n"
      "                            [--tolerance T] [--threads N]\n"
      "       svgf-fixtures list\n"
      "generate writes DIR/<scene>/ (DIR defaults to %s); scene defaults (list) reproduce the\n"
      "committed fixtures; --split adds the direct and indirect channels. verify re-renders\n"
      "sequence folders (or folders of them; default %s) and compares them with the files.\n",
      svgf::gbuffer::tool::default_fixture_dir().c_str(),
      svgf::gbuffer::tool::default_fixture_dir().c_str());
}

}  // namespace

int main(int argc, char** argv) {
  using namespace svgf::gbuffer::tool;
  if (argc < 2) {
    usage(stderr);
    return 2;
  }
  const std::string cmd = argv[1];
  const Args args(argv + 2, argv + argc);
  try {
    install_interrupt_handler();
    if (cmd == "generate") return run_generate(args);
    if (cmd == "verify") return run_verify(args);
    if (cmd == "list") return run_list(args);
    if (cmd == "-h" || cmd == "--help" || cmd == "help") {
      usage(stdout);
      return 0;
    }
    throw UsageError("unknown command '" + cmd + "'");
  } catch (const UsageError& e) {
    std::fprintf(stderr, "svgf-fixtures: %s (svgf-fixtures --help shows the usage)\n",
                 svgf::io::printable(e.what()).c_str());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "svgf-fixtures: error: %s\n", svgf::io::printable(e.what()).c_str());
    return 1;
  }
}

// svgf-fixtures list: the built-in scenes and their defaults.
#include <cstdio>

#include "gbuffer/eval_set.h"
#include "gbuffer/scenes.h"
#include "cli/command_line.h"
#include "tool/commands.h"

namespace svgf::gbuffer::tool {

namespace {

int run_list() {
  std::printf("%-15s %-9s %6s %4s %7s %5s %4s  %s\n", "scene", "size", "frames", "spp",
              "ref-spp", "cuts", "grad", "what it tests");
  for (const SceneDesc& s : scene_library()) {
    std::string cuts;
    for (int c : s.camera_cuts) cuts += (cuts.empty() ? "" : ",") + std::to_string(c);
    const std::string size = std::to_string(s.width) + "x" + std::to_string(s.height);
    std::printf("%-15s %-9s %6d %4d %7d %5s %4s  %s\n", s.name.c_str(), size.c_str(), s.frames,
                s.spp, s.reference_spp, cuts.empty() ? "-" : cuts.c_str(),
                s.gradients ? "yes" : "-", s.summary.c_str());
  }
  std::printf("default output folder: %s/<scene>\n", default_fixture_dir().c_str());
  std::printf("evaluation set (svgf-fixtures eval): %s/<scene>\n", default_eval_dir().c_str());
  return 0;
}

}  // namespace

void add_list(CLI::App& tool, int& status) {
  tool.add_subcommand("list", "the built-in scenes and their defaults")->callback([&status] {
    status = run_list();
  });
}

}  // namespace svgf::gbuffer::tool

// svgf-fixtures generate: renders scenes into sequence folders, each written atomically.
#include <tbb/global_control.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>
#include <optional>

#include "gbuffer/fixture_format.h"
#include "gbuffer/renderer.h"
#include "gbuffer/scenes.h"
#include "io/sequence.h"
#include "cli/command_line.h"
#include "tool/commands.h"
#include "tool/progress.h"

namespace fs = std::filesystem;

namespace svgf::gbuffer::tool {

namespace {

struct Job {
  const SceneDesc* scene;
  RenderSettings settings;
  int frames;
};

uint64_t folder_bytes(const fs::path& dir) {
  uint64_t total = 0;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_regular_file()) total += e.file_size();
  return total;
}

void generate_one(const Renderer& renderer, const Job& job, const fs::path& out) {
  const SceneDesc& scene = *job.scene;
  io::Manifest m;
  m.scene = scene.name;
  m.width = job.settings.width;
  m.height = job.settings.height;
  m.spp = job.settings.spp;
  m.reference_spp = job.settings.reference_spp;
  m.seed = job.settings.seed;
  m.generator = generator_tag();
  for (int c : scene.camera_cuts)
    if (c > 0 && c < job.frames) m.camera_cuts.push_back(c);

  const fs::path dir = out / scene.name;
  // Opened before rendering, so an unwritable folder fails at once; not committed on failure.
  io::SequenceWriter writer(dir.string(), fixture_storage());
  RenderCounters counters;
  double render_s = 0.0, total_s = 0.0;
  {
    Progress progress(scene.name, job.frames, job.settings.height, counters);
    for (int k = 0; k < job.frames; ++k) {
      const double t0 = progress.seconds();
      const Frame f = renderer.render(scene, k, job.settings, &counters);
      render_s += progress.seconds() - t0;
      writer.add(f);
    }
    writer.commit(m);
    total_s = progress.seconds();
  }
  const double rays = static_cast<double>(counters.rays.load());
  std::printf("%s: %d frames %dx%d, spp %d, reference spp %d, seed %llu: %.3g rays, "
              "render %.2f s (%s), total with EXR writing %.2f s -> %s (%.2f MB)\n",
              scene.name.c_str(), job.frames, m.width, m.height, m.spp, m.reference_spp,
              static_cast<unsigned long long>(m.seed), rays, render_s,
              format_rate(render_s > 0 ? rays / render_s : 0).c_str(), total_s,
              dir.string().c_str(), static_cast<double>(folder_bytes(dir)) / 1e6);
  std::fflush(stdout);
}

struct GenerateArgs {
  std::vector<std::string> names;
  bool all = false, split = false, gradients = false, no_gradients = false;
  std::string size;
  std::optional<int> frames, spp, reference_spp;
  uint64_t seed = 1;
  int threads = 0;
  std::string out = default_fixture_dir();
};

int run_generate(const GenerateArgs& a) {
  const std::vector<std::string>& names = a.names;
  const bool all = a.all;
  std::optional<int> width, height;
  if (!a.size.empty()) {
    int w = 0, h = 0;
    parse_size(a.size, w, h);
    width = w;
    height = h;
  }
  const std::optional<int>& frames = a.frames;
  const std::optional<int>& spp = a.spp;
  const std::optional<int>& reference_spp = a.reference_spp;
  const uint64_t seed = a.seed;
  const bool split = a.split;
  const int threads = a.threads;
  const std::string& out = a.out;
  if (all == !names.empty()) throw UsageError("generate: give either --scene NAME or --all");

  std::vector<Job> jobs;
  try {
    std::vector<const SceneDesc*> scenes;
    if (all)
      for (const SceneDesc& s : scene_library()) scenes.push_back(&s);
    for (const std::string& n : names) scenes.push_back(&find_scene(n));
    for (const SceneDesc* s : scenes) {
      Job j{s, RenderSettings{}, frames.value_or(s->frames)};
      j.settings.width = width.value_or(s->width);
      j.settings.height = height.value_or(s->height);
      j.settings.spp = spp.value_or(s->spp);
      j.settings.reference_spp = reference_spp.value_or(s->reference_spp);
      j.settings.seed = seed;
      j.settings.split = split;
      j.settings.gradients = a.gradients || (s->gradients && !a.no_gradients);
      validate(j.settings);
      jobs.push_back(j);
    }
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("generate: ") + e.what());
  }

  std::error_code ec;
  fs::create_directories(out, ec);
  if (ec || !fs::is_directory(out))
    throw std::runtime_error("cannot create output folder '" + out + "': " +
                             (ec ? ec.message() : "not a directory"));
  std::unique_ptr<tbb::global_control> limit;
  if (threads > 0)
    limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                  static_cast<size_t>(threads));
  const Renderer renderer;
  for (const Job& j : jobs) generate_one(renderer, j, out);
  return 0;
}

}  // namespace

void add_generate(CLI::App& tool, int& status) {
  auto a = std::make_shared<GenerateArgs>();
  CLI::App* sub = tool.add_subcommand("generate", "render scenes into sequence folders");
  sub->footer("Writes DIR/<scene>/ atomically; the scene defaults (list) reproduce the committed\n"
              "fixtures; --split adds the direct and indirect channels, --gradients the A-SVGF\n"
              "gradient samples (docs/frame-format.md).");
  sub->add_option("--scene", a->names, "a scene to render (repeatable; list names them)")
      ->type_name("NAME");
  sub->add_flag("--all", a->all, "every scene");
  sub->add_option("--size", a->size, "image size (default: the scene's)")->type_name("WxH");
  sub->add_option("--frames", a->frames, "frames (default: the scene's)")
      ->type_name("N")->check(CLI::Range(1, 100000));
  sub->add_option("--spp", a->spp, "samples per pixel (default: the scene's)")
      ->type_name("N")->check(CLI::Range(1, kMaxSpp));
  sub->add_option("--reference-spp", a->reference_spp,
                  "samples per pixel of the reference, 0 = none (default: the scene's)")
      ->type_name("N")->check(CLI::Range(0, kMaxSpp));
  sub->add_option("--seed", a->seed, "random seed (default 1)")
      ->type_name("S")
      ->check(CLI::Validator(
          [](std::string& s) {
            return !s.empty() && s[0] != '-' ? "" : "must be an integer >= 0, got '" + s + "'";
          },
          ""));
  sub->add_option("--out", a->out, "output folder (default " + default_fixture_dir() + ")")
      ->type_name("DIR");
  sub->add_flag("--split", a->split, "also the direct and indirect channels");
  CLI::Option* gradients = sub->add_flag(
      "--gradients", a->gradients,
      "also A-SVGF gradient samples (default: the scene's, list shows it)");
  sub->add_flag("--no-gradients", a->no_gradients, "no gradient samples, whatever the scene's default")
      ->excludes(gradients);
  sub->add_option("--threads", a->threads, "render threads (default: all cores)")
      ->type_name("N")->check(CLI::Range(1, 1024));
  sub->callback([a, &status] { status = run_generate(*a); });
}

}  // namespace svgf::gbuffer::tool

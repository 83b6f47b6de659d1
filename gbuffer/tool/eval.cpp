// svgf-fixtures eval: renders the evaluation set into its cache, resuming frame by frame.
#include <tbb/global_control.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "gbuffer/eval_record.h"
#include "gbuffer/eval_set.h"
#include "gbuffer/renderer.h"
#include "gbuffer/scenes.h"
#include "cli/command_line.h"
#include "tool/commands.h"
#include "tool/progress.h"

namespace fs = std::filesystem;

namespace svgf::gbuffer::tool {

namespace {

// ", reference noise 40.84 dB (0.0% of it at the clamp)" from the folder's eval.json
// (reference_noise.h), or "".
std::string reference_noise_phrase(const std::string& dir) {
  const std::optional<EvalRecord> r = read_eval_record(dir);
  const SequenceNoise noise = r ? sequence_reference_noise(*r) : SequenceNoise{0, 0};
  if (!(noise.mse > 0)) return "";
  char buf[96];
  std::snprintf(buf, sizeof buf, ", reference noise %.2f dB (%.1f%% of it at the clamp)",
                -10.0 * std::log10(noise.mse), 100.0 * noise.clamped_share);
  return buf;
}

struct EvalArgs {
  std::vector<std::string> names;
  std::string out = default_eval_dir();
  int threads = 0;
  // Overrides of the set's parameters, for measurements and tests only.
  std::string size;
  std::optional<int> frames, spp, reference_spp;
  std::optional<uint64_t> seed;
};

EvalParams params_of(const EvalArgs& a) {
  EvalParams p;
  if (!a.size.empty()) parse_size(a.size, p.width, p.height);
  p.frames = a.frames.value_or(p.frames);
  p.spp = a.spp.value_or(p.spp);
  p.reference_spp = a.reference_spp.value_or(p.reference_spp);
  p.seed = a.seed.value_or(p.seed);
  return p;
}

int run_eval(const EvalArgs& a) {
  const EvalParams params = params_of(a);
  std::vector<std::string> names = a.names.empty() ? eval_scene_names() : a.names;
  std::vector<EvalSequence> seqs;
  try {
    for (const std::string& n : names) seqs.push_back(eval_sequence(a.out, n, params));
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("eval: ") + e.what());
  }
  std::error_code ec;
  fs::create_directories(a.out, ec);
  if (ec || !fs::is_directory(a.out))
    throw std::runtime_error("cannot create the cache folder '" + a.out + "': " +
                             (ec ? ec.message() : "not a directory"));

  std::vector<EvalPlan> plans;
  int to_render = 0, kept = 0;
  for (const EvalSequence& s : seqs) {
    plans.push_back(plan_eval_sequence(s, params));
    for (const std::string& note : plans.back().notes) std::fprintf(stderr, "%s\n", note.c_str());
    to_render += static_cast<int>(plans.back().to_render.size());
    kept += plans.back().kept;
  }
  std::printf("eval: %zu scene%s x %d frames of %dx%d, %d spp, %d-spp references, seed %llu%s "
              "-> %s: %d frames cached, %d to render\n",
              seqs.size(), seqs.size() == 1 ? "" : "s", params.frames, params.width,
              params.height, params.spp, params.reference_spp,
              static_cast<unsigned long long>(params.seed), params.split ? ", split" : "",
              a.out.c_str(), kept, to_render);
  std::fflush(stdout);
  if (interrupted()) return 130;

  std::unique_ptr<tbb::global_control> limit;
  if (a.threads > 0)
    limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                  static_cast<size_t>(a.threads));
  const Renderer renderer;
  RenderCounters counters;
  int rendered = 0;
  double seconds = 0.0;
  bool stopped = false;
  {
    Progress progress("eval", to_render, params.height, counters);
    try {
      for (size_t i = 0; i < seqs.size(); ++i)
        render_eval_sequence(renderer, seqs[i], params, plans[i], &counters,
                             [&rendered](int) { ++rendered; });
    } catch (const std::exception&) {
      if (!interrupted()) throw;
      stopped = true;
    }
    seconds = progress.seconds();
  }
  if (stopped) {
    std::fprintf(stderr,
                 "eval: interrupted after %d of %d frames; the frames written are kept: run the "
                 "same command again to render the rest\n",
                 rendered, to_render);
    return 130;
  }
  const double rays = static_cast<double>(counters.rays.load());
  for (size_t i = 0; i < seqs.size(); ++i)
    std::printf("%s: %d frames (%zu rendered, %d cached)%s -> %s\n", seqs[i].scene.name.c_str(),
                params.frames, plans[i].to_render.size(), plans[i].kept,
                reference_noise_phrase(seqs[i].dir).c_str(), seqs[i].dir.c_str());
  std::printf("eval: %d frames rendered in %.1f s (%.2f s per frame, %s)\n", rendered, seconds,
              rendered ? seconds / rendered : 0.0,
              format_rate(seconds > 0 ? rays / seconds : 0).c_str());
  return 0;
}

}  // namespace

void add_eval(CLI::App& tool, int& status) {
  auto a = std::make_shared<EvalArgs>();
  const EvalParams set;
  CLI::App* sub = tool.add_subcommand(
      "eval", "render the evaluation set (every scene, realistic size) into its cache");
  sub->footer(
      "The evaluation set: every scene at " + std::to_string(set.width) + "x" +
      std::to_string(set.height) + ", " + std::to_string(set.frames) + " frames (the scene's "
      "story spread over them), " + std::to_string(set.spp) + " spp, " +
      std::to_string(set.reference_spp) + "-spp references, direct and indirect, gradient "
      "samples where the committed fixture has them. Each scene goes to DIR/<scene>/ (a "
      "sequence once complete); frames are checked by SHA-256 and only missing or bad ones are "
      "rendered, so an interrupted run resumes; other parameters than the cache's render the "
      "sequence again. Never committed (docs/gbuffer.md, \"Evaluation set\").");
  sub->add_option("--scene", a->names, "a scene (repeatable; default: all, list names them)")
      ->type_name("NAME");
  sub->add_option("--out", a->out, "cache folder (default " + default_eval_dir() + ")")
      ->type_name("DIR");
  sub->add_option("--threads", a->threads, "render threads (default: all cores)")
      ->type_name("N")->check(CLI::Range(1, 1024));
  const std::string overrides = "overrides of the set, for measurements and tests";
  sub->add_option("--size", a->size, "image size")->type_name("WxH")->group(overrides);
  sub->add_option("--frames", a->frames, "frames")
      ->type_name("N")->check(CLI::Range(1, 100000))->group(overrides);
  sub->add_option("--spp", a->spp, "samples per pixel")
      ->type_name("N")->check(CLI::Range(1, kMaxSpp))->group(overrides);
  sub->add_option("--reference-spp", a->reference_spp, "reference samples per pixel")
      ->type_name("N")->check(CLI::Range(1, kMaxSpp))->group(overrides);
  sub->add_option("--seed", a->seed, "random seed")->type_name("S")->group(overrides);
  sub->callback([a, &status] { status = run_eval(*a); });
}

}  // namespace svgf::gbuffer::tool

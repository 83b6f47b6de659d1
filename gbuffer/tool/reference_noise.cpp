// svgf-fixtures reference-noise: how noisy a reference of the evaluation set is. Renders one
// frame's reference with two seeds and prints the PSNR between them (metrics::psnr, the PSNR
// every report uses); their noise is independent, so one reference against the true image is
// 10 log10(2) = 3.01 dB better. Beside it, the first reference's estimate from its own two
// halves (reference_noise.h; what eval.json records per frame), with its standard
// error in dB: the two should agree.
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "gbuffer/eval_set.h"
#include "gbuffer/renderer.h"
#include "io/png.h"
#include "metrics/image_metrics.h"
#include "cli/command_line.h"
#include "tool/commands.h"

namespace svgf::gbuffer::tool {

namespace {

struct NoiseArgs {
  std::vector<std::string> names;
  int frame = 0;
  int threads = 0;
  std::string size;
  std::optional<int> reference_spp;
  std::string diff_dir;
};

// Where the two references differ: |A - B| after the clamp to [0, 1] PSNR applies, mean over
// RGB, x4 (white: 0.25 or more), as a gray PNG.
void write_difference_png(const std::string& path, const Image& a, const Image& b) {
  std::vector<uint8_t> gray(a.pixel_count() * 3);
  for (size_t i = 0; i < a.pixel_count(); ++i) {
    float sum = 0.f;
    for (int c = 0; c < 3; ++c)
      sum += std::fabs(std::clamp(a.plane(c)[i], 0.f, 1.f) - std::clamp(b.plane(c)[i], 0.f, 1.f));
    const float v = std::min(1.f, 4.f * sum / 3.f);
    gray[3 * i] = gray[3 * i + 1] = gray[3 * i + 2] = static_cast<uint8_t>(std::lround(v * 255.f));
  }
  io::write_png_rgb8(path, gray.data(), a.width(), a.height());
}

int run_reference_noise(const NoiseArgs& a) {
  EvalParams params;
  if (!a.size.empty()) parse_size(a.size, params.width, params.height);
  params.reference_spp = a.reference_spp.value_or(params.reference_spp);
  params.split = false;
  if (a.frame >= params.frames)
    throw UsageError("reference-noise: --frame " + std::to_string(a.frame) + " is past the set's " +
                     std::to_string(params.frames) + " frames");
  const std::vector<std::string> names = a.names.empty() ? eval_scene_names() : a.names;
  std::vector<EvalSequence> seqs;
  try {
    for (const std::string& n : names) seqs.push_back(eval_sequence("", n, params));
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("reference-noise: ") + e.what());
  }
  std::unique_ptr<tbb::global_control> limit;
  if (a.threads > 0)
    limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                  static_cast<size_t>(a.threads));
  const Renderer renderer;
  std::printf("%-15s %5s %9s %7s %14s %16s %18s %7s\n", "scene", "frame", "size", "ref-spp",
              "PSNR A vs B dB", "one ref noise dB", "A's halves dB (se)", "clamped");
  for (EvalSequence& s : seqs) {
    s.settings.gradients = false;
    RenderSettings other = s.settings;
    other.seed = s.settings.seed + 1;
    RenderCounters counters;  // cancel on Ctrl-C
    ReferenceNoise halves;  // A's own estimate from its two halves (reference_noise.h)
    const Frame fa = renderer.render(s.scene, a.frame, s.settings, &counters, &halves);
    if (interrupted()) return 130;
    const Frame fb = renderer.render(s.scene, a.frame, other, &counters);
    const double between = metrics::psnr(fa.reference, fb.reference);
    const double halves_db = -10.0 * std::log10(halves.mse);
    const double se_db = 10.0 * std::log10((halves.mse + halves.standard_error) / halves.mse);
    std::printf("%-15s %5d %4dx%-4d %7d %14.2f %16.2f %11.2f (%.2f) %7.3f\n", s.scene.name.c_str(),
                a.frame, params.width, params.height, params.reference_spp, between,
                between + 10.0 * std::log10(2.0), halves_db, se_db, halves.clamped_share);
    std::fflush(stdout);
    if (!a.diff_dir.empty()) {
      std::filesystem::create_directories(a.diff_dir);
      write_difference_png(
          (std::filesystem::path(a.diff_dir) / (s.scene.name + "_reference_noise.png")).string(),
          fa.reference, fb.reference);
    }
  }
  return 0;
}

}  // namespace

void add_reference_noise(CLI::App& tool, int& status) {
  auto a = std::make_shared<NoiseArgs>();
  CLI::App* sub = tool.add_subcommand(
      "reference-noise", "PSNR between two references of one frame rendered with two seeds");
  sub->footer(
      "Renders one frame of each scene at the evaluation set's size and reference spp with seeds\n"
      "S and S+1 and prints the PSNR between the two references (peak 1, clamped, as svgf\n"
      "compare); one reference's own noise PSNR is that + 3.01 dB (independent noise).");
  sub->add_option("--scene", a->names, "a scene (repeatable; default: all)")->type_name("NAME");
  sub->add_option("--frame", a->frame, "frame number (default 0)")
      ->type_name("K")->check(CLI::Range(0, 100000));
  sub->add_option("--size", a->size, "image size (default: the set's)")->type_name("WxH");
  sub->add_option("--reference-spp", a->reference_spp, "reference samples (default: the set's)")
      ->type_name("N")->check(CLI::Range(1, kMaxSpp));
  sub->add_option("--diff", a->diff_dir,
                  "also write DIR/<scene>_reference_noise.png: |A - B| per pixel, x4, gray")
      ->type_name("DIR");
  sub->add_option("--threads", a->threads, "render threads (default: all cores)")
      ->type_name("N")->check(CLI::Range(1, 1024));
  sub->callback([a, &status] { status = run_reference_noise(*a); });
}

}  // namespace svgf::gbuffer::tool

#include "bench/stability_inputs.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>

#include <tbb/task_arena.h>

#include "bench/baselines.h"
#include "io/exr_frame.h"
#include "io/sequence.h"

#if defined(SVGF_BENCH_HAVE_GBUFFER)
#include "gbuffer/fixture_format.h"
#include "gbuffer/renderer.h"
#include "gbuffer/scenes.h"
#endif

namespace fs = std::filesystem;

namespace svgf::bench {

bool StabilitySequence::is_cut(int k) const {
  return std::find(cuts.begin(), cuts.end(), k) != cuts.end();
}

std::vector<Image> StabilitySequence::references() const {
  std::vector<Image> r;
  for (const Frame& f : frames) r.push_back(f.reference);
  return r;
}

std::vector<std::vector<uint32_t>> StabilitySequence::mesh_ids() const {
  std::vector<std::vector<uint32_t>> m;
  for (const Frame& f : frames) m.push_back(f.mesh_id);
  return m;
}

StabilitySequence fixture_sequence(const std::string& fixtures_root, const std::string& name) {
  const std::string dir = (fs::path(fixtures_root) / name).string();
  const io::Sequence seq(dir);
  StabilitySequence s;
  for (int k = 0; k < seq.size(); ++k) {
    Frame f = seq.read(k);
    if (!f.has_reference())
      throw std::invalid_argument(seq.path(k) + ": the stability suite needs a reference channel");
    f.direct = Image();
    f.indirect = Image();
    s.frames.push_back(std::move(f));
    if (seq.is_camera_cut(k)) s.cuts.push_back(k);
  }
  const io::Manifest& m = seq.manifest();
  s.description = "committed fixture `" + name + "`: " + std::to_string(seq.size()) +
                  " frames of " + std::to_string(m.width) + "x" + std::to_string(m.height) +
                  ", 1 spp, " + std::to_string(m.reference_spp) + "-sample references";
  return s;
}

bool stability_can_render() {
#if defined(SVGF_BENCH_HAVE_GBUFFER)
  return true;
#else
  return false;
#endif
}

StabilitySequence rendered_sequence(const std::string& scene, int width, int height, int frames,
                                    int reference_spp, int threads, const std::string& cache_dir,
                                    bool quiet) {
  StabilitySequence s;
  s.description = "`" + scene + "` rendered at " + std::to_string(width) + "x" +
                  std::to_string(height) + ": " + std::to_string(frames) +
                  " frames, 1 spp with gradient samples, " + std::to_string(reference_spp) +
                  "-sample references";
#if defined(SVGF_BENCH_HAVE_GBUFFER)
  gbuffer::RenderSettings settings;
  settings.width = width;
  settings.height = height;
  settings.reference_spp = reference_spp;
  settings.split = false;
  settings.gradients = true;
  gbuffer::validate(settings);
  const gbuffer::SceneDesc& desc = gbuffer::find_scene(scene);
  fs::path folder;
  if (!cache_dir.empty()) {
    folder = fs::path(cache_dir) /
             ("stability_" + scene + "_" + std::to_string(width) + "x" + std::to_string(height) +
              "_r" + std::to_string(reference_spp) + "_gen" +
              std::to_string(gbuffer::kGeneratorVersion));
    fs::create_directories(folder);
  }
  io::FrameStorage exact;  // every group FLOAT: a cached frame reads back with its own bits
  exact.albedo = exact.normal = io::PixelStorage::Float;
  std::unique_ptr<gbuffer::Renderer> renderer;  // made only when a frame is not cached
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  const auto t0 = std::chrono::steady_clock::now();
  int rendered = 0;
  for (int k = 0; k < frames; ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%04d.exr", k);
    const std::string path = folder.empty() ? std::string() : (folder / name).string();
    if (!path.empty() && fs::exists(path)) {
      s.frames.push_back(io::read_frame(path));
      continue;
    }
    if (!renderer) renderer = std::make_unique<gbuffer::Renderer>();
    Frame f;
    arena.execute([&] { f = renderer->render(desc, k, settings); });
    ++rendered;
    if (!path.empty()) io::write_frame(path, f, exact);
    s.frames.push_back(std::move(f));
    if (!quiet)
      std::fprintf(stderr, "\r  rendering %s %dx%d: frame %d/%d", scene.c_str(), width, height,
                   k + 1, frames);
  }
  if (rendered && !quiet)
    std::fprintf(stderr, " (%.1f s)\n",
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
#else
  (void)width, (void)height, (void)frames, (void)reference_spp, (void)threads, (void)cache_dir,
      (void)quiet;
  throw std::runtime_error("this build has no renderer: cannot render " + scene);
#endif
  return s;
}

std::vector<Image> denoise_sequence(const RunConfig& c, const StabilitySequence& seq) {
  std::vector<Image> out(seq.frames.size());
  std::unique_ptr<Denoiser> den;
  if (c.project())
    den = make_denoiser(c.denoiser);
  else
    set_baseline_threads(c.resolved_threads());
  for (size_t k = 0; k < seq.frames.size(); ++k) {
    if (den) {
      if (seq.is_cut(static_cast<int>(k))) den->reset();
      den->denoise(seq.frames[k], out[k]);
    } else {
      run_baseline(c.baseline, seq.frames[k], out[k]);
    }
  }
  return out;
}

}  // namespace svgf::bench

#include "bench/workload.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "io/exr_frame.h"
#include "io/sequence.h"
#include "tests/synthetic_sequence.h"
#if defined(SVGF_BENCH_HAVE_GBUFFER)
#include "gbuffer/fixture_format.h"
#include "gbuffer/renderer.h"
#include "gbuffer/scenes.h"
#endif

namespace fs = std::filesystem;

namespace svgf::bench {

bool FrameSet::is_cut(int k) const { return std::find(cuts.begin(), cuts.end(), k) != cuts.end(); }

bool FrameSet::gradient_samples() const {
  return !frames.empty() && std::all_of(frames.begin(), frames.end(),
                                        [](const Frame& f) { return !f.gradient.empty(); });
}

double FrameSet::surface_fraction() const {
  size_t surface = 0, total = 0;
  for (const Frame& f : frames) {
    const float* d = f.depth.plane(0);
    for (size_t i = 0; i < f.depth.pixel_count(); ++i) surface += d[i] > 0.f ? 1 : 0;
    total += f.depth.pixel_count();
  }
  return total ? static_cast<double>(surface) / static_cast<double>(total) : 1.0;
}

void parse_size(const std::string& text, int& width, int& height) {
  std::string t = text;
  std::transform(t.begin(), t.end(), t.begin(), [](unsigned char c) { return std::tolower(c); });
  if (t == "720p") {
    width = 1280;
    height = 720;
    return;
  }
  if (t == "1080p") {
    width = 1920;
    height = 1080;
    return;
  }
  if (t == "4k" || t == "2160p") {
    width = 3840;
    height = 2160;
    return;
  }
  int w = 0, h = 0;
  char extra = 0;
  if (std::sscanf(t.c_str(), "%dx%d%c", &w, &h, &extra) == 2 ||
      (std::sscanf(t.c_str(), "%d%c", &w, &extra) == 1 && (h = w) > 0)) {
    if (w >= 8 && h >= 8 && w <= 16384 && h <= 16384) {
      width = w;
      height = h;
      return;
    }
  }
  throw std::invalid_argument("size '" + text +
                              "': expected 720p, 1080p, 4k, N (square) or WxH, 8 to 16384");
}

namespace {

// Optional channels no method reads unless asked (emission and position some do): dropped to
// save memory.
void drop_unused(Frame& f, bool split) {
  if (split) return;
  f.direct = Image();
  f.indirect = Image();
}

}  // namespace

FrameSet load_fixture(const std::string& dir, int max_frames, bool split) {
  const io::Sequence seq(dir);
  FrameSet s;
  s.source = "fixture";
  s.scene = seq.manifest().scene;
  s.width = seq.manifest().width;
  s.height = seq.manifest().height;
  const int n = max_frames > 0 ? std::min(max_frames, seq.size()) : seq.size();
  for (int k = 0; k < n; ++k) {
    Frame f = seq.read(k);
    drop_unused(f, split);
    s.frames.push_back(std::move(f));
    if (seq.is_camera_cut(k)) s.cuts.push_back(k);
  }
  s.description = "fixture " + s.scene + " (" + fs::path(dir).filename().string() + "), " +
                  std::to_string(n) + " frames of " + std::to_string(s.width) + "x" +
                  std::to_string(s.height) + ", " + std::to_string(seq.manifest().spp) +
                  " spp, reference " + std::to_string(seq.manifest().reference_spp) + " spp, " +
                  (s.gradient_samples() ? "with" : "no") + " gradient samples";
  return s;
}

bool renderer_available() {
#if defined(SVGF_BENCH_HAVE_GBUFFER)
  return true;
#else
  return false;
#endif
}

FrameSet generate_frames(const std::string& scene, int width, int height, int count,
                         const std::string& cache_dir, bool split) {
  FrameSet s;
  s.scene = scene;
  s.width = width;
  s.height = height;
  count = std::max(count, 1);
#if defined(SVGF_BENCH_HAVE_GBUFFER)
  const gbuffer::SceneDesc& desc = gbuffer::find_scene(scene);
  gbuffer::RenderSettings settings;
  settings.width = width;
  settings.height = height;
  settings.spp = 1;
  settings.reference_spp = 0;
  settings.split = split;
  settings.gradients = true;  // A-SVGF's samples, for --antilag gradient
  gbuffer::validate(settings);
  std::unique_ptr<gbuffer::Renderer> renderer;  // made only when a frame is not cached
  double render_s = 0;
  int rendered = 0;
  for (int k = 0; k < count; ++k) {
    std::string path;
    if (!cache_dir.empty()) {
      fs::create_directories(cache_dir);
      path = (fs::path(cache_dir) /
              (scene + "_" + std::to_string(width) + "x" + std::to_string(height) + "_frame" +
               std::to_string(k) + "_gen" + std::to_string(gbuffer::kGeneratorVersion) +
               (split ? "_split" : "") + ".exr"))
                 .string();
      if (fs::exists(path)) {
        Frame f = io::read_frame(path);
        // Older caches were written without the world positions the JBF reads, or without the
        // gradient samples A-SVGF reads: render again.
        if (!f.position.empty() && !f.gradient.empty()) {
          drop_unused(f, split);
          s.frames.push_back(std::move(f));
          continue;
        }
      }
    }
    if (!renderer) renderer = std::make_unique<gbuffer::Renderer>();
    const auto t0 = std::chrono::steady_clock::now();
    Frame f = renderer->render(desc, k, settings);
    render_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    ++rendered;
    drop_unused(f, split);
    if (!path.empty()) io::write_frame(path, f);
    s.frames.push_back(std::move(f));
  }
  if (rendered)
    std::fprintf(stderr, "svgf-bench: rendered %d frame(s) of %s at %dx%d in %.1f s\n", rendered,
                 scene.c_str(), width, height, render_s);
  s.source = "rendered";
  s.description = scene + " rendered by the Embree path tracer at " + std::to_string(width) + "x" +
                  std::to_string(height) + ", 1 spp, with gradient samples, " +
                  std::to_string(count) + " distinct frames played cyclically";
#else
  (void)cache_dir;
  test::SyntheticScene syn;
  syn.width = width;
  syn.height = height;
  syn.square = std::max(4, height / 4);
  syn.speed = std::max(1, width / 256);
  for (int k = 0; k < count; ++k) {
    Frame f = syn.frame(k);
    f.reference = Image();
    drop_unused(f, split);
    s.frames.push_back(std::move(f));
  }
  s.source = "synthetic";
  s.description = "synthetic moving square (this build has no renderer) at " +
                  std::to_string(width) + "x" + std::to_string(height) +
                  ", no gradient samples, " + std::to_string(count) +
                  " distinct frames played cyclically";
#endif
  return s;
}

std::vector<std::string> fixture_dirs(const std::string& root) {
  std::vector<std::string> dirs;
  std::error_code ec;
  if (!fs::is_directory(root, ec)) return dirs;
  for (const auto& e : fs::directory_iterator(root, ec))
    if (e.is_directory() && fs::exists(e.path() / "manifest.json"))
      dirs.push_back(e.path().string());
  std::sort(dirs.begin(), dirs.end());
  return dirs;
}

}  // namespace svgf::bench

// Exact mode's two storages give the same bits. The CUDA engine runs exact mode over packed
// pixels (methods/svgf/flavors.h: SvgfExactPacked), the CPU over planes (SvgfExact, with its row
// drivers); storage is not arithmetic, so the two must agree bit for bit. Here both run on the
// CPU: the SVGF denoiser over a CPU backend that stores packed, against the CPU's own denoiser,
// frame by frame, the output and every debug buffer, on every fixture and on synthetic frames
// with settings that take each branch of the frame (methods/svgf/pipeline.h). The GPU tests then
// compare the CUDA denoiser with the CPU's (docs/cuda.md).
#include <algorithm>
#include <filesystem>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "io/sequence.h"
#include "kernels_cpu/cpu_backend.h"
#include "methods/svgf/denoiser.h"
#include "pipeline/make_denoiser.h"
#include "synthetic_sequence.h"
#include "test_support.h"

using namespace svgf;

namespace {

// The CPU backend with the CUDA backend's storage choice: the denoiser then runs the packed
// flavor (its kernels through the generic per-pixel driver).
struct PackedCpuBackend : cpu::CpuBackend {
  using CpuBackend::CpuBackend;
  static constexpr bool kPackedStorage = true;
};

// The same, copying the inputs and leaving the sanitize stage to the denoiser, as the CUDA
// backend does: the packed flavor then fuses it into its first kernel where it can
// (methods/svgf/pipeline.h: fuses_sanitize) or runs it first.
struct PackedCopyingCpuBackend : PackedCpuBackend {
  explicit PackedCopyingCpuBackend(const EngineConfig& config) : PackedCpuBackend(config) {
    copies_inputs_ = true;
  }
};

// The committed sequences (SVGF_FIXTURES_DIR overrides where they are, as for the GPU tests).
std::vector<std::string> fixture_dirs() {
  namespace fs = std::filesystem;
  const char* env = std::getenv("SVGF_FIXTURES_DIR");
  fs::path root = env ? fs::path(env) : fs::path(SVGF_SOURCE_DIR) / "fixtures";
  if (!env && !fs::is_directory(root)) root = "fixtures";  // a copied binary, run from a checkout
  std::vector<std::string> dirs;
  if (!fs::is_directory(root)) return dirs;
  for (const auto& e : fs::directory_iterator(root))
    if (e.is_directory() && fs::exists(e.path() / "manifest.json"))
      dirs.push_back(e.path().string());
  std::sort(dirs.begin(), dirs.end());
  return dirs;
}

void require_same_repairs(const InputRepairs& a, const InputRepairs& b, const std::string& at) {
  INFO(at);
  REQUIRE(a.color == b.color);
  REQUIRE(a.albedo == b.albedo);
  REQUIRE(a.emission == b.emission);
  REQUIRE(a.normal == b.normal);
  REQUIRE(a.surface == b.surface);
  REQUIRE(a.motion == b.motion);
}

// The CPU's denoiser and the packed flavor over `Backend` over `frames` (`cut[k]`: reset both
// before frame k): the output, every debug buffer and the repairs. `keep_scratch` false: the
// packed one shares its scratch as the CUDA denoiser does (the frame's normals in a-trous buffer
// 1, SvgfDenoiser::normals_planes), so its scratch buffers cannot be read back.
template <class Backend>
void require_same_bits_over(const SvgfParams& p, const std::vector<Frame>& frames,
                            const std::vector<bool>& cut, const std::string& what,
                            bool keep_scratch = true) {
  DenoiserConfig c;
  c.svgf = p;
  c.threads = 2;
  c.keep_scratch = true;  // the scratch compared too
  const std::unique_ptr<Denoiser> planes = make_denoiser(c);
  EngineConfig e;
  e.threads = 2;
  e.keep_scratch = keep_scratch;
  SvgfDenoiser<Backend> packed(p, e);
  for (size_t k = 0; k < frames.size(); ++k) {
    if (k < cut.size() && cut[k]) {
      planes->reset();
      packed.reset();
    }
    Image a, b;
    planes->denoise(frames[k], a);
    packed.denoise(frames[k], b);
    const std::string at = what + ", frame " + std::to_string(k);
    test::require_identical(b, a, at + ": output");
    for (const std::string& name : planes->debug_buffers()) {
      const bool scratch =
          name == svgf_buffer::kIllumination || name == svgf_buffer::kAccumulated;
      if (scratch && !keep_scratch) continue;
      test::require_identical(packed.read_buffer(name), planes->read_buffer(name),
                              at + ": debug buffer " + name);
    }
    require_same_repairs(packed.last_report().repairs, planes->last_report().repairs, at);
  }
}

// Both backends: reading the frame sanitized, and sanitizing a copy in the denoiser's frame.
void require_same_bits(const SvgfParams& p, const std::vector<Frame>& frames,
                       const std::vector<bool>& cut, const std::string& what) {
  require_same_bits_over<PackedCpuBackend>(p, frames, cut, what);
  require_same_bits_over<PackedCopyingCpuBackend>(p, frames, cut, what + " (sanitized by SVGF)");
  require_same_bits_over<PackedCopyingCpuBackend>(p, frames, cut,
                                                  what + " (sanitized by SVGF, scratch shared)",
                                                  /*keep_scratch=*/false);
}

std::vector<Frame> synthetic_frames(int n, int width = 61, int height = 37) {
  test::SyntheticScene scene;
  scene.width = width;  // odd sizes: partial strata, borders on every side
  scene.height = height;
  std::vector<Frame> frames;
  for (int k = 0; k < n; ++k) frames.push_back(scene.frame(k));
  return frames;
}

// Color split into a direct part and a noisier indirect one (direct + indirect = color up to
// rounding, which the filter does not need).
std::vector<Frame> split_frames(std::vector<Frame> frames) {
  std::mt19937 rng(17u);
  std::uniform_real_distribution<float> share(0.2f, 0.8f);
  for (Frame& f : frames) {
    f.direct = f.color;
    f.indirect = Image(f.width(), f.height(), 3);
    for (int c = 0; c < 3; ++c)
      for (size_t i = 0; i < f.color.pixel_count(); ++i) {
        const float s = share(rng);
        f.direct.plane(c)[i] = s * f.color.plane(c)[i];
        f.indirect.plane(c)[i] = (1.f - s) * f.color.plane(c)[i];
      }
  }
  return frames;
}

// A-SVGF's gradient samples: one per 3x3 stratum (from the second frame on), at a pixel that
// moves with the frame, the previous luminance perturbed so that some strata see a change.
std::vector<Frame> gradient_frames(std::vector<Frame> frames) {
  std::mt19937 rng(23u);
  std::uniform_real_distribution<float> change(0.5f, 1.5f);
  for (size_t k = 0; k < frames.size(); ++k) {
    Frame& f = frames[k];
    f.gradient = Image(f.width(), f.height(), 3);
    if (k == 0) continue;  // no previous sample to re-shade
    for (int sy = 0; sy * 3 < f.height(); ++sy)
      for (int sx = 0; sx * 3 < f.width(); ++sx) {
        const int x = std::min(f.width() - 1, sx * 3 + static_cast<int>(k % 3));
        const int y = std::min(f.height() - 1, sy * 3 + static_cast<int>((k / 3) % 3));
        const float l = luminance(f.color.rgb().load(y * f.width() + x));
        f.gradient.at(x, y, 0) = (sx + sy) % 4 == 0 ? l * change(rng) : l;
        f.gradient.at(x, y, 1) = l;
        f.gradient.at(x, y, 2) = 1.f;
      }
  }
  return frames;
}

// Every kind of bad input the sanitize stage repairs, in frames 1 to 3 (each pixel's kind by
// its index): radiance NaN, Inf, negative; albedo outside [0, 1]; depth NaN and Inf; a depth
// gradient of Inf; normals too long (renormalized) and zero (background); motion NaN and huge.
// Some land on the pixels of gradient samples, whose guides the fused gradient launch reads.
std::vector<Frame> with_bad_inputs(std::vector<Frame> frames) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  for (size_t k = 1; k < frames.size() && k <= 3; ++k) {
    Frame& f = frames[k];
    const size_t n = f.color.pixel_count();
    for (size_t i = 7 * k; i < n; i += 29) {
      switch ((i / 29 + k) % 10) {
        case 0: f.color.plane(i % 3)[i] = nan; break;
        case 1: f.color.plane(0)[i] = inf; break;
        case 2: f.albedo.plane(1)[i] = (i % 2) ? nan : 1.5f; break;
        case 3: f.depth.plane(0)[i] = nan; break;
        case 4: f.depth.plane(0)[i] = inf; break;
        case 5: f.depth_gradient.plane(i % 2)[i] = inf; break;
        case 6: for (int c = 0; c < 3; ++c) f.normal.plane(c)[i] *= 2.f; break;
        case 7: for (int c = 0; c < 3; ++c) f.normal.plane(c)[i] = 0.f; break;
        case 8: f.motion.plane(0)[i] = nan; break;
        default: f.motion.plane(1)[i] = -1e9f; break;
      }
    }
  }
  return frames;
}

}  // namespace

TEST_CASE("exact mode over packed storage: the same bits as over planes, every fixture",
          "[pipeline][packed]") {
  const std::vector<std::string> dirs = fixture_dirs();
  REQUIRE_FALSE(dirs.empty());
  for (const std::string& dir : dirs) {
    const io::Sequence seq(dir);
    std::vector<Frame> frames;
    std::vector<bool> cut;
    for (int k = 0; k < std::min(seq.size(), 8); ++k) {
      frames.push_back(seq.read(k));
      cut.push_back(seq.is_camera_cut(k));
    }
    require_same_bits(SvgfParams(), frames, cut, dir);
  }
}

TEST_CASE("exact mode over packed storage: the same bits in every branch of the frame",
          "[pipeline][packed]") {
  const std::vector<Frame> frames = synthetic_frames(7);
  const std::vector<bool> cut = {false, false, false, false, true, false, false};
  struct Setting {
    const char* name;
    void (*edit)(SvgfParams&);
  };
  const Setting settings[] = {
      {"defaults", [](SvgfParams&) {}},
      {"paper: 5 iterations, feedback tap 0",
       [](SvgfParams& p) { p.iterations = 5; p.feedback_tap = 0; }},
      {"feedback tap on the last iteration",
       [](SvgfParams& p) { p.iterations = 3; p.feedback_tap = 2; }},
      {"no feedback tap", [](SvgfParams& p) { p.feedback_tap = -1; }},
      {"no iterations", [](SvgfParams& p) { p.iterations = 0; }},
      {"run-time normal power", [](SvgfParams& p) { p.phi_normal = 100.f; }},
      {"statistics anti-lag", [](SvgfParams& p) { p.antilag = Antilag::Statistics; }},
      {"TAA", [](SvgfParams& p) { p.taa = true; }},
  };
  for (const Setting& s : settings) {
    SvgfParams p;
    s.edit(p);
    require_same_bits(p, frames, cut, s.name);
  }
  SvgfParams split;
  split.split = SplitMode::On;
  require_same_bits(split, split_frames(frames), cut, "direct and indirect");
  SvgfParams gradient;
  gradient.antilag = Antilag::Gradient;
  require_same_bits(gradient, gradient_frames(frames), cut, "gradient anti-lag");
  // Bad inputs: the sanitize stage first, or fused into the first kernel with the gradient
  // launch reading the guides through its rule (the CPU's planes sanitize before anything).
  require_same_bits(gradient, with_bad_inputs(gradient_frames(frames)), cut,
                    "gradient anti-lag, bad inputs");
  require_same_bits(SvgfParams(), with_bad_inputs(frames), cut, "defaults, bad inputs");
  SvgfParams off;
  off.antilag = Antilag::Off;
  require_same_bits(off, with_bad_inputs(frames), cut, "no anti-lag, bad inputs");
  require_same_bits(split, with_bad_inputs(split_frames(frames)), cut,
                    "direct and indirect, bad inputs");
  // The shared scratch's homes change with the frame (SvgfDenoiser::scratch_in_history, its
  // mutations fail the runs above): split channels on frames 3 and 4 only (SplitMode::Auto) move
  // it out of the history from the first split frame on; on frames of 5x2 pixels the stratum
  // planes do not fit one plane and keep their own.
  SvgfParams late_split = gradient;
  late_split.split = SplitMode::Auto;
  std::vector<Frame> late = split_frames(gradient_frames(frames));
  for (size_t k : {0, 1, 2, 5, 6}) {
    late[k].direct = Image();
    late[k].indirect = Image();
  }
  require_same_bits(late_split, late, cut, "gradient anti-lag, split from frame 3 to 4");
  require_same_bits(gradient, gradient_frames(synthetic_frames(7, 5, 2)), cut,
                    "gradient anti-lag, 5x2 frames");
  // The packed flavor fuses A-SVGF's stages where the filter is small enough (one step at most,
  // a lambda radius of at most 1: methods/svgf/gradient_tile.h) and runs the three passes
  // otherwise; the planes always run the three.
  for (const auto& [steps, radius] : {std::pair<int, int>{0, 1}, {1, 0}, {2, 1}, {1, 2}}) {
    SvgfParams g = gradient;
    g.gradient_iterations = steps;
    g.gradient_lambda_radius = radius;
    require_same_bits(g, with_bad_inputs(gradient_frames(frames)), cut,
                      "gradient anti-lag, " + std::to_string(steps) + " step(s), lambda radius " +
                          std::to_string(radius));
  }
}

// CPU vs CUDA, one stage at a time: every core/ kernel on seeded random inputs (never zeros;
// NaN, Inf, negative and subnormal values where the stage guards against them) at several sizes
// and block shapes, and every stage of the pipeline on the frames of every fixture (each stage
// fed the CPU's state, so a difference points at the stage that made it). Exact mode: bitwise.
#include <algorithm>
#include <cstdio>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <catch2/catch.hpp>

#include "methods/svgf/pipeline.h"
#include "gpu_test_support.h"
#include "io/sequence.h"
#include "synthetic_sequence.h"

using namespace svgf;
using namespace svgf::gpu_test;

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

struct Size {
  int w, h;
};

std::vector<Size> sizes() {
  if (options().reduced) return {{257, 89}, {1, 1}};
  return {{257, 89}, {64, 48}, {1, 1}, {3, 200}, {31, 17}, {640, 360}};
}

std::vector<cuda::LaunchShape> shapes() {
  if (options().reduced) return {{16, 8}, {13, 7}};
  return {{16, 8}, {32, 4}, {13, 7}};
}

std::string label(const char* stage, Size s, cuda::LaunchShape b, const std::string& extra = "") {
  return std::string(stage) + " " + std::to_string(s.w) + "x" + std::to_string(s.h) +
         ", block " + std::to_string(b.block_x) + "x" + std::to_string(b.block_y) + extra;
}

// Seeded random planes.
class Random {
 public:
  explicit Random(uint32_t seed) : rng_(seed) {}
  float uniform(float lo, float hi) { return std::uniform_real_distribution<float>(lo, hi)(rng_); }
  bool chance(double p) { return std::bernoulli_distribution(p)(rng_); }
  void fill(float* p, size_t n, float lo, float hi) {
    for (size_t i = 0; i < n; ++i) p[i] = uniform(lo, hi);
  }

  // Surfaces at depth 1..4 (8% background, a few NaN), normals near +z (so the ^128 normal
  // weight varies instead of vanishing), three meshes, sub-pixel and a few wild motion vectors.
  void guides(const GuideView& g) {
    const size_t n = static_cast<size_t>(g.width) * g.height;
    auto* depth = const_cast<float*>(g.depth);
    auto* dx = const_cast<float*>(g.depth_dx);
    auto* dy = const_cast<float*>(g.depth_dy);
    auto* nx = const_cast<float*>(g.normal.r);
    auto* ny = const_cast<float*>(g.normal.g);
    auto* nz = const_cast<float*>(g.normal.b);
    auto* mx = const_cast<float*>(g.motion_x);
    auto* my = const_cast<float*>(g.motion_y);
    auto* mesh = const_cast<uint32_t*>(g.mesh_id);
    for (size_t i = 0; i < n; ++i) {
      const bool background = chance(0.08);
      depth[i] = background ? 0.f : (chance(0.005) ? kNaN : uniform(1.f, 4.f));
      dx[i] = uniform(-0.05f, 0.05f);
      dy[i] = chance(0.005) ? kNaN : uniform(-0.05f, 0.05f);
      float v[3] = {uniform(-0.12f, 0.12f), uniform(-0.12f, 0.12f), 1.f};
      const float len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
      nx[i] = background ? 0.f : v[0] / len;
      ny[i] = background ? 0.f : v[1] / len;
      nz[i] = background ? 0.f : (chance(0.003) ? kNaN : v[2] / len);
      mesh[i] = background ? 0u : (chance(0.85) ? 1u : 2u + static_cast<uint32_t>(chance(0.5)));
      mx[i] = chance(0.01) ? (chance(0.5) ? kNaN : 3e8f) : uniform(-1.5f, 1.5f);
      my[i] = uniform(-1.5f, 1.5f);
    }
  }
  // The previous frame: 70% of pixels are this frame's surface moved slightly (so bilinear taps
  // pass the consistency tests), the rest unrelated (fallback and disocclusion paths).
  void prev_guides(const GuideView& cur, const GuideView& prev) {
    guides(prev);
    const size_t n = static_cast<size_t>(cur.width) * cur.height;
    for (size_t i = 0; i < n; ++i) {
      if (!chance(0.7)) continue;
      const_cast<float*>(prev.depth)[i] = cur.depth[i] * uniform(0.995f, 1.005f);
      const_cast<float*>(prev.normal.r)[i] = cur.normal.r[i];
      const_cast<float*>(prev.normal.g)[i] = cur.normal.g[i];
      const_cast<float*>(prev.normal.b)[i] = cur.normal.b[i];
      const_cast<uint32_t*>(prev.mesh_id)[i] = cur.mesh_id[i];
    }
  }
  // Radiance with bad samples: NaN, +-Inf, negative, and subnormals that FTZ would flush.
  void radiance(float* p, size_t n) {
    const float bad[] = {kNaN, kInf, -kInf, -0.75f, 3e-39f};
    for (size_t i = 0; i < n; ++i)
      p[i] = chance(0.03) ? bad[std::uniform_int_distribution<int>(0, 4)(rng_)]
                          : uniform(0.f, 3.f);
  }

 private:
  std::mt19937 rng_;
};

// The variance stage's inputs in an arena: random guides, accumulated color and variance,
// moments (E[l^2] >= E[l]^2 + floor), history lengths young (1-3) with probability
// `young_share`, else 4-32.
VarianceKernel random_variance_kernel(Arena& a, Random& r, double young_share,
                                      float second_moment_floor) {
  const size_t n = a.pixels();
  VarianceKernel k;
  k.guides = a.guides("guides");
  r.guides(k.guides);
  k.accumulated = a.illum_var("accumulated");
  float* accumulated = const_cast<float*>(k.accumulated.color.r);
  r.fill(accumulated, 3 * n, 0.f, 2.f);
  r.fill(accumulated + 3 * n, n, 0.f, 0.3f);
  float* moments = a.planes("moments", 2);
  float* history = a.planes("history", 1);
  for (size_t i = 0; i < n; ++i) {
    moments[i] = r.uniform(0.f, 1.f);
    moments[n + i] = moments[i] * moments[i] + r.uniform(second_moment_floor, 0.5f);
    history[i] = r.chance(young_share) ? std::floor(r.uniform(1.f, 4.f)) : r.uniform(4.f, 32.f);
  }
  k.moment1 = moments;
  k.moment2 = moments + n;
  k.history = history;
  k.out = a.illum_var("out");
  return k;
}

// The a-trous stage's inputs in an arena: random guides, color and variance.
AtrousKernel random_atrous_kernel(Arena& a, Random& r, int step) {
  const size_t n = a.pixels();
  AtrousKernel k;
  k.guides = a.guides("guides");
  r.guides(k.guides);
  k.in = a.illum_var("in");
  float* in = const_cast<float*>(k.in.color.r);
  r.fill(in, 3 * n, 0.f, 2.f);
  r.fill(in + 3 * n, n, 0.f, 0.3f);
  k.out = a.illum_var("out");
  k.step = step;
  return k;
}

}  // namespace

TEST_CASE("stage demodulate: CPU vs CUDA bitwise on random input", "[stage]") {
  for (Size s : sizes())
    for (cuda::LaunchShape b : shapes()) {
      Arena a(s.w, s.h, 12);
      Random r(11u + static_cast<uint32_t>(s.w));
      const size_t n = a.pixels();
      const RgbView color = a.rgb("color"), albedo = a.rgb("albedo");
      const RgbView emission = a.rgb("emission"), illumination = a.rgb("illumination");
      r.radiance(color.r, 3 * n);
      r.fill(albedo.r, 3 * n, 0.f, 1.f);
      r.fill(emission.r, 3 * n, 0.f, 1.f);
      for (size_t i = 0; i < n; i += 17) albedo.g[i] = (i % 2) ? kNaN : 0.f;
      r.fill(illumination.r, 3 * n, 5.f, 6.f);  // overwritten: proves every pixel is written
      check_stage(a, DemodulateKernel{s.w, color, albedo, emission, illumination, 1e-3f},
                  label("demodulate", s, b), b);
    }
}

TEST_CASE("stage reproject: CPU vs CUDA bitwise on random input", "[stage]") {
  for (Size s : sizes())
    for (cuda::LaunchShape b : shapes())
      for (bool has_history : {true, false}) {
        Arena a(s.w, s.h, 40);
        Random r(23u + static_cast<uint32_t>(s.h));
        const size_t n = a.pixels();
        ReprojectKernel k;
        k.guides = a.guides("guides");
        k.prev_guides = a.guides("prev guides");
        r.guides(k.guides);
        r.prev_guides(k.guides, k.prev_guides);
        const RgbView illumination = a.rgb("illumination"), prev_color = a.rgb("prev color");
        float* prev_moments = a.planes("prev moments", 2);
        float* prev_history = a.planes("prev history", 1);
        r.fill(illumination.r, 3 * n, 0.f, 2.f);
        r.fill(prev_color.r, 3 * n, 0.f, 2.f);
        for (size_t i = 0; i < n; ++i) {
          prev_moments[i] = r.uniform(0.f, 1.f);
          prev_moments[n + i] = prev_moments[i] * prev_moments[i] + r.uniform(0.f, 0.5f);
          prev_history[i] = std::floor(r.uniform(1.f, 33.f));
        }
        k.illumination = illumination;
        k.prev_color = prev_color;
        k.prev_moment1 = prev_moments;
        k.prev_moment2 = prev_moments + n;
        k.prev_history = prev_history;
        k.has_history = has_history;
        k.accumulated = a.illum_var("accumulated");
        float* moments = a.planes("moments", 2);
        k.moment1 = moments;
        k.moment2 = moments + n;
        k.history = a.planes("history", 1);
        r.fill(k.accumulated.color.r, 4 * n, 7.f, 8.f);
        r.fill(moments, 3 * n, 7.f, 8.f);  // moments and history: overwritten
        k.params.history_cap = 24;
        // The blend and tap tests alone: the statistics anti-lag (the defaults' rule on frames
        // without gradient samples) reads the frame's color and albedo, which this arena does
        // not hold; it is compared on every fixture in tests/gpu_test_pipeline.cpp.
        k.params.antilag = Antilag::Off;
        check_stage(a, k, label("reproject", s, b, has_history ? "" : ", no history"), b);
      }
}

// The GPU runs the young pixels' 7x7 estimate on compacted threads (core/rare_path.h): half,
// none and all of the pixels young; every pixel's accumulated color copied into the color
// history by either path.
TEST_CASE("stage variance: CPU vs CUDA bitwise on random input", "[stage]") {
  for (double young : {0.5, 0.0, 1.0})
    for (Size s : sizes())
      for (cuda::LaunchShape b : shapes()) {
        Arena a(s.w, s.h, 27);
        Random r(37u + static_cast<uint32_t>(s.w * 3));
        VarianceKernel k = random_variance_kernel(a, r, young, 0.f);
        r.fill(k.out.color.r, 4 * a.pixels(), 7.f, 8.f);
        k.color_history = a.rgb("color history");
        r.fill(k.color_history.r, 3 * a.pixels(), 5.f, 6.f);
        check_stage(a, k, label("variance", s, b, ", young share " + std::to_string(young)), b);
      }
}

namespace {

// A kernel with a rare path: pixels flagged rare get -1 - i, the others i + 1, each added to
// what `out` held (0), so a pixel run twice, or by both paths, shows.
struct RareFlaggedKernel {
  int width;
  const uint8_t* rare;
  float* out;
  SVGF_HD bool common_path(int x, int y) const {
    const int i = y * width + x;
    if (rare[i]) return false;
    out[i] = out[i] + static_cast<float>(i + 1);
    return true;
  }
  SVGF_HD void rare_path(int x, int y) const {
    const int i = y * width + x;
    out[i] = out[i] - static_cast<float>(i + 1);
  }
  SVGF_HD void operator()(int x, int y) const {
    if (!common_path(x, y)) rare_path(x, y);
  }
};

}  // namespace

TEST_CASE("launcher: a kernel's rare path runs once for each rare pixel, on every block shape",
          "[launch]") {
  static_assert(HasRarePath<RareFlaggedKernel>::value, "the launcher must see the rare path");
  static_assert(!HasRarePath<AtrousKernel>::value, "a plain kernel has none");
  const int w = 75, h = 41;
  const size_t n = static_cast<size_t>(w) * h;
  for (double share : {0.0, 0.3, 1.0})
    for (cuda::LaunchShape b : std::vector<cuda::LaunchShape>{{32, 8}, {13, 7}, {1, 1}, {32, 32},
                                                              {64, 1}}) {
      Random r(5u);
      std::vector<uint8_t> rare(n);
      for (auto& f : rare) f = r.chance(share) ? 1 : 0;
      cuda::DeviceArray<uint8_t> d_rare(rare.data(), n);
      const std::vector<float> zeros(n, 0.f);
      cuda::DeviceArray<float> d_out(zeros.data(), n);
      cuda::run(RareFlaggedKernel{w, d_rare.get(), d_out.get()}, w, h, b, "rare flagged");
      const std::vector<float> out = d_out.to_host();
      size_t bad = 0;
      for (size_t i = 0; i < n; ++i) {
        const float want = (rare[i] ? -1.f : 1.f) * static_cast<float>(i + 1);
        if (out[i] != want && bad++ < 5)
          UNSCOPED_INFO("pixel " << i << ": " << out[i] << ", expected " << want);
      }
      INFO("share " << share << ", block " << b.block_x << "x" << b.block_y);
      REQUIRE(bad == 0);
    }
}

TEST_CASE("stage atrous: CPU vs CUDA bitwise on random input, every step", "[stage]") {
  struct Variant {
    const char* name;
    float phi_normal, phi_depth;
  };
  const Variant variants[] = {{"defaults", 128.f, 1.f},
                              {"phi_normal 37.5 (det_pow's exp/log path)", 37.5f, 1.f},
                              {"phi_depth 0 (no depth term)", 128.f, 0.f}};
  const std::vector<int> steps =
      options().reduced ? std::vector<int>{1, 8} : std::vector<int>{1, 2, 4, 8, 16};
  for (Size s : sizes())
    for (cuda::LaunchShape b : shapes())
      for (const Variant& v : variants)
        for (int step : steps) {
          if (options().reduced && &v != &variants[0]) continue;
          Arena a(s.w, s.h, 17);
          Random r(53u + static_cast<uint32_t>(step));
          const size_t n = a.pixels();
          AtrousKernel k = random_atrous_kernel(a, r, step);
          const_cast<float*>(k.in.color.r)[n / 2] = 1e-39f;  // a subnormal survives on both sides
          r.fill(k.out.color.r, 4 * n, 7.f, 8.f);
          k.params.phi_normal = v.phi_normal;
          k.params.phi_depth = v.phi_depth;
          check_stage(a, k,
                      label("atrous", s, b, ", step " + std::to_string(step) + ", " + v.name),
                      b);
        }
}

TEST_CASE("stage remodulate, tonemap, copy: CPU vs CUDA bitwise on random input", "[stage]") {
  for (Size s : sizes())
    for (cuda::LaunchShape b : shapes()) {
      const size_t n = static_cast<size_t>(s.w) * s.h;
      {
        Arena a(s.w, s.h, 12);
        Random r(71u);
        const RgbView illumination = a.rgb("illumination"), albedo = a.rgb("albedo");
        const RgbView emission = a.rgb("emission"), output = a.rgb("output");
        r.fill(illumination.r, 3 * n, 0.f, 3.f);
        r.fill(albedo.r, 3 * n, 0.f, 1.f);
        r.fill(emission.r, 3 * n, 0.f, 2.f);
        for (size_t i = 0; i < n; i += 13) albedo.b[i] = kNaN;
        r.fill(output.r, 3 * n, 7.f, 8.f);
        check_stage(a, RemodulateKernel{s.w, illumination, {albedo, emission, output, 1e-3f}},
                    label("remodulate", s, b), b);
      }
      {
        Arena a(s.w, s.h, 4);
        Random r(73u);
        const RgbView color = a.rgb("color");
        auto* rgb8 = reinterpret_cast<uint8_t*>(a.planes("rgb8", 1, true));
        r.radiance(color.r, 3 * n);
        for (size_t i = 0; i < n; i += 7) color.g[i] = r.uniform(0.f, 0.004f);  // linear toe
        for (size_t i = 0; i < 4 * n; ++i) rgb8[i] = static_cast<uint8_t>(i * 37u);
        check_stage(a, TonemapKernel{s.w, color, rgb8, 1.3f}, label("tonemap", s, b), b);
      }
      {
        Arena a(s.w, s.h, 6);
        Random r(79u);
        const RgbView src = a.rgb("src"), dst = a.rgb("dst");
        r.radiance(src.r, 3 * n);
        r.fill(dst.r, 3 * n, 7.f, 8.f);
        check_stage(a, CopyRgbKernel{s.w, src, dst}, label("copy_rgb", s, b), b);
      }
    }
}

// ---------------------------------------------------------------------------------------------
// Every stage inside the pipeline, on real frames: run_svgf_frame driven by an engine that runs
// each stage on the CPU and on the GPU from the same state and compares (the CPU result then
// carries on, so a difference is caught at the stage that made it).

namespace {

class MirrorEngine {
 public:
  MirrorEngine(Arena& arena, std::string where) : arena_(arena), where_(std::move(where)) {}
  template <class K>
  void run(const char* stage, const K& kernel, int, int) {
    check_stage(arena_, kernel,
                where_ + ", stage " + stage + " #" + std::to_string(++calls_[stage]));
  }
  template <class K>
  void run_counting(const char* stage, const K& kernel, int w, int h) {
    run(stage, kernel, w, h);
  }
  // A kernel returning repair bits (the sanitize stage, alone or fused into the first kernel):
  // its writes compared; the bits the two sides count are compared by the pipeline tests.
  template <class K>
  void run_tallying(const char* stage, const K& kernel, int w, int h) {
    run(stage, kernel, w, h);
  }
  template <class K>
  void run_blocks(const char* stage, const K& kernel, int blocks) {
    check_block_stage(arena_, kernel, blocks,
                      where_ + ", stage " + stage + " #" + std::to_string(++calls_[stage]));
  }

 private:
  Arena& arena_;
  std::string where_;
  std::map<std::string, int> calls_;
};

// The CPU denoiser's buffers, in an arena: inputs, two guide slots, two history slots, scratch
// (the packed guides too, for the packed flavor: CUDA's exact mode).
class ArenaPipeline {
 public:
  ArenaPipeline(int w, int h) : arena_(w, h, 63) {  // 62 planes and the packed regions' pads
    color_ = arena_.rgb("color");
    albedo_ = arena_.rgb("albedo");
    for (int s = 0; s < 2; ++s) guides_[s] = arena_.guides("guides slot " + std::to_string(s));
    for (int s = 0; s < 2; ++s) {
      const std::string slot = " slot " + std::to_string(s);
      color_history_[s] = arena_.rgb("color history" + slot);
      moments_[s] = arena_.planes("moments" + slot, 2);
      history_[s] = arena_.planes("history" + slot, 1);
    }
    illumination_ = arena_.rgb("illumination");
    accumulated_ = arena_.illum_var("accumulated");
    signal_[0] = arena_.planes("a-trous signal 0", 4, false, true);
    signal_[1] = arena_.planes("a-trous signal 1", 4, false, true);
    // Two slots: the packed flavors' reprojection reads the previous frame's.
    for (int s = 0; s < 2; ++s)
      packed_guides_[s] = arena_.planes("packed guides slot " + std::to_string(s), 4, false, true);
    output_ = arena_.rgb("output");
  }

  template <class Flavor>
  void frame(const Frame& f, bool reset, const SvgfParams& p, const std::string& where) {
    const size_t n = arena_.pixels();
    auto put = [&](const float* src, const float* dst, size_t count) {
      std::copy(src, src + count, const_cast<float*>(dst));
    };
    put(f.color.plane(0), color_.r, 3 * n);
    put(f.albedo.plane(0), albedo_.r, 3 * n);
    const GuideView& g = guides_[input_];
    put(f.depth.plane(0), g.depth, n);
    put(f.depth_gradient.plane(0), g.depth_dx, n);
    put(f.depth_gradient.plane(1), g.depth_dy, n);
    put(f.normal.plane(0), g.normal.r, 3 * n);
    put(f.motion.plane(0), g.motion_x, n);
    put(f.motion.plane(1), g.motion_y, n);
    std::copy(f.mesh_id.begin(), f.mesh_id.end(), const_cast<uint32_t*>(g.mesh_id));
    if (reset) has_history_ = false;

    const int prev = slot_, next = 1 - slot_;
    SvgfFrameBuffers b;
    b.guides = g;
    b.prev_guides = guides_[1 - input_];
    b.color = color_;
    b.albedo = albedo_;
    b.prev_color = color_history_[prev];
    b.prev_moment1 = moments_[prev];
    b.prev_moment2 = moments_[prev] + n;
    b.prev_history = history_[prev];
    b.next_color = color_history_[next];
    b.next_moment1 = moments_[next];
    b.next_moment2 = moments_[next] + n;
    b.next_history = history_[next];
    b.illumination = illumination_;
    b.accumulated = accumulated_;
    b.signal[0] = signal_[0];
    b.signal[1] = signal_[1];
    b.packed_guides = packed_guides_[input_];
    b.prev_packed_guides = packed_guides_[1 - input_];
    b.output = output_;
    MirrorEngine engine(arena_, where);
    run_svgf_frame<Flavor>(engine, b, p, has_history_);
    slot_ = next;
    input_ = 1 - input_;
    has_history_ = true;
  }

 private:
  Arena arena_;
  RgbView color_, albedo_, color_history_[2], illumination_, output_;
  GuideView guides_[2];
  float* moments_[2] = {};
  float* history_[2] = {};
  IllumVarView accumulated_;
  float* signal_[2] = {};
  float* packed_guides_[2] = {};
  int slot_ = 0, input_ = 0;
  bool has_history_ = false;
};

}  // namespace

namespace {

// Every stage of `Flavor`'s frames: SvgfExact (planes, the CPU's) and SvgfExactPacked (packed
// pixels, what the CUDA denoiser runs in exact mode).
template <class Flavor>
void mirror_pipeline_stages(const char* flavor) {
  // Frames 0..5 cover no history, young history (spatial variance) and the temporal estimate.
  const int cap = options().reduced ? 2 : 6;
  for (const std::string& dir : fixture_dirs()) {
    const io::Sequence seq(dir);
    const int frames = std::min(seq.size(), cap);
    ArenaPipeline pipeline(seq.manifest().width, seq.manifest().height);
    for (int k = 0; k < frames; ++k)
      pipeline.frame<Flavor>(seq.read(k), seq.is_camera_cut(k), SvgfParams(),
                             std::string(flavor) + ", " + dir + " frame " + std::to_string(k));
  }
  // The synthetic scene too (always there, and it has a moving object); odd size on purpose.
  test::SyntheticScene scene;
  scene.width = 97;
  scene.height = 61;
  ArenaPipeline pipeline(scene.width, scene.height);
  SvgfParams p;
  p.iterations = 5;  // the paper's count, feeding back the first iteration
  p.feedback_tap = 0;
  for (int k = 0; k < cap; ++k)
    pipeline.frame<Flavor>(scene.frame(k), false, p,
                           std::string(flavor) + ", synthetic frame " + std::to_string(k));
}

}  // namespace

TEST_CASE("stages inside the pipeline: CPU vs CUDA bitwise on every fixture's frames",
          "[stage][fixture]") {
  mirror_pipeline_stages<SvgfExact>("planes");
  mirror_pipeline_stages<SvgfExactPacked>("packed");
}

// ---------------------------------------------------------------------------------------------
// Fast mode, stage by stage: the SvgfFast a-trous iteration and variance estimate (packed
// storage, FastArith) against the CPU's exact kernels on the same random input, each value
// within the per-stage tolerance of docs/cuda.md (the StageRunner packs and unpacks).

namespace {

// Per value: |fast - exact| <= test::kFastTolerance * max(|exact|, 1e-3).
double worst_relative(const std::vector<float>& fast, const std::vector<float>& exact,
                      const std::string& what) {
  REQUIRE(fast.size() == exact.size());
  double worst = 0;
  size_t bad = 0;
  std::ostringstream first;
  for (size_t i = 0; i < fast.size(); ++i) {
    const double e = exact[i], f = fast[i];
    const double rel = std::fabs(f - e) / std::max(std::fabs(e), 1e-3);
    if (!(rel <= test::kFastTolerance)) {
      if (bad++ < 5) first << "  value " << i << ": fast " << f << " exact " << e << "\n";
    }
    if (rel > worst) worst = rel;
  }
  INFO(what << ": " << bad << " values outside the fast tolerance\n" << first.str());
  REQUIRE(bad == 0);
  return worst;
}

// Random guides in a frame (Random::guides writes through the frame's views).
Frame random_guides_frame(Random& r, int w, int h) {
  Frame f;
  f.allocate(w, h);
  r.guides(f.guides());
  return f;
}

}  // namespace

TEST_CASE("fast stages: a-trous and variance within the per-stage tolerance of exact",
          "[stage][fast]") {
  double worst_atrous = 0, worst_variance = 0;
  for (Size s : sizes()) {
    const int w = s.w, h = s.h;
    const size_t n = static_cast<size_t>(w) * h;
    for (int step : {1, 2, 4, 8}) {
      Random r(71u + static_cast<uint32_t>(step));
      const Frame f = random_guides_frame(r, w, h);
      Image in(w, h, 4), exact(w, h, 4), fast(w, h, 4);
      r.fill(in.plane(0), 3 * n, 0.f, 2.f);
      r.fill(in.plane(3), n, 0.f, 0.3f);
      const SvgfParams p;
      cpu::for_each_pixel(w, h, AtrousKernel{f.guides(), {in.rgb(), in.plane(3)},
                                             {exact.rgb(), exact.plane(3)}, step, p});
      test::StageRunner gpu(test::kCudaFast);
      gpu.run(AtrousIteration<SvgfFast, NormalPowerFixed<7>>{gpu.packed_guides(f),
                                                             gpu.packed(std::as_const(in)),
                                                             gpu.packed(fast), step, p},
              w, h, "fast atrous");
      worst_atrous = std::max(
          worst_atrous, worst_relative(fast.data(), exact.data(),
                                       label("fast atrous", s, {}, ", step " + std::to_string(step))));
    }
    {
      Random r(83u + static_cast<uint32_t>(w));
      const Frame f = random_guides_frame(r, w, h);
      Image accumulated(w, h, 4), moments(w, h, 2), history(w, h, 1);
      Image exact(w, h, 4), fast(w, h, 4);
      r.fill(accumulated.plane(0), 3 * n, 0.f, 2.f);
      r.fill(accumulated.plane(3), n, 0.f, 0.3f);
      for (size_t i = 0; i < n; ++i) {  // E[l^2] >= E[l]^2 + 0.05; 70% young history
        moments.plane(0)[i] = r.uniform(0.f, 1.f);
        moments.plane(1)[i] = moments.plane(0)[i] * moments.plane(0)[i] + r.uniform(0.05f, 0.5f);
        history.plane(0)[i] =
            r.chance(0.7) ? std::floor(r.uniform(1.f, 4.f)) : r.uniform(4.f, 32.f);
      }
      const SvgfParams p;
      cpu::for_each_pixel(w, h, VarianceKernel{f.guides(), {accumulated.rgb(), accumulated.plane(3)},
                                               moments.plane(0), moments.plane(1),
                                               history.plane(0), {exact.rgb(), exact.plane(3)}, p});
      test::StageRunner gpu(test::kCudaFast);
      gpu.run(VarianceEstimate<SvgfFast, NormalPowerFixed<7>>{
                  gpu.packed_guides(f), gpu.illum_var(std::as_const(accumulated)),
                  gpu.plane(std::as_const(moments), 0), gpu.plane(std::as_const(moments), 1),
                  gpu.plane(std::as_const(history)), gpu.packed(fast), p},
              w, h, "fast variance");
      worst_variance = std::max(worst_variance,
                                worst_relative(fast.data(), exact.data(), label("fast variance", s, {})));
    }
  }
  std::printf("fast stages vs exact, worst relative difference: atrous %.3g, variance %.3g "
              "(tolerance %.0e)\n", worst_atrous, worst_variance, test::kFastTolerance);
}

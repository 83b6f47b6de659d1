// bench/stage_cost.cpp's plane counts checked against the kernels: each exact-mode SVGF stage
// functor, the JBF's pass, the wavelet's a-trous pass and BMFR's stages runs on a small
// steady-state frame (a surface everywhere, history old enough, the four bilinear reprojection
// taps passing) whose every plane is its own buffer. A plane is read when changing it changes the
// output at a probe pixel, and written when the kernel overwrites the canary there (BMFR's
// per-block values: counted a value at a time). Operation counts are not checked (they stay
// hand-counted), nor fast mode (its arithmetic exists only under nvcc).
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <deque>
#include <functional>
#include <string>
#include <type_traits>
#include <vector>

#include "bench/stage_cost.h"
#include "core/copy.h"
#include "core/normal_weight.h"
#include "kernels_cpu/cpu_block.h"
#include "methods/bmfr/accumulate.h"
#include "methods/bmfr/denoiser.h"
#include "methods/bmfr/post.h"
#include "methods/bmfr/regression.h"
#include "methods/bmfr/weighted_sum.h"
#include "methods/jbf/filter.h"
#include "methods/svgf/atrous.h"
#include "methods/svgf/demodulate.h"
#include "methods/svgf/flavors.h"
#include "methods/svgf/remodulate.h"
#include "methods/svgf/reproject.h"
#include "methods/svgf/variance.h"
#include "methods/wavelet/atrous.h"

using namespace svgf;
using bench::Stage;

namespace {

constexpr int kW = 40, kH = 40;  // room for the widest a-trous footprint (step 8) at the probes
struct Pixel {
  int x, y;
};
// Surface probes: at A the depth tolerance of the reprojection taps needs |depth_dx|, at B
// |depth_dy| (the tolerance takes the larger), so each derivative changes some output.
const std::vector<Pixel> kSurface = {{20, 20}, {23, 17}};
const std::vector<Pixel> kBackground = {{10, 30}};

// Deterministic noise in [0, 1) per pixel and plane.
float noise(int x, int y, uint32_t salt) {
  uint32_t h = static_cast<uint32_t>(x) * 73856093u ^ static_cast<uint32_t>(y) * 19349663u ^
               salt * 83492791u;
  h ^= h >> 13;
  h *= 0x5bd1e995u;
  h ^= h >> 15;
  return static_cast<float>(h & 0xffffffu) / 16777216.f;
}

bool is_background(int x, int y) {
  for (const Pixel& p : kBackground)
    if (p.x == x && p.y == y) return true;
  return false;
}
float surface_depth(int x, int y) {
  return is_background(x, y) ? 0.f : 5.f + 0.01f * x + 0.01f * y + 0.01f * noise(x, y, 1);
}

// Planes, each its own buffer: inputs the kernel may read, outputs it may write.
class Rig {
 public:
  float* input(const std::string& name, const std::function<float(int, int)>& fill) {
    Plane& p = add(inputs_, name);
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) p.f[y * kW + x] = fill(x, y);
    return p.f.data();
  }
  float* input(const std::string& name, float lo, float hi) {
    const uint32_t salt = static_cast<uint32_t>(std::hash<std::string>()(name));
    return input(name, [&](int x, int y) { return lo + (hi - lo) * noise(x, y, salt); });
  }
  ConstRgbView input_rgb(const std::string& name, float lo, float hi) {
    return {input(name + ".r", lo, hi), input(name + ".g", lo, hi), input(name + ".b", lo, hi)};
  }
  uint32_t* ids(const std::string& name, uint32_t value) {
    Plane& p = add(inputs_, name);
    p.id.assign(p.f.size(), value);
    return p.id.data();
  }
  float* output(const std::string& name) { return add(outputs_, name).f.data(); }
  RgbView output_rgb(const std::string& name) {
    return {output(name + ".r"), output(name + ".g"), output(name + ".b")};
  }
  float& at(float* plane, int x, int y) { return plane[y * kW + x]; }

  // The inputs whose change changes the kernel's output at `probes`.
  template <class Kernel>
  std::vector<std::string> read(const Kernel& k, const std::vector<Pixel>& probes) {
    const std::vector<uint32_t> before = run(k, probes);
    std::vector<std::string> names;
    for (Plane& p : inputs_) {
      const Plane saved = p;
      bool changed = false;
      for (int how = 0; how < kPerturbations && !changed; ++how) {
        perturb(p, how);
        changed = run(k, probes) != before;
        p = saved;
      }
      if (changed) names.push_back(p.name);
    }
    return names;
  }

  // How many of the outputs' values at `probes` the kernel stores into.
  template <class Kernel>
  int stores(const Kernel& k, const std::vector<Pixel>& probes) {
    int n = 0;
    for (uint32_t b : run(k, probes)) n += b != kCanary;
    return n;
  }

  // The outputs the kernel stores into at `probes`.
  template <class Kernel>
  std::vector<std::string> written(const Kernel& k, const std::vector<Pixel>& probes) {
    const std::vector<uint32_t> after = run(k, probes);
    std::vector<std::string> names;
    for (size_t o = 0; o < outputs_.size(); ++o)
      for (size_t q = 0; q < probes.size(); ++q)
        if (after[o * probes.size() + q] != kCanary) {
          names.push_back(outputs_[o].name);
          break;
        }
    return names;
  }

 private:
  static constexpr uint32_t kCanary = 0x7fc0deadu;  // a NaN no kernel computes
  struct Plane {
    std::string name;
    std::vector<float> f = std::vector<float>(kW * kH);
    std::vector<uint32_t> id;  // mesh ids instead of floats
  };

  static Plane& add(std::deque<Plane>& planes, const std::string& name) {
    planes.emplace_back();
    planes.back().name = name;
    return planes.back();
  }

  // Kinds of change, so that a plane read only through a test or a max still shows: scaled,
  // zero, random, negated, and the plane moved by one pixel (which makes a background probe a
  // surface like its neighbours, so that the filters take the path that shows the change).
  static constexpr int kPerturbations = 5;
  static void perturb(Plane& p, int how) {
    const size_t n = p.f.size();
    if (how == 4) {
      std::rotate(p.f.begin(), p.f.begin() + 1, p.f.end());
      if (!p.id.empty()) std::rotate(p.id.begin(), p.id.begin() + 1, p.id.end());
      return;
    }
    for (size_t i = 0; i < n; ++i) {
      const float r = noise(static_cast<int>(i), how, 99);
      if (!p.id.empty()) {
        const uint32_t v = p.id[i];
        p.id[i] = how == 0 ? v + 1 : how == 1 ? 0 : how == 2 ? static_cast<uint32_t>(r * 1e6f) : ~v;
        continue;
      }
      const float v = p.f[i];
      p.f[i] = how == 0 ? v * 1.5f + 0.25f : how == 1 ? 0.f : how == 2 ? 20.f * r - 10.f : -v;
    }
  }

  // Every output's bits at the probes after running the kernel there over canaries.
  template <class Kernel>
  std::vector<uint32_t> run(const Kernel& k, const std::vector<Pixel>& probes) {
    float canary;
    std::memcpy(&canary, &kCanary, sizeof canary);
    for (Plane& o : outputs_) std::fill(o.f.begin(), o.f.end(), canary);
    for (const Pixel& p : probes) k(p.x, p.y);
    std::vector<uint32_t> bits;
    for (const Plane& o : outputs_)
      for (const Pixel& p : probes) {
        uint32_t b;
        std::memcpy(&b, &o.f[p.y * kW + p.x], sizeof b);
        bits.push_back(b);
      }
    return bits;
  }

  std::deque<Plane> inputs_, outputs_;  // a deque keeps the planes where they are
};

// A frame's guides, every plane separate. `prev`: the previous frame's, whose depth at the
// surface probes' four reprojection taps passes only with the probe's larger depth derivative.
GuideView guides(Rig& rig, const std::string& name, bool prev) {
  float* depth = rig.input(name + ".depth", surface_depth);
  float* depth_dx = rig.input(name + ".depth_dx", 0.004f, 0.006f);
  float* depth_dy = rig.input(name + ".depth_dy", 0.004f, 0.006f);
  for (size_t k = 0; k < kSurface.size(); ++k) {
    const Pixel p = kSurface[k];
    // Tolerance 10 |d| + 0.03 z with z about 5.4: 0.36 with the larger derivative (0.02),
    // 0.17 with the smaller (0.001); the previous frame's taps lie 0.25 deeper.
    rig.at(k == 0 ? depth_dx : depth_dy, p.x, p.y) = 0.02f;
    rig.at(k == 0 ? depth_dy : depth_dx, p.x, p.y) = 0.001f;
    if (!prev) continue;
    const int x0 = p.x, y0 = p.y - 1;  // floor of (x + motion_x, y + motion_y)
    for (int t = 0; t < 4; ++t)
      rig.at(depth, x0 + (t & 1), y0 + (t >> 1)) = surface_depth(p.x, p.y) + 0.25f;
  }
  const auto normal = [](int x, int y, int c) {
    const float v[3] = {0.1f * noise(x, y, 2), 0.1f * noise(x, y, 3), 1.f};
    return v[c] / std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  };
  GuideView g;
  g.width = kW;
  g.height = kH;
  g.depth = depth;
  g.depth_dx = depth_dx;
  g.depth_dy = depth_dy;
  g.normal = {rig.input(name + ".normal.x", [&](int x, int y) { return normal(x, y, 0); }),
              rig.input(name + ".normal.y", [&](int x, int y) { return normal(x, y, 1); }),
              rig.input(name + ".normal.z", [&](int x, int y) { return normal(x, y, 2); })};
  g.mesh_id = rig.ids(name + ".mesh_id", 7);
  g.motion_x = rig.input(name + ".motion_x", 0.3f, 0.4f);
  g.motion_y = rig.input(name + ".motion_y", -0.5f, -0.4f);
  return g;
}

IllumVarView output_illum_var(Rig& rig, const std::string& name) {
  return {rig.output_rgb(name), rig.output(name + ".variance")};
}
ConstIllumVarView input_illum_var(Rig& rig, const std::string& name) {
  return {rig.input_rgb(name, 0.2f, 2.f), rig.input(name + ".variance", 0.01f, 0.1f)};
}

// The counts of `stage` the model gives a pixel, in planes of 4 bytes; per iteration for the
// a-trous.
struct Planes {
  double read, written;
};
Planes model(Stage stage, bool emission, bool surface) {
  const SvgfParams p;
  const bench::StageCost c =
      bench::stage_cost(Mode::Exact, stage, p, emission, surface ? 1.0 : 0.0);
  const double per = stage == Stage::Atrous ? 4.0 * p.iterations : 4.0;
  return {c.read / per, c.written / per};
}

// The planes `k` reads and writes at the surface or background probes against the model's `m`.
template <class Kernel>
void require_planes(Rig& rig, const Kernel& k, const std::string& what, bool surface,
                    const Planes& m) {
  const std::vector<Pixel>& probes = surface ? kSurface : kBackground;
  const std::vector<std::string> read = rig.read(k, probes);
  const std::vector<std::string> written = rig.written(k, probes);
  std::string r, w;
  for (const std::string& n : read) r += n + " ";
  for (const std::string& n : written) w += n + " ";
  INFO(what << (surface ? ", surface" : ", background") << ": read " << r << "; written " << w);
  CHECK(static_cast<double>(read.size()) == m.read);
  CHECK(static_cast<double>(written.size()) == m.written);
}

template <class Kernel>
void require_model(Rig& rig, const Kernel& k, Stage stage, bool emission, bool surface) {
  require_planes(rig, k, std::string(bench::stage_name(stage)) + (emission ? ", emission" : ""),
                 surface, model(stage, emission, surface));
}

// A filter stage's count in planes of one pass.
Planes per_pass(const bench::StageCost& c, int passes) {
  return {c.read / (4.0 * passes), c.written / (4.0 * passes)};
}

}  // namespace

TEST_CASE("stage cost: demodulate's planes are the kernel's", "[bench][stage_cost]") {
  for (bool emission : {false, true}) {
    Rig rig;
    const DemodulateKernel k{kW, rig.input_rgb("color", 0.5f, 2.f),
                             rig.input_rgb("albedo", 0.2f, 0.9f),
                             emission ? rig.input_rgb("emission", 0.f, 0.2f) : ConstRgbView(),
                             rig.output_rgb("illumination")};
    require_model(rig, k, Stage::Demodulate, emission, true);
  }
}

TEST_CASE("stage cost: reproject's planes are the kernel's", "[bench][stage_cost]") {
  Rig rig;
  ReprojectKernel k;
  k.guides = guides(rig, "guides", false);
  k.prev_guides = guides(rig, "prev_guides", true);
  k.illumination = rig.input_rgb("illumination", 0.1f, 2.f);
  k.prev_color = rig.input_rgb("prev_color", 0.1f, 2.f);
  k.prev_moment1 = rig.input("prev_moment1", 0.5f, 1.5f);
  k.prev_moment2 = rig.input("prev_moment2", 2.5f, 3.f);
  k.prev_history = rig.input("prev_history", [](int, int) { return 10.f; });
  k.has_history = true;
  k.accumulated = output_illum_var(rig, "accumulated");
  k.moment1 = rig.output("moment1");
  k.moment2 = rig.output("moment2");
  k.history = rig.output("history");
  require_model(rig, k, Stage::Reproject, false, true);
  require_model(rig, k, Stage::Reproject, false, false);
}

// Variance and a-trous run as the pipeline runs them, with the normal weight's power chosen
// from the parameters.
template <class Body>
void with_power(const Body& body) {
  SvgfExact::with_normal_power(SvgfParams().phi_normal, body);
}

TEST_CASE("stage cost: the variance estimate's planes are the kernel's", "[bench][stage_cost]") {
  // Only surface pixels: on a background pixel the history length and depth choose between two
  // branches that both pass the accumulation through, which no change of theirs can show.
  with_power([](const auto& power) {
    using Power = std::decay_t<decltype(power)>;
    Rig rig;
    const VarianceEstimate<SvgfExact, Power> k{guides(rig, "guides", false),
                                               input_illum_var(rig, "accumulated"),
                                               rig.input("moment1", 0.5f, 1.5f),
                                               rig.input("moment2", 2.5f, 3.f),
                                               rig.input("history", [](int, int) { return 10.f; }),
                                               output_illum_var(rig, "filtered"),
                                               SvgfParams()};
    require_model(rig, k, Stage::Variance, false, true);
  });
}

TEST_CASE("stage cost: an a-trous iteration's planes are the kernel's", "[bench][stage_cost]") {
  with_power([](const auto& power) {
    using Power = std::decay_t<decltype(power)>;
    for (int step = 1; step < (1 << SvgfParams().iterations); step *= 2) {
      CAPTURE(step);
      Rig rig;
      const AtrousIteration<SvgfExact, Power> k{guides(rig, "guides", false),
                                                input_illum_var(rig, "in"),
                                                output_illum_var(rig, "out"), step, SvgfParams()};
      require_model(rig, k, Stage::Atrous, false, true);
      require_model(rig, k, Stage::Atrous, false, false);
    }
  });
}

TEST_CASE("stage cost: the feedback copy's planes are the kernel's", "[bench][stage_cost]") {
  Rig rig;
  const CopyRgbKernel k{kW, rig.input_rgb("filtered", 0.1f, 2.f), rig.output_rgb("next_color")};
  require_model(rig, k, Stage::Feedback, false, true);
}

TEST_CASE("stage cost: remodulate's planes are the kernel's", "[bench][stage_cost]") {
  for (bool emission : {false, true}) {
    Rig rig;
    const RemodulateSink sink{rig.input_rgb("albedo", 0.2f, 0.9f),
                              emission ? rig.input_rgb("emission", 0.f, 0.2f) : ConstRgbView(),
                              rig.output_rgb("output")};
    const ForwardKernel<ConstIllumVarView, RemodulateSink> k{kW, input_illum_var(rig, "filtered"),
                                                             sink};
    require_model(rig, k, Stage::Remodulate, emission, true);
  }
}

TEST_CASE("stage cost: a JBF pass's planes are the kernel's", "[bench][stage_cost][jbf]") {
  // Positions on a gently tilted plane, normals near +z: every weight term stays far from 0.
  const auto position = [](int c) {
    return [c](int x, int y) {
      const float v[3] = {0.01f * x, 0.01f * y, 5.f + 0.002f * noise(x, y, 4)};
      return v[c];
    };
  };
  for (int levels : {0, 3}) {  // the full window; the a-trous form at steps 1, 2, 4
    JbfParams p;
    p.levels = levels;
    for (int level = 0; level < std::max(levels, 1); ++level) {
      CAPTURE(levels, level);
      Rig rig;
      JbfPass<ExactArith> k;
      k.guides = guides(rig, "guides", false);
      k.position = {rig.input("position.x", position(0)), rig.input("position.y", position(1)),
                    rig.input("position.z", position(2))};
      k.in = rig.input_rgb("in", 0.2f, 1.f);
      k.out = rig.output_rgb("out");
      k.radius = p.atrous() ? 2 : p.radius;
      k.step = 1 << level;
      k.b3 = p.atrous();
      k.scales = JbfScales::of(p);
      for (bool surface : {true, false})
        require_planes(rig, k, levels ? "jbf a-trous" : "jbf full window", surface,
                       per_pass(bench::jbf_filter_cost(Mode::Exact, p, surface ? 1.0 : 0.0),
                                std::max(levels, 1)));
    }
  }
}

TEST_CASE("stage cost: a wavelet a-trous pass's planes are the kernel's",
          "[bench][stage_cost][wavelet]") {
  for (int size : {3, 5, 7, 9}) {
    WaveletParams p;
    p.kernel_size = size;
    for (int step : {1, 4}) {
      CAPTURE(size, step);
      Rig rig;
      WaveletIteration<ExactArith, NormalPower<>> k;
      k.guides = guides(rig, "guides", false);
      k.in = rig.input_rgb("in", 0.2f, 1.f);
      k.out = rig.output_rgb("out");
      k.luma = rig.input("luma", 0.2f, 1.f);
      k.deviation = rig.input("deviation", 0.1f, 0.5f);
      k.step = step;
      k.kernel_size = size;
      k.inv_sigma_depth = 1.f / (p.sigma_depth + p.epsilon);
      k.sigma_luma = p.sigma_luma;
      k.epsilon = p.epsilon;
      k.normal_power = NormalPower<>::of(p.sigma_normal);
      for (bool surface : {true, false})
        require_planes(rig, k, "wavelet a-trous", surface,
                       per_pass(bench::wavelet_atrous_cost(Mode::Exact, p, surface ? 1.0 : 0.0),
                                p.iterations));
    }
  }
}

TEST_CASE("stage cost: the filters' tap counts follow their footprints", "[bench][stage_cost]") {
  JbfParams jbf;
  CHECK(bench::jbf_filter_cost(Mode::Exact, jbf, 1.0).taps == 33 * 33 - 1);
  CHECK(bench::jbf_filter_cost(Mode::Exact, jbf, 0.5).taps == (33 * 33 - 1) / 2.0);
  jbf.levels = 4;
  CHECK(bench::jbf_filter_cost(Mode::Fast, jbf, 1.0).taps == 4 * 24);
  WaveletParams wavelet;
  wavelet.kernel_size = 9;
  CHECK(bench::wavelet_atrous_cost(Mode::Exact, wavelet, 1.0).taps == 4 * 80);
  CHECK(bench::stage_cost(Mode::Exact, Stage::Atrous, SvgfParams(), false, 1.0).taps == 4 * 24);
  // Fast mode does fewer operations a tap than exact mode, never more.
  CHECK(bench::jbf_filter_cost(Mode::Fast, jbf, 1.0).ops <
        bench::jbf_filter_cost(Mode::Exact, jbf, 1.0).ops);
  CHECK(bench::wavelet_atrous_cost(Mode::Fast, wavelet, 1.0).ops <
        bench::wavelet_atrous_cost(Mode::Exact, wavelet, 1.0).ops);
  // Only the filter stage of another method is counted, and no frame floor exists for it.
  DenoiserConfig d;
  d.method = Method::JbfAtrous;
  d.jbf.levels = 4;
  CHECK(bench::method_stage_cost(d, "atrous", false, 1.0, kW, kH).has_value());
  CHECK_FALSE(bench::method_stage_cost(d, "temporal", false, 1.0, kW, kH).has_value());
  CHECK_FALSE(bench::frame_is_costed(Method::JbfAtrous));
  d.method = Method::Jbf;
  CHECK(bench::method_stage_cost(d, "filter", false, 1.0, kW, kH)->taps == 33 * 33 - 1);
  d.method = Method::Gaussian;
  CHECK_FALSE(bench::method_stage_cost(d, "blur_x", false, 1.0, kW, kH).has_value());
}

// --- BMFR ---------------------------------------------------------------------------------

namespace {

// Positions on a gently tilted plane (|p - p'|^2 well under the 0.01 limit between neighbours'
// histories), normals near +z.
float bmfr_position(int x, int y, int c) {
  const float v[3] = {0.02f * x, 0.02f * y, 1.f + 0.01f * noise(x, y, 4)};
  return v[c];
}
ConstRgbView positions(Rig& rig, const std::string& name, float jitter) {
  auto plane = [&](int c) {
    return rig.input(name + "." + "xyz"[c], [c, jitter](int x, int y) {
      return bmfr_position(x, y, c) + jitter * noise(x, y, 5 + c);
    });
  };
  return {plane(0), plane(1), plane(2)};
}

// The model's count of BMFR stage `name` on the rig's frame size, in planes of 4 bytes.
bench::StageCost bmfr_model(const std::string& name, bool emission, bool surface,
                            BmfrRankStrategy strategy = BmfrRankStrategy::Noise) {
  BmfrParams p;
  p.rank_strategy = strategy;
  return *bench::bmfr_stage_cost(Mode::Exact, p, name, emission, surface ? 1.0 : 0.0, kW, kH);
}
Planes in_planes(const bench::StageCost& c) { return {c.read / 4.0, c.written / 4.0}; }

}  // namespace

TEST_CASE("stage cost: BMFR's accumulate planes are the kernel's", "[bench][stage_cost][bmfr]") {
  for (bool emission : {false, true}) {
    Rig rig;
    BmfrAccumulate k;
    k.guides = guides(rig, "guides", false);
    k.position = positions(rig, "position", 0.f);
    k.color = rig.input_rgb("color", 0.5f, 2.f);
    k.albedo = rig.input_rgb("albedo", 0.2f, 0.9f);
    k.emission = emission ? rig.input_rgb("emission", 0.f, 0.2f) : ConstRgbView();
    // The previous frame's samples at the taps, close to this frame's surface: all four taps
    // are accepted.
    k.prev_position = positions(rig, "prev_position", 0.01f);
    k.prev_normal = {rig.input("prev_normal.x", 0.f, 0.05f), rig.input("prev_normal.y", 0.f, 0.05f),
                     rig.input("prev_normal.z", 0.99f, 1.f)};
    k.prev_noisy = rig.input_rgb("prev_noisy", 0.2f, 2.f);
    k.prev_length = rig.input("prev_length", [](int, int) { return 10.f; });
    k.position_out = rig.output_rgb("position_out");
    k.normal_out = rig.output_rgb("normal_out");
    k.noisy = rig.output_rgb("noisy");
    k.length = rig.output("length");
    k.reprojection = {rig.output("prev_x"), rig.output("prev_y"), rig.output("accept")};
    k.has_history = true;
    for (bool surface : {true, false})
      require_planes(rig, k, std::string("bmfr accumulate") + (emission ? ", emission" : ""),
                     surface, in_planes(bmfr_model(bmfr_stage::kAccumulate, emission, surface)));
  }
}

TEST_CASE("stage cost: BMFR's post-accumulation planes are the kernel's",
          "[bench][stage_cost][bmfr]") {
  for (bool emission : {false, true}) {
    Rig rig;
    BmfrPostAccumulate k;
    k.width = kW;
    k.height = kH;
    k.filtered = rig.input_rgb("filtered", 0.2f, 2.f);
    // All four taps accepted, except at the background probe (no history there).
    float* prev_x = rig.input("prev_x", [](int x, int) { return x + 0.35f; });
    float* prev_y = rig.input("prev_y", [](int, int y) { return y - 0.45f; });
    float* accept =
        rig.input("accept", [](int x, int y) { return is_background(x, y) ? 0.f : 15.f; });
    k.reprojection = {prev_x, prev_y, accept};
    // Short histories: 1 / n is above the post blend's floor, so the length shows.
    k.length = rig.input("length", 4.f, 6.f);
    k.prev_accumulated = rig.input_rgb("prev_accumulated", 0.2f, 2.f);
    k.accumulated = rig.output_rgb("accumulated");
    k.albedo = rig.input_rgb("albedo", 0.2f, 0.9f);
    k.emission = emission ? rig.input_rgb("emission", 0.f, 0.2f) : ConstRgbView();
    k.output = rig.output_rgb("output");
    k.has_history = true;
    for (bool surface : {true, false})
      require_planes(rig, k, std::string("bmfr post") + (emission ? ", emission" : ""), surface,
                     in_planes(bmfr_model(bmfr_stage::kPost, emission, surface)));
  }
}

TEST_CASE("stage cost: BMFR's weighted sum reads its pixel's planes and its block's values",
          "[bench][stage_cost][bmfr]") {
  Rig rig;
  const BmfrGrid grid = BmfrGrid::of(kW, kH, 0);
  // Per block: positive weights (so the clamp at 0 hides nothing), ranges [-1, 2] (scaled by
  // their width 3), rank 10.
  float* blocks = rig.input("blocks", [](int x, int y) {
    const int k = (y * kW + x) % BmfrBlockData::kFloats;
    if (k < BmfrBlockData::kWeights) return 0.1f + noise(x, y, 6);
    if (k < BmfrBlockData::kWeights + BmfrBlockData::kRanges) return k % 2 ? 2.f : -1.f;
    return k == BmfrBlockData::kFloats - 2 ? 10.f : 50.f;  // rank, condition
  });
  REQUIRE(grid.blocks() * BmfrBlockData::kFloats <= kW * kH);
  BmfrWeightedSum<ExactArith> k{grid,
                                guides(rig, "guides", false),
                                positions(rig, "position", 0.f),
                                rig.input_rgb("noisy", 0.2f, 2.f),
                                BmfrBlockData{blocks},
                                rig.output_rgb("filtered")};
  for (bool surface : {true, false}) {
    const std::vector<Pixel>& probes = surface ? kSurface : kBackground;
    // The values of its block the first probe reads, one value at a time (zeroed, negated or
    // scaled: the rank shows only when zeroed).
    const Pixel p = probes.front();
    const int j = p.y * kW + p.x;
    const auto output = [&] {
      k(p.x, p.y);
      return std::vector<float>{k.filtered.r[j], k.filtered.g[j], k.filtered.b[j]};
    };
    const int b = grid.block_of(p.x, p.y);
    int block_values = 0;
    for (int v = 0; v < BmfrBlockData::kFloats; ++v) {
      float& value = blocks[b * BmfrBlockData::kFloats + v];
      const float saved = value;
      const std::vector<float> before = output();
      bool changed = false;
      for (float changed_to : {saved * 1.5f + 0.25f, 0.f, -saved}) {
        value = changed_to;
        changed = changed || output() != before;
      }
      value = saved;
      block_values += changed;
    }
    // The pixel's own planes (the block values' plane left out).
    std::vector<std::string> read = rig.read(k, probes);
    read.erase(std::remove(read.begin(), read.end(), "blocks"), read.end());
    const std::vector<std::string> written = rig.written(k, probes);
    std::string r;
    for (const std::string& n : read) r += n + " ";
    INFO("bmfr weighted sum, " << (surface ? "surface" : "background") << ": read " << r << "and "
                               << block_values << " values of its block");
    // A block's values are read once for all its pixels: the model counts them times the
    // blocks per pixel.
    const bench::StageCost m = bmfr_model(bmfr_stage::kWeightedSum, false, surface);
    CHECK(m.read / 4.0 ==
          Approx(read.size() + block_values * bench::bmfr_blocks_per_px(kW, kH)));
    CHECK(static_cast<double>(written.size()) == m.written / 4.0);
  }
}

namespace {

// BMFR's regression over the first `blocks` blocks of a frame's grid, run by the CPU's block
// context once per probe sweep (at the first probe): the Rig sees the block values it stores.
struct RegressionSweep {
  const BmfrFit<ExactArith>& fit;
  int blocks;
  Pixel first;
  void operator()(int x, int y) const {
    if (x != first.x || y != first.y) return;
    std::vector<float> scratch(BmfrFit<ExactArith>::kScratchFloats);
    for (int b = 0; b < blocks; ++b) fit(cpu::CpuBlock(scratch.data()), b);
  }
};

// The probes over the first `values` values of a per-block plane.
std::vector<Pixel> value_probes(int values) {
  std::vector<Pixel> v;
  for (int i = 0; i < values; ++i) v.push_back({i % kW, i / kW});
  return v;
}

}  // namespace

TEST_CASE("stage cost: BMFR's regression reads a row's planes and stores a block's values",
          "[bench][stage_cost][bmfr]") {
  for (BmfrRankStrategy strategy : {BmfrRankStrategy::Noise, BmfrRankStrategy::Skip}) {
    CAPTURE(to_string(strategy));
    Rig rig;
    BmfrFit<ExactArith> fit;
    fit.grid = BmfrGrid::of(kW, kH, 0);
    fit.guides = guides(rig, "guides", false);
    fit.position = positions(rig, "position", 0.f);
    fit.noisy = rig.input_rgb("noisy", 0.2f, 2.f);
    fit.length = rig.input("length", [](int, int) { return 10.f; });
    fit.out = BmfrBlockData{rig.output("blocks")};
    fit.strategy = strategy;
    REQUIRE(fit.grid.blocks() * BmfrBlockData::kFloats <= kW * kH);
    const bench::StageCost m =
        bmfr_model(bmfr_stage::kRegression, false, true, strategy);
    const double blocks_per_px = bench::bmfr_blocks_per_px(kW, kH);

    // One block's values depend on the planes of its rows.
    const std::vector<Pixel> first_block = value_probes(BmfrBlockData::kFloats);
    const std::vector<std::string> read =
        rig.read(RegressionSweep{fit, 1, first_block.front()}, first_block);
    std::string r;
    for (const std::string& n : read) r += n + " ";
    INFO("bmfr regression: read " << r);
    CHECK(static_cast<double>(read.size()) ==
          Approx(m.read / 4.0 / (blocks_per_px * block::kRows)));

    // Every block stores all its values (weights of skipped columns too).
    const int blocks = fit.grid.blocks();
    const std::vector<Pixel> all = value_probes(blocks * BmfrBlockData::kFloats);
    const int stored = rig.stores(RegressionSweep{fit, blocks, all.front()}, all);
    CHECK(static_cast<double>(stored) / blocks == Approx(m.written / 4.0 / blocks_per_px));
  }
}

TEST_CASE("stage cost: BMFR is counted in every stage, its regression a row of its blocks",
          "[bench][stage_cost][bmfr]") {
  DenoiserConfig d;
  d.method = Method::Bmfr;
  CHECK(bench::frame_is_costed(Method::Bmfr));
  for (const char* stage : {kSanitizeStage, bmfr_stage::kAccumulate, bmfr_stage::kRegression,
                            bmfr_stage::kWeightedSum, bmfr_stage::kPost, kUploadStage})
    CHECK(bench::method_stage_cost(d, stage, false, 1.0, 1920, 1080).has_value());
  CHECK_FALSE(bench::method_stage_cost(d, "atrous", false, 1.0, 1920, 1080).has_value());
  // The grid sticks out of the image: at 1080p 61 x 34.75 blocks (the mean over the offsets) of
  // 1024 rows, 4.7% more rows than pixels.
  CHECK(bench::bmfr_blocks_per_px(1920, 1080) * block::kRows ==
        Approx(61 * 34.75 * 1024 / (1920.0 * 1080)));
  // Sanitize reads the world positions besides SVGF's planes.
  CHECK(bench::method_stage_cost(d, kSanitizeStage, false, 1.0, 1920, 1080)->read ==
        bench::stage_cost(Mode::Exact, Stage::Sanitize, SvgfParams(), false, 1.0).read + 12);
  // Fast mode's FMA make the regression and the weighted sum cheaper, the noise costs skip
  // nothing, and background rows skip the scaling.
  auto ops = [&](Mode mode, BmfrRankStrategy s, const char* stage, double surface) {
    d.mode = mode;
    d.bmfr.rank_strategy = s;
    return bench::method_stage_cost(d, stage, false, surface, 1920, 1080)->ops;
  };
  const auto noise = BmfrRankStrategy::Noise, skip = BmfrRankStrategy::Skip;
  CHECK(ops(Mode::Fast, noise, bmfr_stage::kRegression, 1) <
        ops(Mode::Exact, noise, bmfr_stage::kRegression, 1));
  CHECK(ops(Mode::Fast, noise, bmfr_stage::kWeightedSum, 1) <
        ops(Mode::Exact, noise, bmfr_stage::kWeightedSum, 1));
  CHECK(ops(Mode::Exact, skip, bmfr_stage::kRegression, 1) <
        ops(Mode::Exact, noise, bmfr_stage::kRegression, 1));
  CHECK(ops(Mode::Exact, noise, bmfr_stage::kRegression, 0) <
        ops(Mode::Exact, noise, bmfr_stage::kRegression, 1));
  CHECK(ops(Mode::Fast, noise, bmfr_stage::kAccumulate, 1) ==
        ops(Mode::Exact, noise, bmfr_stage::kAccumulate, 1));
}

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
#include <tuple>
#include <type_traits>
#include <vector>

#include "bench/stage_cost.h"
#include "core/taa.h"
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
#include "methods/svgf/gradient.h"
#include "methods/svgf/split_sum.h"
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

  // How many input values (a plane at a pixel), each changed alone, change the output at
  // `probes`: what a kernel reads where it reads a plane at some pixels only.
  template <class Kernel>
  int values_read(const Kernel& k, const std::vector<Pixel>& probes) {
    const std::vector<uint32_t> before = run(k, probes);
    int n = 0;
    for (Plane& p : inputs_)
      for (size_t i = 0; i < p.f.size(); ++i) {
        const float v = p.f[i];
        bool changed = false;
        for (float to : {v * 1.5f + 0.25f, 0.f, -v, 1.f - v}) {
          p.f[i] = to;
          changed = changed || run(k, probes) != before;
        }
        p.f[i] = v;
        n += changed;
      }
    return n;
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

// Frames of width x height without emission or gradient samples, `surface` of them surface.
bench::FrameTraits frames(double surface, int width, int height) {
  bench::FrameTraits f;
  f.surface_fraction = surface;
  f.width = width;
  f.height = height;
  return f;
}

// The counts of `stage` the model gives a pixel, in planes of 4 bytes; per iteration for the
// a-trous.
struct Planes {
  double read, written;
};
// The defaults without their anti-lag, whose reads the reprojection's own anti-lag case checks.
SvgfParams without_antilag() {
  SvgfParams p;
  p.antilag = Antilag::Off;
  return p;
}

Planes model(Stage stage, bool emission, bool surface) {
  const SvgfParams p = without_antilag();
  const bench::StageCost c =
      bench::stage_cost(Mode::Exact, stage, p, emission, surface ? 1.0 : 0.0);
  const double per = stage == Stage::Atrous ? 4.0 * p.iterations : 4.0;
  return {c.read / per, c.written / per};
}

// The planes `k` reads and writes at the surface or background probes against the model's `m`.
template <class Kernel>
void require_planes_at(Rig& rig, const Kernel& k, const std::string& what,
                       const std::vector<Pixel>& probes, const Planes& m) {
  const std::vector<std::string> read = rig.read(k, probes);
  const std::vector<std::string> written = rig.written(k, probes);
  std::string r, w;
  for (const std::string& n : read) r += n + " ";
  for (const std::string& n : written) w += n + " ";
  INFO(what << ": read " << r << "; written " << w);
  // Approx: per-stratum counts come back from bytes a pixel through the strata a pixel.
  CHECK(static_cast<double>(read.size()) == Approx(m.read));
  CHECK(static_cast<double>(written.size()) == Approx(m.written));
}
template <class Kernel>
void require_planes(Rig& rig, const Kernel& k, const std::string& what, bool surface,
                    const Planes& m) {
  require_planes_at(rig, k, what + (surface ? ", surface" : ", background"),
                    surface ? kSurface : kBackground, m);
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
  k.params = without_antilag();
  require_model(rig, k, Stage::Reproject, false, true);
  require_model(rig, k, Stage::Reproject, false, false);
}

// Variance and a-trous run as the pipeline runs them, with the normal weight's power chosen
// from the parameters.
template <class Body>
void with_power(const Body& body) {
  SvgfExact::with_normal_power(SvgfParams().phi_normal, body);
}

// The variance stage's kernel over the rig's planes, every pixel's history `history` frames old.
template <class Power>
VarianceEstimate<SvgfExact, Power> variance_kernel(Rig& rig, float history) {
  return {guides(rig, "guides", false),
          input_illum_var(rig, "accumulated"),
          rig.input("moment1", 0.5f, 1.5f),
          rig.input("moment2", 2.5f, 3.f),
          rig.input("history", [history](int, int) { return history; }),
          output_illum_var(rig, "filtered"),
          SvgfParams()};
}

TEST_CASE("stage cost: the variance estimate's planes are the kernel's", "[bench][stage_cost]") {
  // Only surface pixels: on a background pixel the history length and depth choose between two
  // branches that both pass the accumulation through, which no change of theirs can show.
  with_power([](const auto& power) {
    Rig rig;
    const auto k = variance_kernel<std::decay_t<decltype(power)>>(rig, 10.f);
    require_model(rig, k, Stage::Variance, false, true);
  });
}

TEST_CASE("stage cost: the young-history variance estimate's planes are the kernel's",
          "[bench][stage_cost]") {
  // A history below spatial_variance_history: the 7x7 estimate, which the model counts for the
  // young share of the surface (FrameTraits::young_fraction), with its taps.
  with_power([](const auto& power) {
    Rig rig;
    const auto k = variance_kernel<std::decay_t<decltype(power)>>(rig, 2.f);
    for (Mode mode : {Mode::Exact, Mode::Fast}) {
      bench::FrameTraits young = frames(1.0, kW, kH);
      young.young_fraction = 1.0;
      const bench::StageCost c = bench::stage_cost(mode, Stage::Variance, SvgfParams(), young);
      CHECK(c.taps == 49);  // the default radius 3, the centre included
      require_planes(rig, k, std::string("variance, young history, ") + to_string(mode), true,
                     {c.read / 4.0, c.written / 4.0});
    }
  });
  // Between the steady state and an all-young surface, linear in the share; background pixels
  // have no history to be young.
  const SvgfParams p;
  const auto cost = [&](double surface, double young) {
    bench::FrameTraits f = frames(surface, 1280, 720);
    f.young_fraction = young;
    return bench::stage_cost(Mode::Exact, Stage::Variance, p, f);
  };
  CHECK(cost(1.0, 0.25).ops == Approx(0.75 * cost(1.0, 0.0).ops + 0.25 * cost(1.0, 1.0).ops));
  CHECK(cost(1.0, 0.25).read == Approx(0.75 * cost(1.0, 0.0).read + 0.25 * cost(1.0, 1.0).read));
  CHECK(cost(1.0, 1.0).ops > 40 * cost(1.0, 0.0).ops);
  CHECK(cost(0.0, 1.0).ops == cost(0.0, 0.0).ops);
  CHECK(cost(0.0, 1.0).taps == 0);
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
  // The copy runs where an iteration is fed back; without one the reprojection accumulates into
  // the color history and no pass copies it (methods/svgf/pipeline.h).
  SvgfParams tap = without_antilag();
  tap.feedback_tap = 1;
  const bench::StageCost c = bench::stage_cost(Mode::Exact, Stage::Feedback, tap, false, 1.0);
  Rig rig;
  const CopyRgbKernel k{kW, rig.input_rgb("filtered", 0.1f, 2.f), rig.output_rgb("next_color")};
  require_planes(rig, k, "feedback", true, {c.read / 4.0, c.written / 4.0});
  SvgfParams no_tap = tap;
  for (int t : {-1, tap.iterations}) {
    no_tap.feedback_tap = t;
    for (Mode mode : {Mode::Exact, Mode::Fast})
      CHECK(bench::stage_cost(mode, Stage::Feedback, no_tap, false, 1.0).bytes() == 0);
  }
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

// --- A-SVGF's gradient stages, the anti-lag in the reprojection, split_sum, TAA ---------------

namespace {

// Frames of the rig's size with gradient samples, under --antilag gradient (or `antilag`).
bench::FrameTraits gradient_frames(double surface) {
  bench::FrameTraits f = frames(surface, kW, kH);
  f.gradient_samples = true;
  return f;
}
SvgfParams with_antilag(Antilag antilag) {
  SvgfParams p;
  p.antilag = antilag;
  return p;
}
// The model's count of a gradient stage, in values a stratum (a step of the a-trous).
Planes per_stratum(Stage stage, bool surface) {
  const SvgfParams p = with_antilag(Antilag::Gradient);
  const bench::StageCost c = bench::stage_cost(Mode::Exact, stage, p, gradient_frames(surface));
  const double steps = stage == Stage::GradientAtrous ? p.gradient_iterations : 1;
  const double per = 4.0 * bench::strata_per_px(kW, kH) * steps;
  return {c.read / per, c.written / per};
}

// The stratum image's planes lie in rig planes with a row pitch of kW strata, so that the probe
// (sx, sy) is stratum (sx, sy). Probes stay where every tap's pixel lies in the frame.
const std::vector<Pixel> kStratumWithData = {{5, 5}};
const std::vector<Pixel> kStratumWithout = {{7, 6}};

GradientPlanes<const float> stratum_inputs(Rig& rig, bool data) {
  return {rig.input("delta", -0.3f, 0.3f), rig.input("normalizer", 0.5f, 1.f),
          rig.input("weight", [data](int, int) { return data ? 1.f : 0.f; })};
}

}  // namespace

TEST_CASE("stage cost: the gradient samples stage reads the mask and the sample of a stratum",
          "[bench][stage_cost][asvgf]") {
  for (bool data : {true, false}) {
    CAPTURE(data);
    const std::vector<Pixel>& probe = data ? kStratumWithData : kStratumWithout;
    Rig rig;
    GradientSamplesKernel k;
    k.width = kW;
    k.height = kH;
    // A sample at the last pixel of every stratum but the probe's without one: the scan reads
    // all nine mask values.
    const Pixel none = kStratumWithout.front();
    k.samples.mask = rig.input("mask", [&](int x, int y) {
      const bool stratum_without = x / 3 == none.x && y / 3 == none.y;
      return !stratum_without && x % 3 == 2 && y % 3 == 2 ? 1.f : 0.f;
    });
    k.samples.previous = rig.input("previous", 0.2f, 1.f);
    k.samples.current = rig.input("current", 0.2f, 1.f);
    k.out = {rig.output("delta"), rig.output("normalizer"), rig.output("weight")};
    k.strata_width = kW;
    k.guide_offset = rig.output("guide_offset");
    const Planes m = per_stratum(Stage::Gradient, data);
    CHECK(rig.values_read(k, probe) == Approx(m.read));
    CHECK(static_cast<double>(rig.written(k, probe).size()) == Approx(m.written));
  }
}

TEST_CASE("stage cost: a gradient a-trous step's planes are the kernel's, a stratum",
          "[bench][stage_cost][asvgf]") {
  // Strata with data only: a stratum without loads its guides before it finds no tap with data,
  // which no change of theirs can show.
  const SvgfParams p = with_antilag(Antilag::Gradient);
  for (int step = 1; step < (1 << p.gradient_iterations); step *= 2) {
    CAPTURE(step);
    Rig rig;
    GradientAtrousKernel k;
    k.guides = guides(rig, "guides", false);
    k.at = StratumGuides{kW, kW, rig.input("guide_offset", [](int x, int y) {
                           return static_cast<float>((x + 2 * y) % 9);
                         })};
    k.strata_height = kH;
    k.in = stratum_inputs(rig, true);
    k.out = {rig.output("delta_out"), rig.output("normalizer_out"), rig.output("weight_out")};
    k.step = step;
    k.phi_depth = p.gradient_phi_depth;
    k.phi_normal = p.gradient_phi_normal;
    require_planes_at(rig, k, "gradient a-trous", kStratumWithData,
                      per_stratum(Stage::GradientAtrous, true));
  }
}

TEST_CASE("stage cost: the gradient lambda stage's planes are the kernel's, a stratum",
          "[bench][stage_cost][asvgf]") {
  for (bool data : {true, false}) {
    Rig rig;
    const GradientLambdaKernel k{kW, stratum_inputs(rig, data), rig.output("lambda")};
    const std::vector<Pixel>& probe = data ? kStratumWithData : kStratumWithout;
    const std::vector<std::string> read = rig.read(k, probe);
    const Planes m = per_stratum(Stage::GradientLambda, data);
    CHECK(static_cast<double>(read.size()) == Approx(m.read));
    CHECK(static_cast<double>(rig.written(k, probe).size()) == Approx(m.written));
  }
}

TEST_CASE("stage cost: the reprojection's anti-lag reads are the kernel's",
          "[bench][stage_cost][asvgf]") {
  for (Antilag antilag : {Antilag::Statistics, Antilag::Gradient}) {
    for (bool emission : {false, true}) {
      CAPTURE(to_string(antilag), emission);
      Rig rig;
      ReprojectKernel k;
      k.guides = guides(rig, "guides", false);
      k.prev_guides = guides(rig, "prev_guides", true);
      k.illumination = rig.input_rgb("illumination", 0.1f, 2.f);
      // This frame's inputs: the statistics rule reads them, A-SVGF does not.
      k.color = rig.input_rgb("color", 0.5f, 2.f);
      k.albedo = rig.input_rgb("albedo", 0.2f, 0.9f);
      k.emission = emission ? rig.input_rgb("emission", 0.f, 0.2f) : ConstRgbView();
      k.prev_color = rig.input_rgb("prev_color", 0.1f, 2.f);
      k.prev_moment1 = rig.input("prev_moment1", 0.5f, 1.5f);
      k.prev_moment2 = rig.input("prev_moment2", 2.5f, 3.f);
      k.prev_history = rig.input("prev_history", [](int, int) { return 10.f; });
      k.has_history = true;
      // Lambda a stratum, strata_along(kW) a row.
      if (antilag == Antilag::Gradient) k.gradient_lambda = rig.input("lambda", 0.2f, 0.5f);
      k.accumulated = output_illum_var(rig, "accumulated");
      k.moment1 = rig.output("moment1");
      k.moment2 = rig.output("moment2");
      k.history = rig.output("history");
      k.params = with_antilag(antilag);
      // The statistics rule drops a share of the history at any discrepancy, so that every
      // input it reads shows in the output.
      k.params.antilag_low = 0.f;
      k.params.antilag_high = 1e3f;
      bench::FrameTraits f = gradient_frames(1.0);
      f.emission = emission;
      const bench::StageCost c = bench::stage_cost(Mode::Exact, Stage::Reproject, k.params, f);
      const std::vector<std::string> read = rig.read(k, kSurface);
      const double lambda = static_cast<double>(std::count(read.begin(), read.end(), "lambda"));
      std::string r;
      for (const std::string& n : read) r += n + " ";
      INFO("reproject: read " << r);
      CHECK(c.read / 4.0 ==
            Approx(read.size() - lambda + lambda * bench::strata_per_px(kW, kH)));
      CHECK(c.written / 4.0 == rig.written(k, kSurface).size());
      // Without history (background) neither rule looks: the model's count without anti-lag.
      CHECK(bench::stage_cost(Mode::Exact, Stage::Reproject, k.params, gradient_frames(0.0)).read ==
            bench::stage_cost(Mode::Exact, Stage::Reproject, SvgfParams(), false, 0.0).read);
    }
  }
}

namespace {

// The split frame's sum works in place: here the direct signal's output is copied into the
// output first, so the rig sees it read.
struct SplitSumInPlace {
  ConstRgbView direct;
  SplitSumKernel sum;
  void operator()(int x, int y) const {
    const int i = y * kW + x;
    sum.output.store(i, direct.load(i));
    sum(x, y);
  }
};

}  // namespace

TEST_CASE("stage cost: split_sum's and TAA's planes are the kernel's", "[bench][stage_cost]") {
  SvgfParams p;
  p.taa = true;
  bench::FrameTraits split = frames(1.0, kW, kH);
  split.split = true;
  {
    Rig rig;
    const SplitSumInPlace k{rig.input_rgb("direct", 0.f, 1.f),
                            SplitSumKernel{kW, rig.input_rgb("indirect", 0.f, 1.f),
                                           rig.output_rgb("output")}};
    const bench::StageCost c = bench::stage_cost(Mode::Exact, Stage::SplitSum, p, split);
    require_planes(rig, k, "split_sum", true, {c.read / 4.0, c.written / 4.0});
  }
  for (bool surface : {true, false}) {
    Rig rig;
    TemporalAntiAliasing k;
    k.guides = guides(rig, "guides", false);
    k.current = rig.input_rgb("current", 0.2f, 1.f);
    k.history = rig.input_rgb("history", 0.2f, 1.f);
    k.history_out = rig.output_rgb("history_out");
    k.output = rig.output_rgb("output");
    k.has_history = true;
    k.alpha = p.taa_alpha;
    for (Mode mode : {Mode::Exact, Mode::Fast}) {
      const bench::StageCost c =
          bench::stage_cost(mode, Stage::Taa, p, frames(surface ? 1.0 : 0.0, kW, kH));
      require_planes(rig, k, "taa", surface, {c.read / 4.0, c.written / 4.0});
    }
  }
}

TEST_CASE("stage cost: CUDA's exact mode over packed pixels differs where the packing moves bytes",
          "[bench][stage_cost]") {
  // methods/svgf/flavors.h, SvgfExactPacked: the demodulation also packs depth + normal, in
  // one kernel with the reprojection; the filter reads 16-byte pixels (the same floats on a
  // surface); the feedback copy and the remodulation ride on the a-trous iterations. Operations
  // do not change, only where the fused passes' are counted.
  const SvgfParams p;
  const auto cost = [&](Stage s, double surface, bool packed, const SvgfParams& params) {
    bench::FrameTraits f = frames(surface, 1920, 1080);
    f.emission = true;
    f.packed_exact = packed;
    return bench::stage_cost(Mode::Exact, s, params, f);
  };
  const auto delta = [&](Stage s, double surface, const SvgfParams& params = SvgfParams()) {
    const bench::StageCost a = cost(s, surface, true, params), b = cost(s, surface, false, params);
    CHECK(a.ops == b.ops);
    return std::make_pair(a.read - b.read, a.written - b.written);
  };
  // Demodulate + reproject + guide packing in one kernel (kFusedReprojection): fast mode's, the
  // same functors, counted under Demodulate; the operations of the two passes.
  for (double surface : {0.0, 1.0}) {
    bench::FrameTraits packed = frames(surface, 1920, 1080);
    packed.emission = true;
    packed.packed_exact = true;
    const bench::StageCost fused = bench::stage_cost(Mode::Exact, Stage::Demodulate, p, packed);
    const bench::StageCost fast = bench::stage_cost(Mode::Fast, Stage::Demodulate, p, packed);
    CHECK(fused.read == fast.read);
    CHECK(fused.written == fast.written);
    CHECK(fused.ops == fast.ops);
    CHECK(cost(Stage::Reproject, surface, true, p).bytes() == 0);
    CHECK(fused.ops == cost(Stage::Demodulate, surface, false, p).ops +
                           cost(Stage::Reproject, surface, false, p).ops);
    // 4 floats more written, the packed guides, and 4 fewer: the illumination in registers and
    // the accumulation's variance, which the variance stage derives from the moments (one
    // float more read there) where the denoiser keeps its scratch in the history: not from a
    // split frame on (methods/svgf/denoiser.h).
    CHECK(fused.written - cost(Stage::Demodulate, surface, false, p).written -
              cost(Stage::Reproject, surface, false, p).written == (4 - 3 - 1) * 4);
    bench::FrameTraits split = packed;
    split.split = true;
    CHECK(bench::stage_cost(Mode::Exact, Stage::Demodulate, p, split).written -
              fused.written == 4);
    CHECK(bench::stage_cost(Mode::Exact, Stage::Variance, p, packed).read -
              bench::stage_cost(Mode::Exact, Stage::Variance, p, split).read == 4);
    CHECK(bench::stage_cost(Mode::Fast, Stage::Variance, p, packed).read -
              bench::stage_cost(Mode::Fast, Stage::Variance, p, split).read == 4);
  }
  CHECK(delta(Stage::Variance, 1.0) == std::make_pair(4.0, 0.0));
  CHECK(delta(Stage::Variance, 0.0) == std::make_pair(16.0, 0.0));
  // The a-trous with the feedback copy and the remodulation, against three passes: the tap's
  // filtered color and the last filtered color are not read back (2 x 3 floats), the last
  // iteration writes the output instead of a packed pixel (4 floats fewer). Without a tap in
  // range neither copies the history (the reprojection accumulates into it).
  SvgfParams tap = p;
  tap.feedback_tap = 1;
  SvgfParams no_tap = p;
  no_tap.feedback_tap = -1;
  for (const auto& [params, read, written] :
       {std::make_tuple(tap, -6.0, -4.0), std::make_tuple(no_tap, -3.0, -4.0)}) {
    REQUIRE(params.iterations > 1);
    bench::StageCost a, b;  // packed, planes
    for (Stage s : {Stage::Atrous, Stage::Feedback, Stage::Remodulate})
      for (auto [sum, packed] : {std::make_pair(&a, true), std::make_pair(&b, false)}) {
        const bench::StageCost c = cost(s, 1.0, packed, params);
        sum->read += c.read;
        sum->written += c.written;
        sum->ops += c.ops;
      }
    CHECK(a.ops == b.ops);
    CHECK(a.read - b.read == read * 4);
    CHECK(a.written - b.written == written * 4);
    CHECK(cost(Stage::Remodulate, 1.0, true, params).bytes() == 0);
  }
  CHECK(cost(Stage::Feedback, 1.0, true, tap).bytes() == 0);
  CHECK(cost(Stage::Feedback, 1.0, true, no_tap).bytes() == 0);
  CHECK(cost(Stage::Feedback, 1.0, false, no_tap).bytes() == 0);
  // The same fused a-trous as fast mode's, but for its operations.
  bench::FrameTraits f = frames(1.0, 1920, 1080), g = f;
  g.packed_exact = true;
  CHECK(bench::stage_cost(Mode::Exact, Stage::Atrous, p, g).bytes() ==
        bench::stage_cost(Mode::Fast, Stage::Atrous, p, f).bytes());
  // Fast mode has its own model, which the flag does not touch.
  CHECK(bench::frame_cost(Mode::Fast, p, f).read == bench::frame_cost(Mode::Fast, p, g).read);
}

TEST_CASE("stage cost: the outputs fused into the a-trous on planes, as the CPU runs them",
          "[bench][stage_cost]") {
  // methods/svgf/flavors.h, SvgfExact: kFusedOutputs (the runner's traits say so). Against the
  // stage kernels' three passes: the tap's filtered color and the last filtered color are not
  // read back (2 x 3 floats), the last iteration writes the output 3 instead of its color +
  // variance 4; the operations are the same, counted in the a-trous.
  const auto sum = [](const SvgfParams& params, bool fused, double surface) {
    bench::FrameTraits f = frames(surface, 1920, 1080);
    f.emission = true;
    f.fused_outputs = fused;
    bench::StageCost total;
    for (Stage s : {Stage::Atrous, Stage::Feedback, Stage::Remodulate}) {
      const bench::StageCost c = bench::stage_cost(Mode::Exact, s, params, f);
      total.read += c.read;
      total.written += c.written;
      total.ops += c.ops;
      if (fused && params.iterations > 0 && s != Stage::Atrous) CHECK(c.bytes() == 0);
    }
    return total;
  };
  SvgfParams tap;
  tap.feedback_tap = 1;
  SvgfParams no_tap;
  no_tap.feedback_tap = -1;
  for (const auto& [params, read, written] :
       {std::make_tuple(tap, -6.0, -4.0), std::make_tuple(no_tap, -3.0, -4.0)}) {
    REQUIRE(params.iterations > 1);
    const bench::StageCost a = sum(params, true, 1.0), b = sum(params, false, 1.0);
    CHECK(a.ops == b.ops);
    CHECK(a.read - b.read == read * 4);
    CHECK(a.written - b.written == written * 4);
  }
  // Without an iteration the remodulation is a pass of its own either way.
  SvgfParams none;
  none.iterations = 0;
  const bench::StageCost a = sum(none, true, 1.0), b = sum(none, false, 1.0);
  CHECK(a.read == b.read);
  CHECK(a.written == b.written);
  CHECK(a.read > 0);
}

TEST_CASE("stage cost: a stage the configuration does not run costs nothing",
          "[bench][stage_cost][asvgf]") {
  // `defaults` here: no anti-lag (the defaults' own anti-lag is `gradient`).
  const SvgfParams defaults = without_antilag(), gradient = with_antilag(Antilag::Gradient);
  const bench::FrameTraits plain = frames(1.0, 1920, 1080), samples = [] {
    bench::FrameTraits f = frames(1.0, 1920, 1080);
    f.gradient_samples = true;
    return f;
  }();
  bench::FrameTraits packed = samples;  // CUDA's exact mode
  packed.packed_exact = true;
  for (Mode mode : {Mode::Exact, Mode::Fast}) {
    for (Stage s : {Stage::Gradient, Stage::GradientAtrous, Stage::GradientLambda}) {
      CHECK(bench::stage_cost(mode, s, defaults, samples).bytes() == 0);
      CHECK(bench::stage_cost(mode, s, gradient, plain).bytes() == 0);  // no samples
      // Three passes on the CPU; on CUDA (fast mode, packed exact) one launch under Gradient
      // (methods/svgf/gradient_tile.h).
      const bool fused = mode == Mode::Fast;
      CHECK((bench::stage_cost(mode, s, gradient, samples).bytes() > 0) ==
            (!fused || s == Stage::Gradient));
    }
    CHECK(bench::stage_cost(mode, Stage::Taa, defaults, plain).bytes() == 0);
    CHECK(bench::stage_cost(mode, Stage::SplitSum, defaults, plain).bytes() == 0);
  }
  // The fused launch: the three stages' operations and taps, the samples' and guides' reads,
  // lambda written; none of the stratum planes between them.
  {
    double ops = 0, taps = 0;
    for (Stage s : {Stage::Gradient, Stage::GradientAtrous, Stage::GradientLambda}) {
      ops += bench::stage_cost(Mode::Exact, s, gradient, samples).ops;
      taps += bench::stage_cost(Mode::Exact, s, gradient, samples).taps;
    }
    const bench::StageCost fused = bench::stage_cost(Mode::Exact, Stage::Gradient, gradient, packed);
    CHECK(fused.ops == Approx(ops));
    CHECK(fused.taps == Approx(taps));
    CHECK(fused.read == Approx((9 + 2 + 7) * 4.0 / 9));
    CHECK(fused.written == Approx(4.0 / 9));
    CHECK(bench::stage_cost(Mode::Exact, Stage::GradientAtrous, gradient, packed).bytes() == 0);
    CHECK(bench::stage_cost(Mode::Exact, Stage::GradientLambda, gradient, packed).bytes() == 0);
    // A filter the fused launch does not take: three passes again.
    SvgfParams wide = gradient;
    wide.gradient_iterations = 3;
    CHECK(bench::stage_cost(Mode::Exact, Stage::GradientAtrous, wide, packed).bytes() > 0);
  }
  // At 1080p the strata are a ninth of the pixels; the a-trous counts 8 taps a stratum and step.
  CHECK(bench::strata_per_px(1920, 1080) == Approx(1.0 / 9));
  CHECK(bench::stage_cost(Mode::Exact, Stage::GradientAtrous, gradient, samples).taps ==
        Approx(8.0 * gradient.gradient_iterations / 9));
  // A-SVGF without samples falls back to the statistics rule, and its reads.
  const SvgfParams statistics = with_antilag(Antilag::Statistics);
  CHECK(bench::stage_cost(Mode::Exact, Stage::Reproject, gradient, plain).read ==
        bench::stage_cost(Mode::Exact, Stage::Reproject, statistics, plain).read);
  CHECK(bench::stage_cost(Mode::Exact, Stage::Reproject, statistics, plain).read ==
        bench::stage_cost(Mode::Exact, Stage::Reproject, defaults, plain).read + 6 * 4);
  // Fast mode's fused kernel has this frame's inputs already: operations only.
  CHECK(bench::stage_cost(Mode::Fast, Stage::Demodulate, statistics, plain).read ==
        bench::stage_cost(Mode::Fast, Stage::Demodulate, defaults, plain).read);
  CHECK(bench::stage_cost(Mode::Fast, Stage::Demodulate, statistics, plain).ops >
        bench::stage_cost(Mode::Fast, Stage::Demodulate, defaults, plain).ops);
  // The CUDA upload sends the gradient samples after the emission's slot.
  CHECK(bench::stage_cost(Mode::Fast, Stage::Upload, gradient, samples).read ==
        bench::stage_cost(Mode::Fast, Stage::Upload, defaults, samples).read + 6 * 4);
  // A split frame: only the stages it runs once are counted.
  DenoiserConfig d;
  d.svgf = gradient;
  d.svgf.taa = true;
  bench::FrameTraits split = samples;
  split.split = true;
  for (const char* stage : {svgf_stage::kGradient, svgf_stage::kGradientAtrous,
                            svgf_stage::kGradientLambda, svgf_stage::kSplitSum, svgf_stage::kTaa})
    CHECK(bench::method_stage_cost(d, stage, split).has_value());
  for (const char* stage : {svgf_stage::kDemodulate, svgf_stage::kAtrous, kSanitizeStage})
    CHECK_FALSE(bench::method_stage_cost(d, stage, split).has_value());
  // BMFR's TAA is the same functor.
  d.method = Method::Bmfr;
  d.bmfr.taa = true;
  CHECK(bench::method_stage_cost(d, bmfr_stage::kTaa, plain)->read == bench::taa_cost().read);
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
  CHECK(bench::method_stage_cost(d, "atrous", frames(1.0, kW, kH)).has_value());
  CHECK_FALSE(bench::method_stage_cost(d, "temporal", frames(1.0, kW, kH)).has_value());
  CHECK_FALSE(bench::frame_is_costed(Method::JbfAtrous));
  d.method = Method::Jbf;
  CHECK(bench::method_stage_cost(d, "filter", frames(1.0, kW, kH))->taps == 33 * 33 - 1);
  d.method = Method::Gaussian;
  CHECK_FALSE(bench::method_stage_cost(d, "blur_x", frames(1.0, kW, kH)).has_value());
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
    CHECK(bench::method_stage_cost(d, stage, frames(1.0, 1920, 1080)).has_value());
  CHECK_FALSE(bench::method_stage_cost(d, "atrous", frames(1.0, 1920, 1080)).has_value());
  // The grid sticks out of the image: at 1080p 61 x 34.75 blocks (the mean over the offsets) of
  // 1024 rows, 4.7% more rows than pixels.
  CHECK(bench::bmfr_blocks_per_px(1920, 1080) * block::kRows ==
        Approx(61 * 34.75 * 1024 / (1920.0 * 1080)));
  // Sanitize reads the world positions besides SVGF's planes.
  CHECK(bench::method_stage_cost(d, kSanitizeStage, frames(1.0, 1920, 1080))->read ==
        bench::stage_cost(Mode::Exact, Stage::Sanitize, SvgfParams(), false, 1.0).read + 12);
  // Fast mode's FMA make the regression and the weighted sum cheaper, the noise costs skip
  // nothing, and background rows skip the scaling.
  auto ops = [&](Mode mode, BmfrRankStrategy s, const char* stage, double surface) {
    d.mode = mode;
    d.bmfr.rank_strategy = s;
    return bench::method_stage_cost(d, stage, frames(surface, 1920, 1080))->ops;
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

TEST_CASE("stage cost: the sanitize stage counted in the demodulation's kernel where it rides",
          "[bench][stage_cost]") {
  // methods/svgf/pipeline.h, fuses_sanitize: fast mode and CUDA's exact mode run the sanitize
  // rule in the demodulate + reproject kernel unless something before it reads the inputs (the
  // statistics anti-lag's neighbourhood, A-SVGF's three passes) or a second signal follows it.
  const SvgfParams off = without_antilag(), gradient = with_antilag(Antilag::Gradient),
                   statistics = with_antilag(Antilag::Statistics);
  SvgfParams wide = gradient;
  wide.gradient_iterations = 3;
  for (double surface : {0.0, 1.0}) {
    bench::FrameTraits samples = frames(surface, 1920, 1080), plain = samples;
    samples.gradient_samples = true;
    bench::FrameTraits packed = samples, split = samples;
    packed.packed_exact = true;
    split.split = true;
    const bench::StageCost alone = bench::stage_cost(Mode::Exact, Stage::Sanitize, off, plain);
    REQUIRE(alone.bytes() > 0);
    struct Case {
      Mode mode;
      const SvgfParams& p;
      const bench::FrameTraits& f;
      bool fused;
    };
    const Case cases[] = {{Mode::Fast, off, plain, true},
                          {Mode::Fast, gradient, samples, true},
                          {Mode::Exact, gradient, packed, true},
                          {Mode::Exact, gradient, samples, false},  // the CPU: planes
                          {Mode::Fast, statistics, plain, false},
                          {Mode::Fast, gradient, plain, false},  // no samples: statistics
                          {Mode::Fast, wide, samples, false},
                          {Mode::Fast, gradient, split, false}};
    for (const Case& c : cases) {
      INFO("surface " << surface << ", mode " << (c.mode == Mode::Fast ? "fast" : "exact")
                      << ", fused " << c.fused);
      const bench::StageCost s = bench::stage_cost(c.mode, Stage::Sanitize, c.p, c.f);
      CHECK(s.bytes() == (c.fused ? 0.0 : alone.bytes()));
      CHECK(s.ops == (c.fused ? 0.0 : alone.ops));
    }
    // Where it rides: its tests added, and on background the planes only it reads (a split
    // frame's kernel, otherwise the same, carries none of it; it writes the accumulation's
    // variance plane, which the other kernel leaves to the variance stage).
    const auto demodulate = [&](Mode mode, const bench::FrameTraits& f) {
      return bench::stage_cost(mode, Stage::Demodulate, gradient, f);
    };
    const bench::StageCost with = demodulate(Mode::Fast, samples);
    const bench::StageCost without = demodulate(Mode::Fast, split);
    CHECK(with.ops - without.ops == Approx(alone.ops));
    CHECK(with.read - without.read == (surface > 0 ? 0.0 : 4 * 4));
    CHECK(without.written - with.written == 4);
    const bench::StageCost exact = demodulate(Mode::Exact, packed);
    CHECK(exact.ops == with.ops);
    CHECK(exact.read == with.read);
  }
}

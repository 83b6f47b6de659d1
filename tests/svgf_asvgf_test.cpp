// A-SVGF's anti-lag (--antilag gradient) through the public Denoiser, each test body on the
// CPU, CUDA exact and CUDA fast (tests/test_device.h); then thread counts on the CPU.
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "methods/svgf/stages.h"
#include "pipeline/make_denoiser.h"
#include "synthetic_sequence.h"
#include "test_device.h"
#include "test_support.h"

using namespace svgf;
using svgf::test::kCpu;
using svgf::test::TestDevice;

namespace {

DenoiserConfig config_for(const TestDevice& d, Antilag antilag, int threads = 2) {
  DenoiserConfig c = d.config(DenoiserConfig());
  c.threads = threads;
  c.svgf.antilag = antilag;
  return c;
}

// A still, 1-spp-noisy scene of two walls with 6 columns of background between them: the
// left (x < 21, mesh 1, depth 2) lit at `before` until frame `change`, then at `after` (a light
// switched almost off); the right (x >= 27, mesh 2, depth 4) always at `right`. No filter
// reaches across the gap with a weight other than 0 (flat walls: the depth tolerance is the
// 1e-8 floor; the variance prefilter's 3x3 ends in the gap), and the gap and the walls are
// whole strata. Each frame after the first carries a gradient sample per 3x3 stratum: the
// previous frame's sample re-shaded with its random number, so its two luminances differ only
// at the change.
struct LightSwitchScene {
  int width = 48, height = 24;
  int change = 6;
  float before = 1.f, after = 0.05f, right = 0.5f;
  float albedo = 0.5f;
  static constexpr int kLeftEnd = 21, kRightStart = 27;

  static bool left(int x) { return x < kLeftEnd; }
  static bool gap(int x) { return x >= kLeftEnd && x < kRightStart; }
  float light(int x, int k) const {
    return left(x) ? (k < change ? before : after) : (gap(x) ? 0.f : right);
  }
  // The frame's random factor per pixel, mean 1.
  std::vector<float> noise(int k) const {
    std::mt19937 rng(9173u + static_cast<uint32_t>(k));
    std::uniform_real_distribution<float> u(0.f, 2.f);
    std::vector<float> n(static_cast<size_t>(width) * height);
    for (float& v : n) v = u(rng);
    return n;
  }
  float grey_luminance(float v) const { return luminance(make_vec3(v, v, v)); }

  // `gradient`: carry the gradient group (frame 0's masks are all zero: no previous sample).
  Frame frame(int k, bool gradient = true) const {
    Frame f = test::flat_frame(width, height, 2.f, albedo);
    f.index = k;
    f.reference = Image(width, height, 3);
    const std::vector<float> n = noise(k);
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const size_t i = static_cast<size_t>(y) * width + x;
        if (gap(x)) {  // background: no surface, albedo 1, no light
          f.depth.plane(0)[i] = 0.f;
          f.normal.plane(2)[i] = 0.f;
          f.mesh_id[i] = 0;
          for (int c = 0; c < 3; ++c) f.albedo.plane(c)[i] = 1.f;
        } else if (!left(x)) {
          f.depth.plane(0)[i] = 4.f;
          f.mesh_id[i] = 2;
        }
        for (int c = 0; c < 3; ++c) {
          f.reference.plane(c)[i] = f.albedo.plane(c)[i] * light(x, k);
          f.color.plane(c)[i] = f.reference.plane(c)[i] * n[i];
        }
      }
    if (!gradient) return f;
    f.gradient = Image(width, height, 3);
    if (k == 0) return f;
    const std::vector<float> prev = noise(k - 1);
    std::mt19937 pick(31u + static_cast<uint32_t>(k));
    for (int sy = 0; sy * kGradientStratum < height; ++sy)
      for (int sx = 0; sx * kGradientStratum < width; ++sx) {
        const int x = sx * kGradientStratum + static_cast<int>(pick() % kGradientStratum);
        const int y = sy * kGradientStratum + static_cast<int>(pick() % kGradientStratum);
        if (x >= width || y >= height) continue;
        const size_t i = static_cast<size_t>(y) * width + x;
        f.gradient.at(x, y, 0) = grey_luminance(albedo * light(x, k - 1) * prev[i]);
        f.gradient.at(x, y, 1) = grey_luminance(albedo * light(x, k) * prev[i]);
        f.gradient.at(x, y, 2) = 1.f;
      }
    return f;
  }
};

std::vector<Image> run(Denoiser& d, const std::vector<Frame>& frames) {
  std::vector<Image> out;
  for (const Frame& f : frames) {
    out.emplace_back();
    d.denoise(f, out.back());
  }
  return out;
}

std::vector<Frame> frames_of(const LightSwitchScene& scene, int n, bool gradient = true) {
  std::vector<Frame> v;
  for (int k = 0; k < n; ++k) v.push_back(scene.frame(k, gradient));
  return v;
}

// Mean of channel 0 over the left wall.
double left_wall_mean(const Image& im) {
  double sum = 0;
  int n = 0;
  for (int y = 0; y < im.height(); ++y)
    for (int x = 0; x < LightSwitchScene::kLeftEnd; ++x) {
      sum += im.at(x, y, 0);
      ++n;
    }
  return sum / n;
}

// Columns from `x0` on of two images, compared as the device compares (exact: bitwise).
void require_columns_match(const TestDevice& d, const Image& got, const Image& want, int x0,
                           const std::string& what) {
  const int w = got.width() - x0;
  Image a(w, got.height(), 3), b(w, got.height(), 3);
  for (int c = 0; c < 3; ++c)
    for (int y = 0; y < got.height(); ++y)
      for (int x = 0; x < w; ++x) {
        a.at(x, y, c) = got.at(x0 + x, y, c);
        b.at(x, y, c) = want.at(x0 + x, y, c);
      }
  if (!d.fast()) {
    test::require_identical(a, b, what);
    return;
  }
  INFO(what);
  REQUIRE(test::max_relative_difference(a, b, 1e-3) <= test::kFastTolerance);
}

// Issue 12, item 3: the light on the left wall drops from 1 to 0.05 at frame 6. With the
// gradient anti-lag the left wall's output is within 5% of the step (0.5 * 0.95) of the new
// level 0.025 from the frame after the change on; without it the history holds the old light
// for many frames. The right wall, unchanged (lambda 0), gets the same output as without.
void gradient_follows_a_light_switched_off(const TestDevice& d) {
  const LightSwitchScene scene;
  const int n = scene.change + 3;
  const std::vector<Frame> frames = frames_of(scene, n);
  auto gradient = make_denoiser(config_for(d, Antilag::Gradient));
  auto off = make_denoiser(config_for(d, Antilag::Off));
  const std::vector<Image> g = run(*gradient, frames);
  const std::vector<Image> o = run(*off, frames);
  // The last frame ran the gradient stages (the report's stage times name them: the samples'
  // stage, which the packed flavors' one fused launch is timed as).
  const StageTimes& times = gradient->last_report().times;
  bool named = false;
  for (const auto& e : times.entries()) named = named || e.first == svgf_stage::kGradient;
  REQUIRE(named);

  const double new_level = scene.albedo * scene.after;
  const double step = scene.albedo * (scene.before - scene.after);
  for (int k = 0; k < n; ++k) {
    INFO("frame " << k);
    // Before the change every delta is 0: the whole output is the output without anti-lag.
    if (k < scene.change) require_columns_match(d, g[k], o[k], 0, "frame before the change");
    require_columns_match(d, g[k], o[k], LightSwitchScene::kRightStart, "right wall");
    if (k < scene.change) continue;
    const double err_gradient = std::fabs(left_wall_mean(g[k]) - new_level) / step;
    const double err_off = std::fabs(left_wall_mean(o[k]) - new_level) / step;
    INFO("left wall: gradient " << left_wall_mean(g[k]) << ", off " << left_wall_mean(o[k])
                                << ", new level " << new_level);
    // At the change itself the history is mostly dropped already; from the next frame on
    // within 5% of the step.
    REQUIRE(err_gradient <= (k == scene.change ? 0.1 : 0.05));
    REQUIRE(err_off >= 0.5);
  }
}

// Without gradient samples (no group, or every mask 0) the gradient mode runs the statistics
// anti-lag: the same bits as --antilag statistics, and no gradient stage in the report.
void without_samples_falls_back_to_statistics(const TestDevice& d) {
  // A moving square, and from frame 3 on the left half lit at 1% (a light switched off): the
  // statistics rule has work to do.
  test::SyntheticScene moving;
  std::vector<Frame> plain, zeros;
  for (int k = 0; k < 5; ++k) {
    plain.push_back(moving.frame(k));
    if (k >= 3)
      for (int c = 0; c < 3; ++c)
        for (int y = 0; y < moving.height; ++y)
          for (int x = 0; x < moving.width / 2; ++x) plain.back().color.at(x, y, c) *= 0.01f;
    zeros.push_back(plain.back());
    zeros.back().gradient = Image(moving.width, moving.height, 3);
  }
  auto statistics = make_denoiser(config_for(d, Antilag::Statistics));
  auto no_group = make_denoiser(config_for(d, Antilag::Gradient));
  auto no_mask = make_denoiser(config_for(d, Antilag::Gradient));
  const std::vector<Image> want = run(*statistics, plain);
  const std::vector<Image> a = run(*no_group, plain);
  const std::vector<Image> b = run(*no_mask, zeros);
  for (int k = 0; k < 5; ++k) {
    test::require_identical(a[k], want[k], "no gradient group, frame " + std::to_string(k));
    test::require_identical(b[k], want[k], "all masks 0, frame " + std::to_string(k));
  }
  REQUIRE(no_group->last_report().times[svgf_stage::kGradient] == 0.0);
  for (const auto& e : no_mask->last_report().times.entries())
    REQUIRE(e.first.rfind("gradient", 0) != 0);
  // And the statistics rule did change something on this sequence (the comparison means it).
  auto off = make_denoiser(config_for(d, Antilag::Off));
  const std::vector<Image> o = run(*off, plain);
  REQUIRE(test::max_relative_difference(o.back(), want.back(), 1e-3) > 0);
}

}  // namespace

SVGF_DEVICE_TEST("asvgf: a light switched off is followed within a frame; the unchanged wall "
                 "keeps the output without anti-lag",
                 "[pipeline][asvgf]", gradient_follows_a_light_switched_off)
SVGF_DEVICE_TEST("asvgf: frames without gradient samples run the statistics anti-lag",
                 "[pipeline][asvgf]", without_samples_falls_back_to_statistics)

TEST_CASE("asvgf: identical bits on 1 and 2 threads", "[pipeline][asvgf][determinism]") {
  const LightSwitchScene scene;
  const std::vector<Frame> frames = frames_of(scene, scene.change + 2);
  auto one = make_denoiser(config_for(kCpu, Antilag::Gradient, 1));
  auto two = make_denoiser(config_for(kCpu, Antilag::Gradient, 2));
  const std::vector<Image> a = run(*one, frames);
  const std::vector<Image> b = run(*two, frames);
  for (size_t k = 0; k < a.size(); ++k)
    test::require_identical(a[k], b[k], "1 vs 2 threads, frame " + std::to_string(k));
  test::require_identical(one->read_buffer(svgf_buffer::kHistoryLength),
                          two->read_buffer(svgf_buffer::kHistoryLength), "history length");
}

TEST_CASE("asvgf: --antilag modes by name, 'on' the statistics mode's alias", "[asvgf][params]") {
  REQUIRE(parse_antilag("off") == Antilag::Off);
  REQUIRE(parse_antilag("on") == Antilag::Statistics);
  REQUIRE(parse_antilag("statistics") == Antilag::Statistics);
  REQUIRE(parse_antilag("gradient") == Antilag::Gradient);
  REQUIRE(std::string(to_string(Antilag::Gradient)) == "gradient");
  REQUIRE_THROWS_WITH(parse_antilag("asvgf"), Catch::Contains("off, statistics (or on) or gradient") &&
                                                  Catch::Contains("'asvgf'"));
  SvgfParams p;
  p.gradient_iterations = 9;
  REQUIRE_THROWS_WITH(p.validate(), Catch::Contains("--gradient-iterations"));
  p.gradient_iterations = 3;
  p.gradient_phi_depth = -1.f;
  REQUIRE_THROWS_WITH(p.validate(), Catch::Contains("--gradient-phi-depth"));
}

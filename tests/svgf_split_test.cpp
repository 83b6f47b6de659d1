// SVGF filtering direct and indirect apart (issue 12, item 2; docs/svgf.md: Direct and
// indirect), through the public Denoiser interface. The bodies run on the CPU, CUDA exact and
// CUDA fast (tests/test_device.h); each compares runs on one device, so the bitwise checks hold
// in every mode.
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "io/sequence.h"
#include "pipeline/make_denoiser.h"
#include "synthetic_sequence.h"
#include "test_device.h"
#include "test_support.h"

using namespace svgf;
using svgf::test::kCpu;
using svgf::test::TestDevice;

namespace {

DenoiserConfig split_config(const TestDevice& d, SplitMode split, int threads = 2) {
  DenoiserConfig c = d.config(DenoiserConfig());
  c.threads = threads;
  c.svgf.split = split;
  return c;
}

// The first `n` frames of a committed fixture (128x128, with emission).
std::vector<Frame> fixture_frames(const std::string& scene, int n) {
  const io::Sequence seq(std::string(SVGF_SOURCE_DIR) + "/fixtures/" + scene);
  std::vector<Frame> frames;
  for (int k = 0; k < n && k < seq.size(); ++k) frames.push_back(seq.read(k));
  return frames;
}

// The frame with color as its direct part and an indirect part of exactly 0.
Frame all_direct(const Frame& f) {
  Frame g = f;
  g.direct = f.color;
  g.indirect = Image(f.width(), f.height(), 3, 0.f);
  return g;
}

std::vector<Image> denoise_all(const DenoiserConfig& c, const std::vector<Frame>& frames) {
  auto d = make_denoiser(c);
  std::vector<Image> out(frames.size());
  for (size_t k = 0; k < frames.size(); ++k) d->denoise(frames[k], out[k]);
  return out;
}

// The synthetic sequence with its color split: direct the lit wall, indirect a noisier,
// dimmer part (color = direct + indirect up to rounding).
Frame split_synthetic(const test::SyntheticScene& scene, int k) {
  Frame f = scene.frame(k);
  f.direct = f.color;
  f.indirect = Image(f.width(), f.height(), 3);
  std::mt19937 rng(1000u + static_cast<uint32_t>(k));
  std::uniform_real_distribution<float> noise(0.f, 1.f);
  for (size_t i = 0; i < f.color.data().size(); ++i) {
    f.indirect.data()[i] = 0.4f * f.reference.data()[i] * noise(rng);
    f.color.data()[i] = f.direct.data()[i] + f.indirect.data()[i];
  }
  return f;
}

void zero_indirect_is_single_signal(const TestDevice& device) {
  // Real rendered frames (emitters in view, moving objects, disocclusions): over 6 frames, history
  // included, a split whose indirect part is 0 gives the single-signal bits, whatever filter the
  // indirect part gets.
  const std::vector<Frame> frames = fixture_frames("cornell-moving", 6);
  REQUIRE(frames.size() == 6);
  REQUIRE_FALSE(frames[0].emission.empty());
  std::vector<Frame> split;
  for (const Frame& f : frames) split.push_back(all_direct(f));

  const auto single = denoise_all(split_config(device, SplitMode::Off), frames);
  DenoiserConfig on = split_config(device, SplitMode::On);
  DenoiserConfig wider = on;
  wider.svgf.indirect_iterations = 5;
  wider.svgf.indirect_phi_color = 40.f;
  const auto split_on = denoise_all(on, split);
  const auto split_auto = denoise_all(split_config(device, SplitMode::Auto), split);
  const auto split_wider = denoise_all(wider, split);
  for (size_t k = 0; k < frames.size(); ++k) {
    const std::string frame = ", frame " + std::to_string(k);
    test::require_identical(split_on[k], single[k], "split on vs single" + frame);
    test::require_identical(split_auto[k], single[k], "split auto vs single" + frame);
    test::require_identical(split_wider[k], single[k], "wider indirect filter vs single" + frame);
  }
  // Off ignores the split channels.
  const auto off = denoise_all(split_config(device, SplitMode::Off), split);
  test::require_identical(off.back(), single.back(), "split off on split frames vs single");
}

// A still wall with a sharp edge in its direct light (1 left, 0.2 right, noise-free) and a flat,
// noisy indirect part (0 or 0.6, mean 0.3). One signal's variance is the indirect noise's, so
// the luminance edge-stopping lets the filter blur the edge; split, the direct part has no
// variance and keeps its edge while the indirect part is smoothed.
struct EdgeScene {
  int width = 48, height = 24, edge = 24;
  Frame frame(int k) const {
    Frame f = test::flat_frame(width, height, 2.f, 1.f);
    f.index = k;
    f.direct = Image(width, height, 3);
    f.indirect = Image(width, height, 3);
    std::mt19937 rng(77u + static_cast<uint32_t>(k));
    std::bernoulli_distribution coin(0.5);
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const float direct = x < edge ? 1.f : 0.2f;
        const float indirect = coin(rng) ? 0.6f : 0.f;
        for (int c = 0; c < 3; ++c) {
          f.direct.at(x, y, c) = direct;
          f.indirect.at(x, y, c) = indirect;
          f.color.at(x, y, c) = direct + indirect;
        }
      }
    return f;
  }
  // Mean over rows of the output's step across the edge.
  double step(const Image& out) const {
    double s = 0;
    for (int y = 0; y < height; ++y) s += out.at(edge - 1, y, 0) - out.at(edge, y, 0);
    return s / height;
  }
};

void split_keeps_direct_edges(const TestDevice& device) {
  const EdgeScene scene;
  // Falcor's values (the sample variance, phi_color 10: the single signal's filter is wide
  // enough to show the blur) with the unfiltered accumulation fed back, so the history holds the
  // edge as rendered; 6 frames, so the last filters with the temporal variance (history >= 4).
  const auto run = [&](SplitMode split) {
    DenoiserConfig c = split_config(device, split);
    c.svgf = svgf_preset("falcor");
    c.svgf.split = split;
    c.svgf.feedback_tap = -1;
    auto d = make_denoiser(c);
    Image out;
    for (int k = 0; k < 6; ++k) d->denoise(scene.frame(k), out);
    return out;
  };
  const Image split = run(SplitMode::On);
  const Image single = run(SplitMode::Off);
  for (float v : split.data()) REQUIRE(std::isfinite(v));
  const double split_step = scene.step(split), single_step = scene.step(single);
  INFO("edge step 0.8 as rendered; split " << split_step << ", single signal " << single_step);
  REQUIRE(std::fabs(split_step - 0.8) < 0.05);
  REQUIRE(single_step < 0.5);  // the property fails without the split
  // Far from the edge, the split result is the direct light + the indirect mean 0.3.
  double right = 0;
  int n = 0;
  for (int y = 4; y < scene.height - 4; ++y)
    for (int x = scene.edge + 8; x < scene.width - 4; ++x, ++n) right += split.at(x, y, 0);
  REQUIRE(std::fabs(right / n - 0.5) < 0.05);
}

// A frame with the split after frames without it starts the split history afresh, as after a
// reset; reset() restarts both signals.
void split_history_starts_fresh(const TestDevice& device) {
  const test::SyntheticScene scene;
  const DenoiserConfig c = split_config(device, SplitMode::Auto);
  auto d = make_denoiser(c);
  Image out;
  for (int k = 0; k < 3; ++k) d->denoise(scene.frame(k), out);  // no split channels
  const Frame f3 = split_synthetic(scene, 3);
  d->denoise(f3, out);
  Image fresh;
  make_denoiser(c)->denoise(f3, fresh);
  test::require_identical(out, fresh, "first split frame after single ones vs a fresh denoiser");

  d->denoise(split_synthetic(scene, 4), out);
  d->reset();
  const Frame f5 = split_synthetic(scene, 5);
  d->denoise(f5, out);
  make_denoiser(c)->denoise(f5, fresh);
  test::require_identical(out, fresh, "split frame after reset() vs a fresh denoiser");

  // And back: a frame without the split after split frames starts afresh too.
  const Frame f6 = scene.frame(6);
  d->denoise(f6, out);
  make_denoiser(c)->denoise(f6, fresh);
  test::require_identical(out, fresh, "single frame after split ones vs a fresh denoiser");
}

void half_split_is_an_error(const TestDevice& device) {
  const test::SyntheticScene scene;
  Frame direct_only = split_synthetic(scene, 0);
  direct_only.indirect = Image();
  Frame indirect_only = split_synthetic(scene, 0);
  indirect_only.direct = Image();
  Image out;
  auto d = make_denoiser(split_config(device, SplitMode::Auto));
  REQUIRE_THROWS_WITH(d->denoise(direct_only, out),
                      Catch::Contains("frame 0") && Catch::Contains("'direct' without 'indirect'"));
  REQUIRE_THROWS_WITH(d->denoise(indirect_only, out),
                      Catch::Contains("'indirect' without 'direct'"));
  auto on = make_denoiser(split_config(device, SplitMode::On));
  REQUIRE_THROWS_WITH(on->denoise(scene.frame(0), out),
                      Catch::Contains("--svgf-split on") && Catch::Contains("neither"));
  // Nothing was half done: the denoisers go on, and off ignores a half split.
  d->denoise(split_synthetic(scene, 0), out);
  on->denoise(split_synthetic(scene, 0), out);
  Image single, ignored;
  make_denoiser(split_config(device, SplitMode::Off))->denoise(direct_only, ignored);
  Frame plain = direct_only;
  plain.direct = Image();
  make_denoiser(split_config(device, SplitMode::Off))->denoise(plain, single);
  test::require_identical(ignored, single, "split off ignores a half split");
}

// A bad sample in direct or indirect is repaired as one in color is (set to 0) and counted
// with color's; a NaN in the split channels when split is off is not read.
void bad_split_samples_are_repaired(const TestDevice& device) {
  const test::SyntheticScene scene;
  Frame bad = split_synthetic(scene, 0);
  bad.direct.at(5, 5, 0) = std::numeric_limits<float>::quiet_NaN();
  bad.indirect.at(9, 7, 2) = -1.f;
  bad.indirect.at(5, 5, 1) = std::numeric_limits<float>::infinity();  // same pixel: counted once
  Frame fixed = bad;
  fixed.direct.at(5, 5, 0) = 0.f;
  fixed.indirect.at(9, 7, 2) = 0.f;
  fixed.indirect.at(5, 5, 1) = 0.f;
  auto d = make_denoiser(split_config(device, SplitMode::On));
  Image out, want;
  d->denoise(bad, out);
  REQUIRE(d->last_report().repairs.color == 2);
  for (float v : out.data()) REQUIRE(std::isfinite(v));
  make_denoiser(split_config(device, SplitMode::On))->denoise(fixed, want);
  test::require_identical(out, want, "bad split samples vs the same set to 0");
  auto off = make_denoiser(split_config(device, SplitMode::Off));
  off->denoise(bad, out);
  REQUIRE(off->last_report().repairs.color == 0);
}

}  // namespace

SVGF_DEVICE_TEST("split: NaN, Inf and negative direct or indirect are repaired and counted",
                 "[pipeline][split]", bad_split_samples_are_repaired)
SVGF_DEVICE_TEST("split: an indirect part of 0 gives the single-signal bits on a rendered sequence",
                 "[pipeline][split]", zero_indirect_is_single_signal)
SVGF_DEVICE_TEST("split: the indirect part's variance does not blur the direct part's edges",
                 "[pipeline][split]", split_keeps_direct_edges)
SVGF_DEVICE_TEST("split: switching to or from the split, and reset(), start the history afresh",
                 "[pipeline][split]", split_history_starts_fresh)
SVGF_DEVICE_TEST("split: half a split, or split on without one, is a clear error",
                 "[pipeline][split]", half_split_is_an_error)

TEST_CASE("split: identical bits on 1 and 2 threads", "[pipeline][split][determinism]") {
  const test::SyntheticScene scene;
  auto one = make_denoiser(split_config(kCpu, SplitMode::On, 1));
  auto two = make_denoiser(split_config(kCpu, SplitMode::On, 2));
  Image a, b;
  for (int k = 0; k < 6; ++k) {
    const Frame f = split_synthetic(scene, k);
    one->denoise(f, a);
    two->denoise(f, b);
    test::require_identical(a, b, "1 vs 2 threads, frame " + std::to_string(k));
  }
  // The split was taken: the single signal differs.
  auto single = make_denoiser(split_config(kCpu, SplitMode::Off, 2));
  Image c;
  for (int k = 0; k < 6; ++k) single->denoise(split_synthetic(scene, k), c);
  REQUIRE(test::max_relative_difference(a, c) > 1e-3);
}

TEST_CASE("split: parameters, their names and ranges", "[pipeline][split][params]") {
  REQUIRE(parse_split_mode("auto") == SplitMode::Auto);
  REQUIRE(parse_split_mode("off") == SplitMode::Off);
  REQUIRE(parse_split_mode("on") == SplitMode::On);
  REQUIRE(std::string(to_string(SplitMode::On)) == "on");
  REQUIRE_THROWS_WITH(parse_split_mode("yes"), Catch::Contains("auto, off or on"));
  SvgfParams p;
  REQUIRE(p.split == SplitMode::Auto);
  p.iterations = 3;
  p.phi_color = 7.f;
  REQUIRE(p.indirect().iterations == 3);  // -1: as the direct signal's
  REQUIRE(p.indirect().phi_color == 7.f);
  p.indirect_iterations = 0;
  p.indirect_phi_color = 20.f;
  REQUIRE(p.indirect().iterations == 0);
  REQUIRE(p.indirect().phi_color == 20.f);
  REQUIRE(p.indirect().indirect_iterations == 0);
  p.validate();
  p.indirect_iterations = 13;
  REQUIRE_THROWS_WITH(p.validate(), Catch::Contains("--indirect-iterations"));
  p.indirect_iterations = -1;
  for (float bad : {0.f, -2.f, NAN, INFINITY}) {
    p.indirect_phi_color = bad;
    REQUIRE_THROWS_WITH(p.validate(), Catch::Contains("--indirect-phi-color"));
  }
}

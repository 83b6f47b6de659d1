// The whole SVGF pipeline through the public Denoiser interface, each test body on the CPU, CUDA
// exact and CUDA fast (tests/test_device.h); then what only the CPU engine has.
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <thread>
#include <utility>

#include <catch2/catch.hpp>

#include "pipeline/make_denoiser.h"
#include "methods/svgf/pipeline.h"
#include "kernels_cpu/ieee_guard.h"
#include "kernels_cpu/parallel_for.h"
#include "metrics/image_metrics.h"
#include "synthetic_sequence.h"
#include "test_device.h"
#include "test_support.h"

using namespace svgf;
using svgf::test::kCpu;
using svgf::test::TestDevice;

namespace {

DenoiserConfig config_for(const TestDevice& d, int threads = 2) {
  DenoiserConfig c = d.config(DenoiserConfig());
  c.threads = threads;
  return c;
}
DenoiserConfig cpu_config(int threads) { return config_for(kCpu, threads); }

// Exact mode: identical bits. Fast mode: within its tolerance of the exact result.
void require_matches(const TestDevice& d, const Image& got, const Image& exact,
                     const std::string& what) {
  if (!d.fast()) {
    test::require_identical(got, exact, what);
    return;
  }
  const double worst = test::max_relative_difference(got, exact, 1e-3);
  INFO(what << ": fast mode's worst relative difference " << worst);
  REQUIRE(worst <= test::kFastTolerance);
}

// `edit` (optional) changes each frame before it is denoised.
std::vector<Image> denoise_sequence(Denoiser& d, const test::SyntheticScene& scene, int frames,
                                    const std::function<void(Frame&)>& edit = {}) {
  std::vector<Image> out;
  for (int k = 0; k < frames; ++k) {
    Frame f = scene.frame(k);
    if (edit) edit(f);
    out.emplace_back();
    d.denoise(f, out.back());
  }
  return out;
}

void beats_noisy_input(const TestDevice& device) {
  test::SyntheticScene scene;
  auto d = make_denoiser(config_for(device, 0));
  double noisy_psnr = 0, denoised_psnr = 0;
  for (int k = 0; k < 10; ++k) {
    const Frame f = scene.frame(k);
    Image out;
    d->denoise(f, out);
    noisy_psnr = metrics::psnr(f.color, f.reference);
    denoised_psnr = metrics::psnr(out, f.reference);
    for (float v : out.data()) REQUIRE(std::isfinite(v));
  }
  INFO("noisy " << noisy_psnr << " dB, denoised " << denoised_psnr << " dB");
  REQUIRE(denoised_psnr > noisy_psnr + 8.0);
  // Wall pixels the square uncovered this frame have no history, except the first column, which
  // the 3x3 fallback joins to the wall beside it.
  const Image history = d->read_buffer(svgf_buffer::kHistoryLength);
  const int k = 9, y = scene.square_y() + scene.square / 2;
  for (int x = scene.square_x(k) - scene.speed + 1; x < scene.square_x(k); ++x)
    REQUIRE(history.at(x, y, 0) == 1.f);
  REQUIRE(history.at(scene.square_x(k) - scene.speed, y, 0) > 1.f);
  REQUIRE(history.at(scene.square_x(k) + 3, y, 0) == 10.f);  // the square tracked its motion
  REQUIRE(history.at(2, 2, 0) == 10.f);                      // the static wall
}



void feedback_tap_is_next_history(const TestDevice& device) {
  test::SyntheticScene scene;
  DenoiserConfig config = config_for(device);
  config.svgf.iterations = 3;
  config.svgf.feedback_tap = 0;
  config.keep_scratch = true;  // frame 1's accumulation and illumination are read back
  auto d = make_denoiser(config);
  const Frame f0 = scene.frame(0);
  Image out;
  d->denoise(f0, out);

  // Recompute frame 0 stage by stage up to the first a-trous iteration.
  const int w = scene.width, h = scene.height;
  const SvgfParams& p = config.svgf;
  Image illum(w, h, 3), acc(w, h, 4), moments(w, h, 2), hist(w, h, 1), var(w, h, 4), it0(w, h, 4);
  Image none3(w, h, 3), none1(w, h, 1);
  cpu::for_each_pixel(w, h, DemodulateKernel{w, f0.color.rgb(), f0.albedo.rgb(), {}, illum.rgb(), p.albedo_epsilon});
  ReprojectKernel r;
  r.guides = r.prev_guides = f0.guides();
  r.illumination = illum.rgb();
  r.prev_color = none3.rgb();
  r.prev_moment1 = r.prev_moment2 = r.prev_history = none1.plane(0);
  r.has_history = false;
  r.accumulated = {acc.rgb(), acc.plane(3)};
  r.moment1 = moments.plane(0);
  r.moment2 = moments.plane(1);
  r.history = hist.plane(0);
  r.params = p;
  cpu::for_each_pixel(w, h, r);
  cpu::for_each_pixel(w, h, VarianceKernel{f0.guides(), {acc.rgb(), acc.plane(3)}, moments.plane(0),
                                           moments.plane(1), hist.plane(0), {var.rgb(), var.plane(3)}, p});
  cpu::for_each_pixel(w, h, AtrousKernel{f0.guides(), {var.rgb(), var.plane(3)}, {it0.rgb(), it0.plane(3)}, 1, p});
  Image it0_rgb(w, h, 3);
  for (int c = 0; c < 3; ++c) std::copy(it0.plane(c), it0.plane(c) + w * h, it0_rgb.plane(c));
  const Image history = d->read_buffer(svgf_buffer::kColorHistory);
  require_matches(device, history, it0_rgb, "color history vs a-trous iteration 0 (CPU)");

  // Frame 1 (the wall is static) blends its sample into exactly that history at alpha 1/2.
  const Frame f1 = scene.frame(1);
  d->denoise(f1, out);
  const Image acc1 = d->read_buffer(svgf_buffer::kAccumulated);
  const Image illum1 = d->read_buffer(svgf_buffer::kIllumination);
  for (int x = 0; x < 4; ++x) {
    const float hv = history.at(x, 2, 0);
    REQUIRE(acc1.at(x, 2, 0) == hv + (illum1.at(x, 2, 0) - hv) * 0.5f);
  }
}

// Without a fed-back iteration the reprojection accumulates into the color history (no copy):
// the `accumulated` debug buffer's color is then the history the next frame reads. A tap past
// the last iteration is the same configuration as -1, and so is one where only the indirect
// parameters would feed back (frames without the split run the direct signal alone; the
// denoiser then keeps the accumulation's color planes, unused): the same buffers.
void accumulation_is_the_history_without_a_tap(const TestDevice& device) {
  test::SyntheticScene scene;
  const auto run = [&](int tap, int indirect_iterations) {
    DenoiserConfig config = config_for(device);
    config.svgf.iterations = 3;
    config.svgf.feedback_tap = tap;
    config.svgf.indirect_iterations = indirect_iterations;
    config.keep_scratch = true;
    auto d = make_denoiser(config);
    Image out;
    for (int k = 0; k < 3; ++k) d->denoise(scene.frame(k), out);
    return std::make_pair(d->read_buffer(svgf_buffer::kAccumulated),
                          d->read_buffer(svgf_buffer::kColorHistory));
  };
  const auto [first_acc, first_history] = run(-1, -1);
  for (const auto& [tap, indirect] :
       {std::make_pair(-1, -1), std::make_pair(3, -1), std::make_pair(3, 4)}) {
    INFO("feedback tap " << tap << " of 3 iterations, indirect iterations " << indirect);
    const auto [acc, history] = run(tap, indirect);
    REQUIRE(acc.channels() == 4);
    REQUIRE(history.channels() == 3);
    const size_t n = history.pixel_count();
    for (int c = 0; c < 3; ++c)
      REQUIRE(std::equal(history.plane(c), history.plane(c) + n, acc.plane(c)));
    REQUIRE(std::equal(first_acc.data().begin(), first_acc.data().end(), acc.data().begin()));
    REQUIRE(std::equal(first_history.data().begin(), first_history.data().end(),
                       history.data().begin()));
  }
}

void bad_input_does_not_poison(const TestDevice& device) {
  test::SyntheticScene scene;
  auto clean = make_denoiser(config_for(device));
  auto dirty = make_denoiser(config_for(device));
  Image out_clean, out_dirty;
  for (int k = 0; k < 5; ++k) {
    Frame f = scene.frame(k);
    Frame g = f;
    if (k == 2) {
      // The same pixels set to 0 in the clean run: the documented replacement.
      const int bad[][2] = {{10, 10}, {30, 20}, {50, 40}};
      const float values[] = {std::numeric_limits<float>::quiet_NaN(),
                              std::numeric_limits<float>::infinity(), -3.f};
      for (int j = 0; j < 3; ++j) {
        g.color.at(bad[j][0], bad[j][1], j) = values[j];
        f.color.at(bad[j][0], bad[j][1], j) = 0.f;
      }
    }
    clean->denoise(f, out_clean);
    dirty->denoise(g, out_dirty);
    REQUIRE(dirty->last_report().replaced_samples == (k == 2 ? 3 : 0));
    for (float v : out_dirty.data()) REQUIRE(std::isfinite(v));
    test::require_identical(out_dirty, out_clean, "frame " + std::to_string(k));
  }
}


void reset_restarts_history(const TestDevice& device) {
  test::SyntheticScene scene;
  auto d = make_denoiser(config_for(device));
  Image out;
  d->denoise(scene.frame(0), out);
  d->denoise(scene.frame(1), out);
  REQUIRE(d->read_buffer(svgf_buffer::kHistoryLength).at(1, 1, 0) == 2.f);
  d->reset();
  d->denoise(scene.frame(2), out);
  REQUIRE(d->read_buffer(svgf_buffer::kHistoryLength).at(1, 1, 0) == 1.f);
}

void defaults_are_documented(const TestDevice& device) {
  // The documented defaults (methods/svgf/params.h, docs/svgf.md), written out here, not read
  // from the header...
  SvgfParams documented;
  documented.iterations = 4;
  documented.feedback_tap = -1;
  documented.phi_color = 4.f;
  documented.phi_normal = 128.f;
  documented.phi_depth = 1.f;
  documented.alpha = 0.03f;
  documented.moments_alpha = 0.2f;
  documented.history_cap = 64;
  documented.variance_of_mean = true;
  documented.antilag = Antilag::Gradient;
  documented.gradient_iterations = 1;
  documented.gradient_lambda_radius = 1;
  documented.spatial_variance_history = 4;
  documented.spatial_variance_radius = 3;
  documented.spatial_variance_phi_depth = 3.f;
  documented.reproject_min_weight = 0.01f;
  // ...and a default-configured denoiser gives the same bits as one given those values by
  // hand, while moving any one of them changes the output: the pipeline reads what the
  // configuration holds, and each default is the value it is documented to be.
  // The synthetic scene's surfaces are flat and face the camera: bumps on the normals and a tilt
  // of the depth let phi_normal and phi_depth matter.
  test::SyntheticScene scene;
  const auto bumps = [](Frame& f) {
    for (int y = 0; y < f.height(); ++y)
      for (int x = 0; x < f.width(); ++x) {
        if (!(f.depth.at(x, y, 0) > 0.f)) continue;
        f.depth.at(x, y, 0) += 0.02f * static_cast<float>(x);
        f.depth_gradient.at(x, y, 0) += 0.02f;
        const float bx = 0.15f * std::sin(0.9f * x), by = 0.15f * std::cos(0.7f * y);
        float n[3] = {f.normal.at(x, y, 0) + bx, f.normal.at(x, y, 1) + by, f.normal.at(x, y, 2)};
        const float len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        for (int c = 0; c < 3; ++c) f.normal.at(x, y, c) = n[c] / len;
      }
  };
  DenoiserConfig by_default = config_for(device);
  DenoiserConfig by_hand = config_for(device);
  by_hand.svgf = documented;
  auto a = make_denoiser(by_default);
  auto b = make_denoiser(by_hand);
  const auto out_a = denoise_sequence(*a, scene, 8, bumps);
  const auto out_b = denoise_sequence(*b, scene, 8, bumps);
  for (int k = 0; k < 8; ++k) test::require_identical(out_a[k], out_b[k], "frame " + std::to_string(k));

  auto changed = [&](auto change) {
    DenoiserConfig c = by_hand;
    change(c.svgf);
    auto d = make_denoiser(c);
    const auto out = denoise_sequence(*d, scene, 8, bumps);
    size_t differing = 0;
    for (int k = 0; k < 8; ++k)
      for (size_t i = 0; i < out[k].data().size(); ++i)
        differing += out[k].data()[i] != out_b[k].data()[i];
    return differing;
  };
  REQUIRE(changed([](SvgfParams& p) { p.iterations = 5; }) > 0);
  REQUIRE(changed([](SvgfParams& p) { p.feedback_tap = 0; }) > 0);
  REQUIRE(changed([](SvgfParams& p) { p.phi_color = 5.f; }) > 0);
  REQUIRE(changed([](SvgfParams& p) { p.phi_normal = 64.f; }) > 0);
  REQUIRE(changed([](SvgfParams& p) { p.phi_depth = 0.5f; }) > 0);
  REQUIRE(changed([](SvgfParams& p) { p.alpha = 0.3f; }) > 0);  // above 1 / length by frame 4
  REQUIRE(changed([](SvgfParams& p) { p.moments_alpha = 0.1f; }) > 0);
  REQUIRE(changed([](SvgfParams& p) { p.spatial_variance_history = 2; }) > 0);
  REQUIRE(changed([](SvgfParams& p) { p.albedo_epsilon = 0.3f; }) > 0);
}

void phi_depth_zero_is_no_depth_term(const TestDevice& device) {
  // Falcor's convention: a zero depth tolerance switches the depth term off (it does not
  // reject every tap with a depth difference). So phi_depth = 0 must give the bits of a depth
  // tolerance so large that every depth term is 0 (phi_depth = FLT_MAX), and differ from 0.01.
  test::SyntheticScene scene;
  auto run = [&](float phi_depth) {
    DenoiserConfig c = config_for(device);
    c.svgf.phi_depth = phi_depth;
    c.svgf.spatial_variance_phi_depth = phi_depth;
    auto d = make_denoiser(c);
    return denoise_sequence(*d, scene, 5);
  };
  // The largest float stands for Inf, which validate() refuses: its terms are < 1e-30.
  const auto zero = run(0.f), inf = run(std::numeric_limits<float>::max()), tiny = run(0.01f);
  size_t differing = 0;
  for (int k = 0; k < 5; ++k) {
    test::require_identical(zero[k], inf[k], "phi_depth 0 vs FLT_MAX, frame " + std::to_string(k));
    for (size_t i = 0; i < zero[k].data().size(); ++i)
      differing += zero[k].data()[i] != tiny[k].data()[i];
  }
  REQUIRE(differing > 0);
}

// --svgf-taa: the frame's output is core/taa.h applied to the output without TAA and the
// previous TAA output, recomputed here on the CPU. The first frame and the first after a reset
// pass through; the SVGF histories are TAA's input, untouched by it.
void taa_follows_remodulation(const TestDevice& device) {
  test::SyntheticScene scene;
  DenoiserConfig with = config_for(device);
  with.svgf.taa = true;
  auto plain = make_denoiser(config_for(device));
  auto taa = make_denoiser(with);
  REQUIRE(taa->stages().back() == svgf_stage::kTaa);
  REQUIRE(plain->stages().back() != svgf_stage::kTaa);
  REQUIRE_THROWS(plain->read_buffer(svgf_buffer::kTaaHistory));  // no TAA, no such buffer
  Image previous;
  for (int k = 0; k < 6; ++k) {
    if (k == 4) {
      plain->reset();
      taa->reset();
    }
    const Frame f = scene.frame(k);
    Image a, b;
    plain->denoise(f, a);
    taa->denoise(f, b);
    INFO("frame " << k);
    for (float v : b.data()) REQUIRE(std::isfinite(v));
    test::require_identical(plain->read_buffer(svgf_buffer::kColorHistory),
                            taa->read_buffer(svgf_buffer::kColorHistory), "color history");
    test::require_identical(taa->read_buffer(svgf_buffer::kTaaHistory), b, "TAA history");
    Image expected(f.width(), f.height(), 3), history_out(f.width(), f.height(), 3);
    TemporalAntiAliasing k_taa;
    k_taa.guides = f.guides();
    k_taa.current = a.rgb();
    k_taa.history = previous.empty() ? a.rgb() : previous.rgb();
    k_taa.history_out = history_out.rgb();
    k_taa.output = expected.rgb();
    k_taa.has_history = k != 0 && k != 4;
    k_taa.alpha = with.svgf.taa_alpha;
    cpu::for_each_pixel(f.width(), f.height(), k_taa);
    require_matches(device, b, expected, "TAA output vs core/taa.h on the output without TAA");
    if (k == 0 || k == 4) test::require_identical(a, b, "a history's first frame passes through");
    else REQUIRE(test::max_relative_difference(a, b, 1e-3) > 1e-4);
    previous = b;
  }
}

// Without EngineConfig::keep_scratch (the default) the illumination, the accumulation and
// A-SVGF's stratum image live in the a-trous buffers' memory, and the color history has one
// slot, overwritten in place (methods/svgf/denoiser.h): the output and every buffer a caller
// can still read are the same bits as with the scratch kept, on every branch the frame takes
// (A-SVGF's gradient samples, a fed-back iteration's or else the variance stage's write of the
// color history, direct and indirect, an indirect signal without a fed-back iteration beside a
// direct one with, TAA, no a-trous iteration, the statistics anti-lag, a reset). The
// illumination and the accumulation are then not debug buffers, and reading one names the
// option.
void shared_scratch_changes_no_bits(const TestDevice& device) {
  test::SyntheticScene scene;
  // Frames with A-SVGF's samples from frame 1 on and, for the split, a third as indirect.
  const auto frame = [&](int k, bool split) {
    Frame f = scene.frame(k);
    scene.add_gradient_samples(f);
    return split ? test::with_split(std::move(f)) : f;
  };
  SvgfParams tap;
  tap.feedback_tap = 1;
  SvgfParams split = tap;
  split.split = SplitMode::On;
  split.indirect_iterations = 5;
  SvgfParams split_unfed = split;  // the variance stage writes the indirect color history
  split_unfed.indirect_iterations = 0;
  SvgfParams taa;
  taa.taa = true;
  SvgfParams none;
  none.iterations = 0;
  SvgfParams statistics = svgf_preset("falcor");
  statistics.antilag = Antilag::Statistics;
  const std::pair<const char*, SvgfParams> settings[] = {
      {"defaults", SvgfParams()},
      {"feedback tap 1", tap},
      {"split", split},
      {"split, indirect without iterations", split_unfed},
      {"taa", taa},
      {"no iteration", none},
      {"falcor, statistics", statistics}};
  for (const auto& [name, p] : settings) {
    DenoiserConfig c = config_for(device);
    c.svgf = p;
    auto shared = make_denoiser(c);
    c.keep_scratch = true;
    auto kept = make_denoiser(c);
    for (const char* scratch : {svgf_buffer::kIllumination, svgf_buffer::kAccumulated}) {
      REQUIRE_THROWS_WITH(shared->read_buffer(scratch), Catch::Contains("keep_scratch"));
      const auto names = shared->debug_buffers();
      REQUIRE(std::find(names.begin(), names.end(), scratch) == names.end());
      REQUIRE(kept->read_buffer(scratch).empty());  // before the first frame
    }
    REQUIRE(kept->debug_buffers().size() == shared->debug_buffers().size() + 2);
    for (int k = 0; k < 6; ++k) {
      if (k == 4) {
        shared->reset();
        kept->reset();
      }
      const Frame f = frame(k, p.split == SplitMode::On);
      Image a, b;
      shared->denoise(f, a);
      kept->denoise(f, b);
      const std::string where = std::string(name) + ", frame " + std::to_string(k);
      test::require_identical(a, b, where + ": output (scratch shared vs kept)");
      for (const std::string& buffer : shared->debug_buffers())
        test::require_identical(shared->read_buffer(buffer), kept->read_buffer(buffer),
                                where + ": " + buffer);
    }
  }
}

// A camera dollying towards a wall changes the depth of every point it sees (by 10% here),
// while nothing in view moves: the reprojection compares the previous depth with the point's
// depth in the previous camera (reproject_camera_depth, core/previous_depth.h), so every pixel
// keeps its history. Compared with the current depth (off, Falcor's test), every pixel loses
// it. Frames carry their cameras; the motion vectors are the dolly's zoom.
void camera_motion_keeps_history(const TestDevice& device) {
  const int w = 48, h = 32;
  const auto camera_at = [&](float z) {
    Camera c;  // looking down -z from (0, 0, z), 60 degrees vertical field of view
    c.world_to_view = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, -z, 0, 0, 0, 1};
    const float ty = 0.57735027f, tx = ty * w / h;
    c.view_to_clip = {1 / tx, 0, 0, 0, 0, 1 / ty, 0, 0, 0, 0, -1.00002f, -0.0200002f, 0, 0, -1, 0};
    return c;
  };
  const float distances[] = {3.6f, 3.3f, 3.f};  // the wall is the plane z = 0
  std::vector<Frame> frames;
  for (int k = 0; k < 3; ++k) {
    Frame f = test::flat_frame(w, h, distances[k]);
    test::fill_uniform(f.color, 0.2f, 0.8f, 40 + k);
    f.index = k;
    f.camera = camera_at(distances[k]);
    // A point at screen offset s from the centre was at s * (now / before) then.
    const float zoom = k > 0 ? distances[k] / distances[k - 1] : 1.f;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const float sx = x + 0.5f - w / 2.f, sy = y + 0.5f - h / 2.f;
        f.motion.at(x, y, 0) = sx * zoom - sx;
        f.motion.at(x, y, 1) = sy * zoom - sy;
      }
    frames.push_back(std::move(f));
  }
  for (bool camera_depth : {true, false}) {
    DenoiserConfig c = config_for(device);
    c.svgf.reproject_camera_depth = camera_depth;
    c.svgf.antilag = Antilag::Off;  // the reprojection's tests alone decide
    auto d = make_denoiser(c);
    Image out;
    for (const Frame& f : frames) d->denoise(f, out);
    const Image length = d->read_buffer(svgf_buffer::kHistoryLength);
    for (float v : out.data()) REQUIRE(std::isfinite(v));
    INFO("reproject_camera_depth " << camera_depth << ", centre pixel's history "
                                   << length.at(w / 2, h / 2, 0));
    for (float v : length.data()) REQUIRE(v == (camera_depth ? 3.f : 1.f));
  }
}

}  // namespace

SVGF_DEVICE_TEST("pipeline: --svgf-taa blends the output with its reprojected, clamped history",
                 "[pipeline]", taa_follows_remodulation)
SVGF_DEVICE_TEST("pipeline: denoising a moving synthetic sequence beats the noisy input",
                 "[pipeline]", beats_noisy_input)
SVGF_DEVICE_TEST("pipeline: without a fed-back iteration the accumulation is the color history",
                 "[pipeline]", accumulation_is_the_history_without_a_tap)
SVGF_DEVICE_TEST("pipeline: the feedback tap is what the next frame reads", "[pipeline]",
                 feedback_tap_is_next_history)
SVGF_DEVICE_TEST("pipeline: NaN, Inf and negative input is counted and does not poison the history",
                 "[pipeline]", bad_input_does_not_poison)
SVGF_DEVICE_TEST("pipeline: reset() restarts the history", "[pipeline]", reset_restarts_history)
SVGF_DEVICE_TEST("pipeline: the scratch shared with the a-trous buffers changes no bits",
                 "[pipeline]", shared_scratch_changes_no_bits)
SVGF_DEVICE_TEST("pipeline: a dollying camera keeps the history of the still wall it sees",
                 "[pipeline]", camera_motion_keeps_history)
SVGF_DEVICE_TEST("pipeline: the defaults are their documented values, as the pipeline uses them",
                 "[pipeline]", defaults_are_documented)
SVGF_DEVICE_TEST("pipeline: phi_depth 0 means no depth term, in the a-trous and the variance stages",
                 "[pipeline]", phi_depth_zero_is_no_depth_term)

// The CPU engine only: thread counts, the FTZ/DAZ guard of its workers, and its refusal of
// fast mode.
TEST_CASE("pipeline: identical bits on 1 and 2 threads and from run to run", "[pipeline][determinism]") {
  test::SyntheticScene scene;
  auto one = make_denoiser(cpu_config(1));
  auto two = make_denoiser(cpu_config(2));
  auto again = make_denoiser(cpu_config(2));
  const auto a = denoise_sequence(*one, scene, 6);
  const auto b = denoise_sequence(*two, scene, 6);
  const auto c = denoise_sequence(*again, scene, 6);
  for (int k = 0; k < 6; ++k) {
    test::require_identical(a[k], b[k], "1 vs 2 threads, frame " + std::to_string(k));
    test::require_identical(b[k], c[k], "run vs rerun, frame " + std::to_string(k));
  }
  test::require_identical(one->read_buffer(svgf_buffer::kColorHistory),
                          two->read_buffer(svgf_buffer::kColorHistory), "color history");
}

TEST_CASE("pipeline: subnormals survive in TBB workers even if the caller flushes them",
          "[pipeline][determinism]") {
  // 1e-39 * 0.5 is subnormal: with FTZ it would become 0.
  Image color(64, 64, 3, 2e-39f), albedo(64, 64, 3, 0.5f), illum(64, 64, 3);
  {
#if defined(SVGF_HAVE_MXCSR)
    const unsigned saved = _mm_getcsr();
    _mm_setcsr(saved | cpu::ScopedIeeeFloat::kFtz | cpu::ScopedIeeeFloat::kDaz);
#endif
    tbb::task_arena arena(2);
    arena.execute([&] {
      cpu::for_each_pixel(64, 64, DemodulateKernel{64, color.rgb(), albedo.rgb(), {}, illum.rgb(), 1e-3f});
    });
#if defined(SVGF_HAVE_MXCSR)
    _mm_setcsr(saved);
#endif
  }
  const float expect = 2e-39f / 0.5f;
  REQUIRE(expect > 0.f);
  for (float v : illum.data()) REQUIRE(v == expect);
}

TEST_CASE("pipeline: bad configurations and size changes are clear errors", "[pipeline]") {
  DenoiserConfig fast = cpu_config(1);
  fast.mode = Mode::Fast;
  REQUIRE_THROWS_WITH(make_denoiser(fast), Catch::Contains("fast mode"));
  auto d = make_denoiser(cpu_config(1));
  Image out;
  d->denoise(test::flat_frame(16, 8), out);
  REQUIRE_THROWS_WITH(d->denoise(test::flat_frame(8, 8), out), Catch::Contains("16x8 to 8x8"));
  Frame broken = test::flat_frame(16, 8);
  broken.albedo = Image(16, 7, 3);
  REQUIRE_THROWS_WITH(d->denoise(broken, out), Catch::Contains("albedo"));
  REQUIRE_THROWS_WITH(parse_backend("gpu"), Catch::Contains("gpu"));
}

// The whole pipeline through the public Denoiser interface: CPU vs CUDA exact bitwise over
// whole sequences (every fixture, plus synthetic ones), CUDA fast within its written tolerance
// of CUDA exact, determinism (runs and block shapes), errors, and a hidden benchmark ([.bench]).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "pipeline/make_denoiser.h"
#include "gpu_test_support.h"
#include "io/sequence.h"
#include "kernels_cuda/cuda_check.h"
#include "kernels_cuda/device_array.h"
#include "kernels_cuda/cuda_denoisers.h"
#include "metrics/image_metrics.h"
#include "synthetic_sequence.h"

using namespace svgf;
using namespace svgf::gpu_test;
using Catch::Matchers::Contains;

namespace {

// Fast mode's tolerance against exact mode, per frame (docs/cuda.md).
constexpr double kFastMaxRelMse = 1e-5;
constexpr double kFastMaxPsnrDelta = 0.05;  // dB, against the frame's reference

DenoiserConfig config(Backend backend, Mode mode = Mode::Exact, int bx = 16, int by = 8) {
  DenoiserConfig c;
  c.backend = backend;
  c.mode = mode;
  c.block_x = bx;
  c.block_y = by;
  return c;
}

// A sequence as the tests consume it: frames on demand, camera cuts.
struct Source {
  std::string name;
  int frames = 0;
  std::function<Frame(int)> frame;
  std::function<bool(int)> cut;
};

std::vector<Source> sources() {
  std::vector<Source> out;
  for (const std::string& dir : fixture_dirs()) {
    auto seq = std::make_shared<io::Sequence>(dir);
    Source s;
    s.name = dir;
    s.frames = frames_to_use(seq->size(), 3);
    s.frame = [seq](int k) { return seq->read(k); };
    s.cut = [seq](int k) { return seq->is_camera_cut(k); };
    out.push_back(s);
  }
  // Synthetic: a moving square at an odd size, with bad samples injected in frame 2 and a camera
  // cut (reset) at frame 6.
  test::SyntheticScene scene;
  scene.width = 203;
  scene.height = 117;
  scene.square = 30;
  Source s;
  s.name = "synthetic 203x117";
  s.frames = frames_to_use(10, 4);
  s.frame = [scene](int k) {
    Frame f = scene.frame(k);
    if (k == 2) {
      f.color.at(10, 10, 0) = std::numeric_limits<float>::quiet_NaN();
      f.color.at(50, 40, 1) = std::numeric_limits<float>::infinity();
      f.color.at(100, 60, 2) = -2.f;
      f.color.at(200, 116, 0) = 3e-39f;  // subnormal: kept, not replaced
      // Bad guides and motion, some at the gradient samples' pixels (every third row and
      // column here): the sanitize stage's guide rule, also where CUDA's fused gradient launch
      // reads the guides before the sanitize stage has run (methods/svgf/pipeline.h).
      const float nan = std::numeric_limits<float>::quiet_NaN();
      for (int y = 0; y < f.height(); y += 7)
        for (int x = (y * 3) % 11; x < f.width(); x += 11) {
          switch ((x + y) % 6) {
            case 0: f.depth.at(x, y, 0) = nan; break;
            case 1: f.depth_gradient.at(x, y, 1) = std::numeric_limits<float>::infinity(); break;
            case 2: for (int c = 0; c < 3; ++c) f.normal.at(x, y, c) *= 3.f; break;
            case 3: for (int c = 0; c < 3; ++c) f.normal.at(x, y, c) = 0.f; break;
            case 4: f.motion.at(x, y, 0) = nan; break;
            default: f.albedo.at(x, y, 2) = 2.f; break;
          }
        }
    }
    scene.add_gradient_samples(f);
    return f;
  };
  s.cut = [](int k) { return k == 6; };
  out.push_back(s);
  return out;
}

void count_values(const Image& im) { tally().frame_values += static_cast<int64_t>(im.data().size()); }

}  // namespace

TEST_CASE("pipeline: CPU vs CUDA exact bitwise over whole sequences; fast within tolerance",
          "[pipeline][fixture]") {
  // The defaults (A-SVGF's gradients on the sequences with gradient samples, the statistics
  // anti-lag on the others), Falcor's values (the defaults until issue 12), and the converging
  // configuration with the statistics anti-lag on every fixture too.
  SvgfParams converge = svgf_preset("converge");
  converge.antilag = Antilag::Statistics;
  // The defaults with TAA after them: only the sequences with gradient samples (the synthetic
  // one, moving-shadow, light-switch).
  SvgfParams taa;
  taa.taa = true;
  // And direct and indirect filtered apart (the frames' color split below), the indirect part
  // with a wider filter.
  SvgfParams split;
  split.split = SplitMode::On;
  split.indirect_iterations = 5;
  split.indirect_phi_color = 20.f;
  // A-SVGF's filter beyond what the CUDA flavors' fused launch takes (methods/svgf/
  // gradient_tile.h): its three passes on CUDA too.
  SvgfParams wide_gradient;
  wide_gradient.gradient_iterations = 3;
  wide_gradient.gradient_lambda_radius = 2;
  struct Setting {
    std::string name;
    SvgfParams params;
    bool needs_gradients;
  };
  const Setting settings[] = {{"defaults", SvgfParams(), false},
                              {"falcor", svgf_preset("falcor"), false},
                              {"converge + statistics antilag", converge, false},
                              {"defaults + taa", taa, true},
                              {"gradient, 3 steps, lambda radius 2", wide_gradient, true},
                              {"split", split, false}};
  // The CPU keeps its scratch (EngineConfig::keep_scratch) and is compared buffer by buffer
  // with the CUDA denoisers; these keep theirs on every other sequence and share it with the
  // a-trous buffers on the rest (the default), where they have fewer buffers to compare.
  int sequence = 0;
  for (const auto& [setting, params, needs_gradients] : settings)
  for (const Source& src : sources()) {
    if (needs_gradients && src.frames > 1 && src.frame(1).gradient.empty())
      continue;
    const bool cuda_keeps_scratch = sequence++ % 2 == 1;
    tally().sequences.push_back(src.name + " (" + std::to_string(src.frames) + " frames, " +
                                setting + (cuda_keeps_scratch ? "" : ", scratch shared") + ")");
    const auto make = [&, params = params](Backend b, Mode m) {
      DenoiserConfig c = config(b, m);
      c.svgf = params;
      c.keep_scratch = b == Backend::Cpu || cuda_keeps_scratch;
      return make_denoiser(c);
    };
    auto cpu = make(Backend::Cpu, Mode::Exact);
    auto exact = make(Backend::Cuda, Mode::Exact);
    auto fast = make(Backend::Cuda, Mode::Fast);
    for (int k = 0; k < src.frames; ++k) {
      const Frame f = params.split == SplitMode::On ? test::with_split(src.frame(k)) : src.frame(k);
      const std::string where = src.name + " (" + setting + "), frame " + std::to_string(k);
      if (k > 0 && src.cut(k)) {
        cpu->reset();
        exact->reset();
        fast->reset();
      }
      Image out_cpu, out_exact, out_fast;
      cpu->denoise(f, out_cpu);
      exact->denoise(f, out_exact);
      fast->denoise(f, out_fast);

      test::require_identical(out_cpu, out_exact, where + ": output (CPU vs CUDA exact)");
      count_values(out_cpu);
      INFO(where);
      REQUIRE(cpu->last_report().replaced_samples == exact->last_report().replaced_samples);
      REQUIRE(fast->last_report().replaced_samples == exact->last_report().replaced_samples);
      for (const Denoiser* d : {exact.get(), fast.get()}) {
        const InputRepairs a = cpu->last_report().repairs, b = d->last_report().repairs;
        REQUIRE(a.albedo == b.albedo);
        REQUIRE(a.normal == b.normal);
        REQUIRE(a.surface == b.surface);
        REQUIRE(a.motion == b.motion);
      }
      for (const std::string& name : exact->debug_buffers()) {
        const Image a = cpu->read_buffer(name);
        test::require_identical(a, exact->read_buffer(name), where + ": " + name);
        count_values(a);
      }
      tally().frames += 1;

      // Fast mode: the history decisions are exact mode's (same reprojection code and flags),
      // the filtered values within tolerance.
      test::require_identical(fast->read_buffer(svgf_buffer::kHistoryLength),
                              exact->read_buffer(svgf_buffer::kHistoryLength),
                              where + ": fast history length");
      if (cuda_keeps_scratch)
        test::require_identical(fast->read_buffer(svgf_buffer::kIllumination),
                                exact->read_buffer(svgf_buffer::kIllumination),
                                where + ": fast illumination");
      for (float v : out_fast.data()) REQUIRE(std::isfinite(v));
      const double rel = metrics::relmse(out_fast, out_exact);
      double delta = 0;
      if (f.has_reference())
        delta = std::fabs(metrics::psnr(out_fast, f.reference) - metrics::psnr(out_exact, f.reference));
      Tally& t = tally();
      t.fast_frames += 1;
      if (rel >= t.fast_worst_relmse) {
        t.fast_worst_relmse = rel;
        t.fast_worst_relmse_at = where;
      }
      if (f.has_reference() && delta >= t.fast_worst_psnr_delta) {
        t.fast_worst_psnr_delta = delta;
        t.fast_worst_psnr_at = where;
      }
      INFO("fast vs exact: relMSE " << rel << ", PSNR delta " << delta << " dB");
      REQUIRE(rel <= kFastMaxRelMse);
      REQUIRE(delta <= kFastMaxPsnrDelta);
    }
  }
}

TEST_CASE("parameter sweep: CPU vs CUDA exact bitwise, fast within tolerance, every setting",
          "[pipeline][sweep]") {
  // Fast mode runs the exact mode's functors with other arithmetic and storage, and its own
  // fusion choices (which iteration feeds back, which remodulates): every iteration count
  // 0-6 with every feedback tap -1..iterations, and edge-stopping parameters at 0 and large.
  test::SyntheticScene scene;
  scene.width = 61;
  scene.height = 37;
  scene.square = 12;
  const int frames = options().reduced ? 3 : 5;
  std::vector<std::pair<std::string, SvgfParams>> settings;
  for (int it = 0; it <= 6; ++it)
    for (int tap = -1; tap <= it; ++tap) {
      SvgfParams p;
      p.iterations = it;
      p.feedback_tap = tap;
      settings.emplace_back("iterations " + std::to_string(it) + " tap " + std::to_string(tap), p);
    }
  auto with = [&](const std::string& name, auto change) {
    SvgfParams p;
    change(p);
    settings.emplace_back(name, p);
  };
  with("phi_depth 0", [](SvgfParams& p) { p.phi_depth = 0.f; p.spatial_variance_phi_depth = 0.f; });
  with("phi_depth 1e6", [](SvgfParams& p) { p.phi_depth = 1e6f; });
  with("phi_normal 0", [](SvgfParams& p) { p.phi_normal = 0.f; });
  with("phi_normal 1024", [](SvgfParams& p) { p.phi_normal = 1024.f; });
  with("phi_normal 100 (not 2^m)", [](SvgfParams& p) { p.phi_normal = 100.f; });
  with("phi_color 1e6", [](SvgfParams& p) { p.phi_color = 1e6f; });
  with("phi_color 0.5", [](SvgfParams& p) { p.phi_color = 0.5f; });
  with("preset paper", [](SvgfParams& p) { p = svgf_preset("paper"); });
  with("preset converge", [](SvgfParams& p) { p = svgf_preset("converge"); });
  with("antilag, relative 0", [](SvgfParams& p) {
    p.antilag = Antilag::Statistics;
    p.antilag_relative = 0.f;
  });
  for (const auto& [name, p] : settings) {
    DenoiserConfig c = config(Backend::Cpu);
    c.svgf = p;
    auto cpu = make_denoiser(c);
    c.backend = Backend::Cuda;
    auto exact = make_denoiser(c);
    c.mode = Mode::Fast;
    auto fast = make_denoiser(c);
    for (int k = 0; k < frames; ++k) {
      const Frame f = scene.frame(k);
      Image a, b, d;
      cpu->denoise(f, a);
      exact->denoise(f, b);
      fast->denoise(f, d);
      const std::string where = name + ", frame " + std::to_string(k);
      test::require_identical(a, b, where + ": output (CPU vs CUDA exact)");
      test::require_identical(cpu->read_buffer(svgf_buffer::kColorHistory),
                              exact->read_buffer(svgf_buffer::kColorHistory),
                              where + ": color history (CPU vs CUDA exact)");
      const double rel = metrics::relmse(d, b);
      const double rel_history = metrics::relmse(fast->read_buffer(svgf_buffer::kColorHistory),
                                                 exact->read_buffer(svgf_buffer::kColorHistory));
      INFO(where << ": fast vs exact relMSE " << rel << ", color history " << rel_history);
      for (float v : d.data()) REQUIRE(std::isfinite(v));
      REQUIRE(rel <= kFastMaxRelMse);
      REQUIRE(rel_history <= kFastMaxRelMse);
      if (rel >= tally().fast_worst_relmse) {
        tally().fast_worst_relmse = rel;
        tally().fast_worst_relmse_at = "sweep " + where;
      }
      tally().fast_frames += 1;
      tally().frames += 1;
      count_values(a);
    }
  }
}

// A single-frame method on the three devices over the first `frames` frames of a source: the
// CPU and CUDA exact give the same bits (output and every debug buffer) and the same replaced
// sample count, fast mode stays within the pipeline tolerance. `configure` sets the method
// and its parameters on a config.
void compare_method(const Source& src, int frames,
                    const std::function<void(DenoiserConfig&)>& configure) {
  auto with = [&](Backend b, Mode m) {
    DenoiserConfig c = config(b, m, 13, 7);
    configure(c);
    return make_denoiser(c);
  };
  auto cpu = with(Backend::Cpu, Mode::Exact);
  auto exact = with(Backend::Cuda, Mode::Exact);
  auto fast = with(Backend::Cuda, Mode::Fast);
  for (int k = 0; k < std::min(src.frames, frames); ++k) {
    const Frame f = src.frame(k);
    const std::string where = src.name + ", frame " + std::to_string(k) + ", " + cpu->description();
    Image a, b, c;
    cpu->denoise(f, a);
    exact->denoise(f, b);
    fast->denoise(f, c);
    test::require_identical(a, b, where + ": output (CPU vs CUDA exact)");
    for (const std::string& name : cpu->debug_buffers())
      test::require_identical(cpu->read_buffer(name), exact->read_buffer(name), where + ": " + name);
    INFO(where);
    REQUIRE(cpu->last_report().replaced_samples == exact->last_report().replaced_samples);
    REQUIRE(fast->last_report().replaced_samples == exact->last_report().replaced_samples);
    for (float v : c.data()) REQUIRE(std::isfinite(v));
    REQUIRE(metrics::relmse(c, b) <= kFastMaxRelMse);
    count_values(a);
  }
}

TEST_CASE("gaussian: CPU vs CUDA exact bitwise, fast within tolerance, every source",
          "[pipeline][gaussian]") {
  for (const Source& src : sources())
    for (const std::pair<float, int>& setting : {std::pair<float, int>{2.f, 0}, {5.f, 3}})
      compare_method(src, 3, [&](DenoiserConfig& c) {
        c.method = Method::Gaussian;
        c.gaussian.sigma = setting.first;
        c.gaussian.radius = setting.second;
      });
}

TEST_CASE("wavelet: CPU vs CUDA exact bitwise, fast within tolerance, every source and size",
          "[pipeline][wavelet]") {
  // Every kernel size, and non-default sigmas (sigma_N not a power of 2: the det_pow path).
  struct Setting {
    int kernel_size, iterations;
    float sigma_normal, sigma_luma;
  };
  for (const Source& src : sources())
    for (const Setting s : {Setting{3, 4, 64.f, 4.f}, Setting{5, 4, 64.f, 4.f},
                            Setting{7, 3, 100.f, 2.f}, Setting{9, 2, 64.f, 8.f},
                            Setting{5, 0, 64.f, 4.f}})
      compare_method(src, 2, [&](DenoiserConfig& c) {
        c.method = Method::Wavelet;
        c.wavelet.kernel_size = s.kernel_size;
        c.wavelet.iterations = s.iterations;
        c.wavelet.sigma_normal = s.sigma_normal;
        c.wavelet.sigma_luma = s.sigma_luma;
      });
}

TEST_CASE("jbf: CPU vs CUDA exact bitwise, fast within tolerance, both forms, every source",
          "[pipeline][jbf]") {
  struct Setting {
    Method method;
    int radius, levels;
    float sigma_color;
  };
  for (const Source& src : sources())
    for (const Setting s : {Setting{Method::Jbf, 16, 0, 0.6f}, Setting{Method::Jbf, 5, 0, 2.f},
                            Setting{Method::JbfAtrous, 16, 4, 0.6f},
                            Setting{Method::JbfAtrous, 16, 2, 2.f}})
      compare_method(src, 2, [&](DenoiserConfig& c) {
        c.method = s.method;
        c.jbf.radius = s.radius;
        c.jbf.levels = s.levels;
        c.jbf.sigma_color = s.sigma_color;
      });
}

TEST_CASE("bmfr: CPU vs CUDA exact bitwise, fast within tolerance, both strategies (skip with TAA), every source",
          "[pipeline][bmfr]") {
  for (const Source& src : sources())
    for (BmfrRankStrategy s : {BmfrRankStrategy::Noise, BmfrRankStrategy::Skip})
      compare_method(src, 6, [&](DenoiserConfig& c) {
        c.method = Method::Bmfr;
        c.bmfr.rank_strategy = s;
        c.bmfr.taa = s == BmfrRankStrategy::Skip;  // TAA (core/taa.h) on one of the two
      });
}

TEST_CASE("determinism: two runs and three block shapes give the same bits, exact and fast",
          "[determinism]") {
  std::vector<Source> all = sources();
  // The first fixture (if any) and the synthetic sequence.
  std::vector<Source> use = {all.back()};
  if (all.size() > 1) use.insert(use.begin(), all.front());
  const int shapes[][2] = {{16, 8}, {16, 8}, {32, 4}, {13, 7}};  // 16x8 twice: run to run
  for (const Source& src : use)
    for (Mode mode : {Mode::Exact, Mode::Fast}) {
      std::vector<std::unique_ptr<Denoiser>> ds;
      for (const auto& s : shapes) ds.push_back(make_denoiser(config(Backend::Cuda, mode, s[0], s[1])));
      const int frames = std::min(src.frames, options().reduced ? 3 : 8);
      for (int k = 0; k < frames; ++k) {
        const Frame f = src.frame(k);
        std::vector<Image> outs(ds.size());
        for (size_t d = 0; d < ds.size(); ++d) {
          if (k > 0 && src.cut(k)) ds[d]->reset();
          ds[d]->denoise(f, outs[d]);
        }
        for (size_t d = 1; d < ds.size(); ++d) {
          const std::string where = src.name + ", " + to_string(mode) + ", frame " +
                                    std::to_string(k) + ", block " + std::to_string(shapes[d][0]) +
                                    "x" + std::to_string(shapes[d][1]) + " vs the first 16x8 run";
          test::require_identical(outs[0], outs[d], where);
          test::require_identical(ds[0]->read_buffer(svgf_buffer::kColorHistory),
                                  ds[d]->read_buffer(svgf_buffer::kColorHistory),
                                  where + ": color history");
        }
        tally().determinism_frames += 1;
      }
    }
}

TEST_CASE("interface: Backend::Auto picks CUDA and says so; descriptions", "[interface]") {
  std::string why;
  REQUIRE(cuda_available(&why));
  auto a = make_denoiser(config(Backend::Auto, Mode::Fast));
  INFO(a->description());
  REQUIRE_THAT(a->description(), Contains("svgf cuda fast"));
  auto e = make_denoiser(config(Backend::Cuda, Mode::Exact, 13, 7));
  REQUIRE_THAT(e->description(), Contains("svgf cuda exact"));
  REQUIRE_THAT(e->description(), Contains("13x7"));
  // Before the first frame there is nothing to read back (as on the CPU).
  REQUIRE(e->read_buffer(svgf_buffer::kHistoryLength).empty());
}

TEST_CASE("errors: size change and bad block shapes are clear errors", "[errors]") {
  for (Mode mode : {Mode::Exact, Mode::Fast}) {
    auto d = make_denoiser(config(Backend::Cuda, mode));
    Image out;
    d->denoise(test::flat_frame(16, 8), out);
    REQUIRE_THROWS_WITH(d->denoise(test::flat_frame(8, 8), out),
                        Contains("frame size changed mid-sequence from 16x8 to 8x8"));
    Frame broken = test::flat_frame(16, 8);
    broken.albedo = Image(16, 7, 3);
    REQUIRE_THROWS_WITH(d->denoise(broken, out), Contains("albedo"));
    d->denoise(test::flat_frame(16, 8), out);  // still usable after refusing bad input
    for (float v : out.data()) REQUIRE(std::isfinite(v));
  }
  REQUIRE_THROWS_WITH(make_denoiser(config(Backend::Cuda, Mode::Exact, 0, 8)), Contains("empty"));
  REQUIRE_THROWS_WITH(make_denoiser(config(Backend::Cuda, Mode::Exact, 64, 32)),
                      Contains("threads per block"));
}

// These provoke real CUDA errors, which compute-sanitizer reports as API errors by design, so the
// sanitizer runs leave them out ("~[cuda-errors]~[bench]": an exclusion-only Catch2 filter would
// also select the hidden benchmark).
TEST_CASE("errors: CUDA failures are CudaError naming the kernel or the buffer",
          "[errors][cuda-errors]") {
  SECTION("a refused launch names the kernel") {
    Image color(8, 8, 3, 1.f), albedo(8, 8, 3, 0.5f);
    cuda::DeviceArray<float> c(color.data().data(), color.data().size());
    cuda::DeviceArray<float> a(albedo.data().data(), albedo.data().size());
    cuda::DeviceArray<float> out(color.data().size());
    auto rgb = [](float* p) { return RgbView{p, p + 64, p + 128}; };
    const DemodulateKernel k{8, rgb(c.get()), rgb(a.get()), {}, rgb(out.get()), 1e-3f};
    try {
      cuda::run(k, 8, 8, cuda::LaunchShape{64, 32}, "demodulate");  // 2048 threads: more than a block holds
      FAIL("no error");
    } catch (const cuda::CudaError& e) {
      INFO(e.what());
      REQUIRE_THAT(e.what(), Contains("kernel 'demodulate'") && Contains("block 64x32"));
      // CUDA 13 on an H100 answers cudaErrorInvalidValue; older stacks said InvalidConfiguration.
      REQUIRE((e.code() == cudaErrorInvalidValue || e.code() == cudaErrorInvalidConfiguration));
    }
    REQUIRE(cuda::run(k, 8, 8) == 0);  // the device is fine afterwards
  }
  SECTION("an impossible allocation names cudaMalloc and the size") {
    try {
      cuda::DeviceArray<float> huge(size_t(1) << 46);  // 256 TiB
      FAIL("no error");
    } catch (const cuda::CudaError& e) {
      REQUIRE_THAT(e.what(), Contains("cudaMalloc"));
      REQUIRE(e.code() == cudaErrorMemoryAllocation);
    }
  }
  SECTION("out of device memory while a denoiser sets up: a clear error, then recovery") {
    size_t free_bytes = 0, total = 0;
    cuda::check(cudaMemGetInfo(&free_bytes, &total), "cudaMemGetInfo");
    // Leave ~256 MiB free; a 4096x4096 frame needs ~4 GiB of buffers.
    std::vector<cuda::DeviceArray<char>> filler;
    size_t left = free_bytes > (size_t(256) << 20) ? free_bytes - (size_t(256) << 20) : 0;
    while (left >= (size_t(64) << 20)) {
      const size_t chunk = std::min(left, size_t(4) << 30);
      try {
        filler.emplace_back(chunk);
      } catch (const cuda::CudaError&) {
        break;
      }
      left -= chunk;
    }
    auto d = make_denoiser(config(Backend::Cuda));
    Image out;
    const Frame big = test::flat_frame(4096, 4096);
    try {
      d->denoise(big, out);
      FAIL("no error");
    } catch (const cuda::CudaError& e) {
      INFO(e.what());
      REQUIRE_THAT(e.what(), Contains("4096x4096 frames need about"));
      REQUIRE(e.code() == cudaErrorMemoryAllocation);
    }
    filler.clear();
    d->denoise(big, out);  // memory is back: the same denoiser now works
    REQUIRE(out.width() == 4096);
  }
}

// ---------------------------------------------------------------------------------------------
// Speed: exact vs fast per stage at 1080p and 4K (synthetic frames), CPU exact at 1080p for
// scale. Not a correctness test; run with `svgf_gpu_tests "[.bench]"`.

namespace {

struct Timing {
  double median_filter_ms = 0;
  std::vector<std::pair<std::string, double>> median_stages;
};

Timing time_denoiser(Denoiser& d, const std::vector<Frame>& frames, int warmup, int reps) {
  Image out;
  for (int k = 0; k < warmup; ++k) d.denoise(frames[k % frames.size()], out);
  std::vector<StageTimes> all;
  for (int k = 0; k < reps; ++k) {
    d.denoise(frames[(warmup + k) % frames.size()], out);
    all.push_back(d.last_report().times);
  }
  Timing t;
  std::vector<double> v;
  for (const auto& s : all) v.push_back(s.filter_ms());
  std::sort(v.begin(), v.end());
  t.median_filter_ms = v[v.size() / 2];
  for (const std::string& stage : d.stages()) {
    std::vector<double> u;
    for (const auto& x : all) u.push_back(x[stage]);
    std::sort(u.begin(), u.end());
    t.median_stages.emplace_back(stage, u[u.size() / 2]);
  }
  return t;
}

void print_timing(const char* what, const Timing& t) {
  std::printf("%-28s filter %8.3f ms |", what, t.median_filter_ms);
  for (const auto& [stage, ms] : t.median_stages) std::printf(" %s %.3f", stage.c_str(), ms);
  std::printf("\n");
}

}  // namespace

TEST_CASE("bench: exact vs fast", "[.bench]") {
  struct Res {
    int w, h;
  };
  for (Res r : {Res{1920, 1080}, Res{3840, 2160}}) {
    test::SyntheticScene scene;
    scene.width = r.w;
    scene.height = r.h;
    scene.square = r.h / 4;
    scene.speed = 3;
    std::vector<Frame> frames;
    for (int k = 0; k < 4; ++k) frames.push_back(scene.frame(k));
    std::printf("\n%dx%d, median of 30 frames after 10 (ms):\n", r.w, r.h);
    for (auto shape : {std::pair<int, int>{16, 8}, std::pair<int, int>{32, 8}}) {
      auto exact = make_denoiser(config(Backend::Cuda, Mode::Exact, shape.first, shape.second));
      auto fast = make_denoiser(config(Backend::Cuda, Mode::Fast, shape.first, shape.second));
      const Timing te = time_denoiser(*exact, frames, 10, 30);
      const Timing tf = time_denoiser(*fast, frames, 10, 30);
      const std::string b = " " + std::to_string(shape.first) + "x" + std::to_string(shape.second);
      print_timing(("cuda exact" + b).c_str(), te);
      print_timing(("cuda fast" + b).c_str(), tf);
      std::printf("fast speed-up%s: %.2fx\n", b.c_str(), te.median_filter_ms / tf.median_filter_ms);
    }
    if (r.w == 1920) {
      auto cpu = make_denoiser(config(Backend::Cpu));
      print_timing(cpu->description().c_str(), time_denoiser(*cpu, frames, 1, 3));
    }
  }
}

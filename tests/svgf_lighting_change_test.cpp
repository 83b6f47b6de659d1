// Issue 12's "done when" for moving light (docs/svgf.md: Moving shadows and light changes),
// measured with metrics/lighting_change.h:
//  - shadow contrast: on `moving-shadow`, the output's shadow contrast within 25% of the
//    reference's at every frame from the 3rd on (the shadow moves every frame), on the committed
//    96x96 fixture and rendered here at 192x192 (8 frames, 64-sample references);
//  - lag: on the committed `light-switch` fixture (a light goes off at frame 6), frames until
//    the error over the pixels whose reference changed is back within 1 dB of where it stood
//    at the same age before the change, at most 2.
// Each measure is also shown to fail for Falcor's configuration (the defaults until issue 12),
// so the scenes test what they claim. CPU exact; CUDA exact gives the same bits
// (tests/gpu_test_pipeline.cpp).
#include <cmath>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "gbuffer/renderer.h"
#include "gbuffer/scenes.h"
#include "io/exr_frame.h"
#include "io/sequence.h"
#include "metrics/lighting_change.h"
#include "pipeline/make_denoiser.h"

using namespace svgf;

namespace {

struct Sequence {
  std::vector<Frame> frames;
  std::vector<Image> references;
  std::vector<std::vector<uint32_t>> mesh_ids;
  void add(Frame f) {
    references.push_back(f.reference);
    mesh_ids.push_back(f.mesh_id);
    frames.push_back(std::move(f));
  }
};

const Sequence& moving_shadow_192() {
  static const Sequence seq = [] {
    Sequence s;
    gbuffer::RenderSettings settings;
    settings.width = settings.height = 192;
    settings.reference_spp = 64;
    settings.split = false;
    settings.gradients = true;
    const gbuffer::Renderer renderer;
    const gbuffer::SceneDesc& desc = gbuffer::find_scene("moving-shadow");
    for (int k = 0; k < 8; ++k) s.add(renderer.render(desc, k, settings));
    return s;
  }();
  return seq;
}

Sequence committed(const std::string& scene) {
  const std::string dir = std::string(SVGF_SOURCE_DIR) + "/fixtures/" + scene;
  const io::Manifest m = io::read_manifest(dir);
  Sequence s;
  for (const auto& f : m.frames) s.add(io::read_frame(dir + "/" + f.name));
  return s;
}

std::vector<Image> denoise(const Sequence& seq, const SvgfParams& params) {
  DenoiserConfig c;
  c.svgf = params;
  c.threads = 2;
  auto denoiser = make_denoiser(c);
  std::vector<Image> out(seq.frames.size());
  for (size_t k = 0; k < seq.frames.size(); ++k) denoiser->denoise(seq.frames[k], out[k]);
  return out;
}

// The output's contrast over the reference's, per frame.
std::vector<double> contrast_ratios(const Sequence& seq, const std::vector<Image>& out) {
  const metrics::ShadowFinder finder(seq.references, seq.mesh_ids);
  std::vector<double> r;
  for (size_t k = 0; k < out.size(); ++k) {
    const metrics::ShadowRegions regions = finder.regions(k);
    r.push_back(metrics::shadow_contrast(out[k], regions) /
                metrics::shadow_contrast(seq.references[k], regions));
  }
  return r;
}

std::string list(const std::vector<double>& v) {
  std::string s;
  char buf[24];
  for (double x : v) {
    std::snprintf(buf, sizeof buf, " %.3f", x);
    s += buf;
  }
  return s;
}

bool within_from(const std::vector<double>& ratios, size_t first, double low, double high) {
  for (size_t k = first; k < ratios.size(); ++k)
    if (!(ratios[k] >= low && ratios[k] <= high)) return false;
  return true;
}

// 10 log10 relMSE over the pixels whose reference changed at `change`, per frame.
std::vector<double> changed_error_db(const Sequence& seq, const std::vector<Image>& out,
                                     size_t change) {
  const metrics::PixelMask changed =
      metrics::changed_pixels(seq.references[change - 1], seq.references[change],
                              seq.mesh_ids[change - 1], seq.mesh_ids[change]);
  REQUIRE(changed.count > seq.references[0].pixel_count() / 10);
  std::vector<double> e;
  for (size_t k = 0; k < out.size(); ++k)
    e.push_back(10.0 * std::log10(metrics::relmse_in(out[k], seq.references[k], changed)));
  return e;
}

}  // namespace

TEST_CASE("svgf: the defaults keep a moving shadow's contrast within 25% from the 3rd frame",
          "[svgf][lighting]") {
  const Sequence& seq = moving_shadow_192();
  const std::vector<double> def = contrast_ratios(seq, denoise(seq, svgf_preset("default")));
  INFO("defaults, output / reference contrast per frame:" << list(def));
  CHECK(within_from(def, 3, 0.75, 1.25));
  const std::vector<double> falcor = contrast_ratios(seq, denoise(seq, svgf_preset("falcor")));
  INFO("falcor:" << list(falcor));
  CHECK_FALSE(within_from(falcor, 3, 0.75, 1.25));
}

TEST_CASE("svgf: on the committed moving-shadow the defaults keep its contrast within 25%",
          "[svgf][lighting]") {
  const Sequence seq = committed("moving-shadow");
  const std::vector<double> def = contrast_ratios(seq, denoise(seq, svgf_preset("default")));
  INFO("defaults, output / reference contrast per frame:" << list(def));
  CHECK(within_from(def, 3, 0.75, 1.25));
  const std::vector<double> falcor = contrast_ratios(seq, denoise(seq, svgf_preset("falcor")));
  INFO("falcor:" << list(falcor));
  CHECK_FALSE(within_from(falcor, 3, 0.75, 1.25));
}

TEST_CASE("svgf: after a light switches off the defaults lag at most 2 frames",
          "[svgf][lighting]") {
  const Sequence seq = committed("light-switch");
  constexpr size_t kChange = 6;  // gbuffer/scenes.cpp: light-a goes off at frame 6
  const std::vector<double> def =
      changed_error_db(seq, denoise(seq, svgf_preset("default")), kChange);
  INFO("defaults, changed pixels' relMSE per frame (dB):" << list(def));
  const int lag = metrics::lag_frames(def, metrics::restart_baseline(def, kChange), kChange);
  CHECK(lag >= 0);
  CHECK(lag <= 2);
  const std::vector<double> falcor =
      changed_error_db(seq, denoise(seq, svgf_preset("falcor")), kChange);
  INFO("falcor:" << list(falcor));
  const int falcor_lag =
      metrics::lag_frames(falcor, metrics::restart_baseline(falcor, kChange), kChange);
  CHECK((falcor_lag < 0 || falcor_lag > 2));
}

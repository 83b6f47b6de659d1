#include "bench/stability.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <stdexcept>

#include "bench/baselines.h"
#include "bench/quality.h"
#include "bench/stability_inputs.h"
#include "metrics/detail.h"
#include "metrics/disocclusion.h"
#include "metrics/image_metrics.h"
#include "metrics/lighting_change.h"
#include "metrics/outlier_spread.h"

namespace fs = std::filesystem;

namespace svgf::bench {
namespace {

using json = nlohmann::json;

// Frames the temporal and detail measures average over: from 4 on, when every method's history
// has settled past its first frames (issue 12's convergence rule starts there too).
constexpr int kSettled = 4;
constexpr int kFireflyFrame = 6;
constexpr double kFireflyGain = 1000.0;
constexpr int kFireflyWindow = 16;  // pixels either side of the outlier: how long is timed there
// Issue 12's lag bar, also held to the other "frames until" measures.
constexpr int kMaxLag = 2;

std::string num(double v, int decimals) {
  if (std::isnan(v)) return "n/a";
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

std::string signed_num(double v, int decimals) {
  if (std::isnan(v)) return "n/a";
  char buf[48];
  std::snprintf(buf, sizeof buf, "%+.*f", decimals, v);
  return buf;
}

std::string list(const std::vector<double>& v, int decimals, size_t first = 0) {
  std::string s;
  for (size_t k = first; k < v.size(); ++k) s += (s.empty() ? "" : " ") + num(v[k], decimals);
  return s;
}

json finite_or_null(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

json array(const std::vector<double>& v) {
  json a = json::array();
  for (double x : v) a.push_back(finite_or_null(x));
  return a;
}

double db(double relmse) { return 10.0 * std::log10(relmse); }

std::string frames_text(long n) { return std::to_string(n) + (n == 1 ? " frame" : " frames"); }

// "2 frames", or "never within the 6 frames after" for -1.
std::string lag_text(int lag, size_t change, size_t frames) {
  if (lag >= 0) return frames_text(lag);
  return "never within the " + std::to_string(frames - change) + " frames after";
}

Outcome verdict(bool pass) { return pass ? Outcome::Pass : Outcome::Fail; }

// Keeps the frame the page shows of a failed row (ScenarioResult::shown_*). The OpenCV
// baselines' outputs are left out: reference points, not methods of the suite, and the images
// are committed.
void keep_if_failed(ScenarioResult& r, const StabilityMethod& m, const StabilityRow& row,
                    const StabilitySequence& seq, const std::vector<Image>& out) {
  if (row.verdict != Outcome::Fail || r.shown_frame < 0 || !m.config.project()) return;
  const size_t k = static_cast<size_t>(r.shown_frame);
  if (k >= out.size() || k >= seq.frames.size()) return;
  if (r.shown_failures.empty()) {
    r.shown_input = seq.frames[k].color;
    r.shown_reference = seq.frames[k].reference;
  }
  r.shown_failures.emplace_back(row.method, out[k]);
}

// What every scenario shares: the options, the methods, the fixtures read once.
class Suite {
 public:
  explicit Suite(const StabilityOptions& o)
      : options_(o), methods_(stability_methods(o.backend, o.threads)) {
    if (!o.methods.empty()) {
      std::vector<StabilityMethod> picked;
      for (const std::string& name : o.methods) {
        const auto it = std::find_if(methods_.begin(), methods_.end(),
                                     [&](const StabilityMethod& m) { return m.name == name; });
        if (it == methods_.end()) {
          std::string known;
          for (const StabilityMethod& m : methods_) known += (known.empty() ? "" : ", ") + m.name;
          throw std::invalid_argument("stability: unknown method '" + name + "' (known: " + known +
                                      ")");
        }
        picked.push_back(*it);
      }
      methods_ = picked;
    }
  }

  const StabilityOptions& options() const { return options_; }
  const std::vector<StabilityMethod>& methods() const { return methods_; }

  const StabilitySequence& fixture(const std::string& name) {
    auto it = fixtures_.find(name);
    if (it == fixtures_.end())
      it = fixtures_.emplace(name, fixture_sequence(options_.fixtures_root, name)).first;
    return it->second;
  }

  StabilitySequence render(const std::string& scene, int w, int h, int frames, int spp) const {
    return rendered_sequence(scene, w, h, frames, spp, options_.threads, options_.cache_dir,
                             options_.quiet);
  }

  // One row per method: `measure` turns the method's outputs into a row (method name set here).
  // A method that throws gets a row saying so, and the others still run.
  using Measure = std::function<StabilityRow(const StabilityMethod&, const std::vector<Image>&)>;
  void each_method(ScenarioResult& r, const StabilitySequence& seq, const Measure& measure) const {
    for (const StabilityMethod& m : methods_) {
      if (!options_.quiet) std::fprintf(stderr, "  %s: %s\n", r.name.c_str(), m.name.c_str());
      StabilityRow row;
      std::vector<Image> out;
      try {
        out = denoise_sequence(m.config, seq);
        row = measure(m, out);
      } catch (const std::exception& e) {
        row = StabilityRow{};
        row.value = std::string("did not run: ") + e.what();
        row.verdict = Outcome::NotMeasured;
      }
      row.method = m.name;
      keep_if_failed(r, m, row, seq, out);
      r.rows.push_back(std::move(row));
    }
  }

 private:
  StabilityOptions options_;
  std::vector<StabilityMethod> methods_;
  std::map<std::string, StabilitySequence> fixtures_;
};

ScenarioResult moving_shadow(Suite& suite) {
  const RenderedSizes& z = suite.options().sizes;
  ScenarioResult r;
  r.name = "moving-shadow";
  r.title = "Moving shadow";
  r.measure =
      "the output's shadow contrast over the reference's, per frame (metrics/lighting_change.h: "
      "1 - mean luminance in the shadow / mean luminance of the lit pixels within 4 pixels of "
      "it); the shadow moves every frame";
  r.threshold = "0.75 to 1.25 at every frame from the 3rd on (issue 12: within 25% of the "
                "reference's contrast at every frame after the 3rd following a change)";
  r.bar = "0.75..1.25 from frame 3";
  r.reading =
      "Methods that keep a long history without anti-lag (`svgf falcor`, `svgf paper`, `svgf "
      "converge`, `bmfr`) blend the shadow's old places into the new one: the ratio falls frame "
      "after frame, below 0 once the old place is darker than the shadow. SVGF's defaults restart "
      "the pixels whose shading changed from the gradient samples. Filters whose footprint reaches "
      "across the shadow's edge lighten it with or without history: the JBF (a 33x33 window, "
      "weighted by colour with sigma 0.6) keeps 55-70% of it after the first frame. The a-trous "
      "wavelet (4 passes of 5x5, 31 px) keeps three quarters or more: the shadow (a 1 m slab's, "
      "about 110 px across at 192x192) is wider than its footprint, as shadows at 1080p are.";
  if (!stability_can_render()) {
    r.skipped = "this build has no renderer";
    return r;
  }
  const StabilitySequence seq = suite.render("moving-shadow", z.shadow_width, z.shadow_height,
                                             z.shadow_frames, z.shadow_reference_spp);
  r.input = seq.description;
  const std::vector<Image> refs = seq.references();
  const std::vector<std::vector<uint32_t>> meshes = seq.mesh_ids();
  const metrics::ShadowFinder finder(refs, meshes);
  std::vector<metrics::ShadowRegions> regions;
  std::vector<double> ref_contrast;
  for (size_t k = 0; k < refs.size(); ++k) {
    regions.push_back(finder.regions(k));
    ref_contrast.push_back(metrics::shadow_contrast(refs[k], regions.back()));
  }
  r.shown_frame = static_cast<int>(seq.frames.size()) - 1;  // the last frame
  suite.each_method(r, seq, [&](const StabilityMethod&, const std::vector<Image>& out) {
    std::vector<double> ratio;
    bool pass = out.size() > 3;
    double worst = std::numeric_limits<double>::quiet_NaN();
    bool undefined = false;  // a frame without a shadow or lit region: n/a is the worst
    for (size_t k = 0; k < out.size(); ++k) {
      ratio.push_back(metrics::shadow_contrast(out[k], regions[k]) / ref_contrast[k]);
      if (k < 3) continue;
      if (!(ratio[k] >= 0.75 && ratio[k] <= 1.25)) pass = false;
      undefined = undefined || std::isnan(ratio[k]);
      if (!undefined && (std::isnan(worst) || std::abs(ratio[k] - 1.0) > std::abs(worst - 1.0)))
        worst = ratio[k];
    }
    if (undefined) worst = std::numeric_limits<double>::quiet_NaN();
    StabilityRow row;
    row.value = list(ratio, 2) + " (worst from frame 3: " + num(worst, 2) + ")";
    row.verdict = verdict(pass);
    row.data = {{"contrast_ratio", array(ratio)}, {"reference_contrast", array(ref_contrast)}};
    return row;
  });
  return r;
}

// 10 log10 relMSE over `mask`, per frame.
std::vector<double> masked_error_db(const std::vector<Image>& out, const StabilitySequence& seq,
                                    const metrics::PixelMask& mask) {
  std::vector<double> e;
  for (size_t k = 0; k < out.size(); ++k)
    e.push_back(db(metrics::relmse_in(out[k], seq.frames[k].reference, mask)));
  return e;
}

ScenarioResult light_switch(Suite& suite) {
  constexpr size_t kChange = 6;  // gbuffer/scenes.cpp: light-a goes off at frame 6
  ScenarioResult r;
  r.name = "light-switch";
  r.title = "Light change";
  r.measure =
      "lag: frames after the light goes off (frame 6) until the relMSE over the pixels whose "
      "reference changed by more than 25% is within 1 dB of the restart baseline (the same "
      "pixels at the same history age from the sequence start, metrics::restart_baseline); the "
      "value lists the excess over that baseline (dB) at frames 6 onwards";
  r.threshold = "at most 2 frames (issue 12)";
  r.bar = "lag <= 2";
  r.reading =
      "Without anti-lag (`svgf falcor`, `svgf paper`, `svgf converge`, `bmfr`) the history keeps "
      "the old light until alpha has blended it away, far longer than the 6 frames that follow. "
      "SVGF's defaults restart the changed pixels from the gradient samples; the JBF's temporal "
      "clamp (k = 1) rejects the old colour at once; the methods without history have nothing to "
      "lag.";
  const StabilitySequence& seq = suite.fixture("light-switch");
  r.input = seq.description;
  if (seq.frames.size() < kChange + 3) throw std::invalid_argument("light-switch: too few frames");
  const metrics::PixelMask changed = metrics::changed_pixels(
      seq.frames[kChange - 1].reference, seq.frames[kChange].reference,
      seq.frames[kChange - 1].mesh_id, seq.frames[kChange].mesh_id);
  r.shown_frame = static_cast<int>(kChange) + 1;  // the frame after the switch
  suite.each_method(r, seq, [&](const StabilityMethod&, const std::vector<Image>& out) {
    const std::vector<double> e = masked_error_db(out, seq, changed);
    const std::vector<double> base = metrics::restart_baseline(e, kChange);
    const int lag = metrics::lag_frames(e, base, kChange);
    std::vector<double> excess;
    for (size_t k = kChange; k < e.size(); ++k) excess.push_back(e[k] - base[k]);
    StabilityRow row;
    std::string ex;
    for (double x : excess) ex += (ex.empty() ? "" : " ") + signed_num(x, 1);
    row.value = "lag " + lag_text(lag, kChange, e.size()) + "; excess " + ex;
    row.verdict = verdict(lag >= 0 && lag <= kMaxLag);
    row.data = {{"lag", lag}, {"error_db", array(e)}, {"baseline_db", array(base)},
                {"changed_pixels", changed.count}};
    return row;
  });
  return r;
}

ScenarioResult static_convergence(Suite& suite) {
  const RenderedSizes& z = suite.options().sizes;
  ScenarioResult r;
  r.name = "static-convergence";
  r.title = "Static convergence";
  r.measure =
      "PSNR per frame against the mean of every frame's reference (the scene is still): the "
      "largest frame-to-frame drop after frame 4, and the gain from frame 4 to the last";
  r.threshold = "drop <= 0.1 dB and gain >= 2 dB (issue 12, item 4: over 64 frames)";
  r.bar = "drop <= 0.1 dB, gain >= 2 dB";
  r.reading =
      "Methods without history (`gaussian`, `wavelet`, the OpenCV filters) give the same quality "
      "every frame: no gain, and their frame-to-frame noise makes drops. Feeding a filtered "
      "iteration back (`svgf falcor`, `svgf paper`) re-blurs the history every frame. A history of "
      "fixed weight (the JBF's alpha 0.2, BMFR's 0.2 and 0.1) stops gaining once it holds about "
      "1/alpha frames, short of the 2 dB; SVGF's defaults and `converge` average up to 64 frames "
      "and step the spatial filter back as the history grows.";
  if (!stability_can_render()) {
    r.skipped = "this build has no renderer";
    return r;
  }
  const StabilitySequence seq = suite.render("cornell-static", z.static_size, z.static_size,
                                             z.static_frames, z.static_reference_spp);
  r.input = seq.description + "; PSNR against the mean of the " +
            std::to_string(seq.frames.size()) + " references";
  Image reference(z.static_size, z.static_size, 3, 0.f);
  for (const Frame& f : seq.frames)
    for (size_t i = 0; i < reference.data().size(); ++i)
      reference.data()[i] += f.reference.data()[i] / static_cast<float>(seq.frames.size());
  r.shown_frame = static_cast<int>(seq.frames.size()) - 1;  // the last frame
  suite.each_method(r, seq, [&](const StabilityMethod&, const std::vector<Image>& out) {
    std::vector<double> psnr;
    for (const Image& im : out) psnr.push_back(metrics::psnr(im, reference));
    const metrics::StaticConvergence c = metrics::static_convergence(psnr, kSettled);
    const double drop = c.worst_drop, gain = c.gain;
    StabilityRow row;
    row.value = "worst drop " + num(drop, 2) + " dB, gain " + signed_num(gain, 2) +
                " dB (frame 4: " + num(psnr[kSettled], 2) + " dB, frame " +
                std::to_string(psnr.size() - 1) + ": " + num(psnr.back(), 2) + " dB)";
    row.verdict = verdict(c.meets_rule());
    row.data = {{"worst_drop_db", drop}, {"gain_db", gain}, {"psnr", array(psnr)}};
    return row;
  });
  return r;
}

ScenarioResult camera_cut(Suite& suite) {
  ScenarioResult r;
  r.name = "camera-cut";
  r.title = "Camera cut";
  r.measure =
      "frames after the cut until the PSNR is within 1 dB of what the same method reached at "
      "the same age from the sequence start (restart baseline); the value lists PSNR after the "
      "cut minus that baseline (dB)";
  r.threshold = "at most 2 frames (issue 13 asks for the frames to recover; the bar is issue "
                "12's lag bar)";
  r.bar = "<= 2 frames";
  r.reading =
      "Every method resets its history at the cut (the manifest's `camera_cuts`), so each "
      "recovers at once unless the second shot is harder for it than the first: "
      "`cv-joint-bilateral` (no history) stays 4 dB under its own first frames on every frame "
      "after the cut, which is the restart baseline comparing two different views, not a slow "
      "recovery. BMFR's first frame after the cut is 1.3 dB under the baseline and recovers the "
      "next.";
  const StabilitySequence& seq = suite.fixture("cut");
  r.input = seq.description + " (cut at frame " +
            (seq.cuts.empty() ? std::string("?") : std::to_string(seq.cuts[0])) + ")";
  if (seq.cuts.empty() || seq.cuts[0] < 1)
    throw std::invalid_argument("stability: the `cut` fixture lists no camera cut");
  const size_t cut = static_cast<size_t>(seq.cuts[0]);
  r.shown_frame = static_cast<int>(cut) + 1;  // the frame after the cut
  suite.each_method(r, seq, [&](const StabilityMethod&, const std::vector<Image>& out) {
    std::vector<double> loss;  // -PSNR: lower is better, as lag_frames wants
    for (size_t k = 0; k < out.size(); ++k)
      loss.push_back(-metrics::psnr(out[k], seq.frames[k].reference));
    const std::vector<double> base = metrics::restart_baseline(loss, cut);
    const int lag = metrics::lag_frames(loss, base, cut);
    std::string diff;
    for (size_t k = cut; k < loss.size(); ++k)
      diff += (diff.empty() ? "" : " ") + signed_num(base[k] - loss[k], 1);
    StabilityRow row;
    row.value = "frames to recover: " + lag_text(lag, cut, loss.size()) + "; " + diff;
    row.verdict = verdict(lag >= 0 && lag <= kMaxLag);
    std::vector<double> psnr;
    for (double l : loss) psnr.push_back(-l);
    row.data = {{"frames_to_recover", lag}, {"psnr", array(psnr)}};
    return row;
  });
  return r;
}

ScenarioResult disocclusion(Suite& suite) {
  ScenarioResult r;
  r.name = "disocclusion";
  r.title = "Disocclusion trail";
  r.measure =
      "for each frame t, the pixels the moving object uncovered (metrics/disocclusion.h: their "
      "motion lands on another mesh in frame t-1; frames with 4 or more), and their relMSE in "
      "frames t, t+1, ... against the same method restarted at frame t (its history reset: the "
      "same pixels and content at the same age, with every neighbour fresh too); the lag is the "
      "frames until within 1 dB of the restart, worst over t = 1..N-4; the excess is the dB "
      "over the restart at uncovering, mean over t";
  r.threshold = "lag at most 2 frames (issue 13 asks for the frames until within 1 dB of steady "
                "state; the bar is issue 12's lag bar)";
  r.bar = "lag <= 2";
  const StabilitySequence& seq = suite.fixture("cornell-moving");
  r.input = seq.description;
  const size_t n = seq.frames.size();
  struct Uncovered {
    size_t frame;
    metrics::PixelMask mask;
    StabilitySequence rest;  // frames t.., for the restarted run
  };
  std::vector<Uncovered> uncovered;
  for (size_t t = 1; t + 3 < n; ++t) {
    metrics::PixelMask m = metrics::disoccluded_pixels(seq.frames[t - 1].mesh_id,
                                                       seq.frames[t].mesh_id, seq.frames[t].motion);
    if (m.count < 4) continue;
    StabilitySequence rest;
    rest.frames.assign(seq.frames.begin() + static_cast<long>(t), seq.frames.end());
    uncovered.push_back({t, std::move(m), std::move(rest)});
  }
  if (uncovered.empty()) {
    r.skipped = "no frame of the fixture uncovers 4 pixels or more";
    return r;
  }
  r.input += "; " + std::to_string(uncovered.size()) + " frames with uncovered pixels";
  r.shown_frame = static_cast<int>(seq.frames.size()) - 1;  // the last frame
  suite.each_method(r, seq, [&](const StabilityMethod& m, const std::vector<Image>& out) {
    int worst = 0;
    double excess = 0;
    json per = json::array();
    for (const Uncovered& u : uncovered) {
      const std::vector<Image> restarted = denoise_sequence(m.config, u.rest);
      std::vector<double> e(out.size()), base(out.size());
      for (size_t k = 0; k < out.size(); ++k) {
        const Image& ref = seq.frames[k].reference;
        e[k] = db(metrics::relmse_in(out[k], ref, u.mask));
        // Before t the restart has not begun: its baseline is the run itself.
        base[k] = k < u.frame ? e[k] : db(metrics::relmse_in(restarted[k - u.frame], ref, u.mask));
      }
      const int lag = metrics::lag_frames(e, base, u.frame);
      if (worst >= 0) worst = lag < 0 ? -1 : std::max(worst, lag);
      excess += (e[u.frame] - base[u.frame]) / static_cast<double>(uncovered.size());
      per.push_back({{"frame", u.frame}, {"pixels", u.mask.count}, {"lag", lag},
                     {"error_db", array(e)}, {"restart_db", array(base)}});
    }
    StabilityRow row;
    row.value = "worst lag " + (worst < 0 ? std::string("never back") : std::to_string(worst)) +
                "; excess at uncovering " + signed_num(excess, 1) + " dB";
    row.verdict = verdict(worst >= 0 && worst <= kMaxLag);
    row.data = {{"worst_lag", worst}, {"excess_at_uncovering_db", excess}, {"per_frame", per}};
    return row;
  });
  r.reading =
      "Without history the run and its restart are the same (excess 0.0, lag 0): the check of the "
      "measure. SVGF's uncovered pixels beat the restart (their neighbours bring a converged "
      "history into the spatial filter). A method would lag where its uncovered pixels inherit "
      "something stale: reprojection onto the wrong surface, a clamp box or variance from the "
      "object's old neighbourhood; BMFR's per-block regression, fitted over the block's older "
      "history, comes closest (lag 2).";
  return r;
}

// cornell-static's flicker and firefly scenarios share the clean runs.
std::vector<ScenarioResult> static_fixture(Suite& suite, bool flicker_wanted, bool firefly_wanted) {
  const StabilitySequence& seq = suite.fixture("cornell-static");
  const size_t n = seq.frames.size();
  if (n < static_cast<size_t>(kFireflyFrame) + 3)
    throw std::invalid_argument("stability: cornell-static needs at least 9 frames");

  ScenarioResult flicker;
  flicker.name = "flicker";
  flicker.title = "Flicker on a static scene";
  flicker.input = seq.description;
  flicker.measure =
      "bench/quality.h's output change: mean |out_t - out_(t-1)| over pixels and channels on "
      "values clamped to [0, 1], averaged over frames 4.." + std::to_string(n - 1) +
      "; the scene and camera are still, so the ideal output does not change at all";
  // The reference's own change is the noise of its 1024 samples: the floor a perfect method
  // could reach is ~0, and 2x that noise is what a viewer could not tell from a still image.
  double ref_change = 0;
  for (size_t k = kSettled; k < n; ++k)
    ref_change += mean_abs_change(seq.frames[k].reference, seq.frames[k - 1].reference) /
                  static_cast<double>(n - kSettled);
  double input_change = 0;
  for (size_t k = kSettled; k < n; ++k)
    input_change += mean_abs_change(seq.frames[k].color, seq.frames[k - 1].color) /
                    static_cast<double>(n - kSettled);
  const double flicker_bar = 2.0 * ref_change;
  flicker.threshold =
      "at most twice the reference's own frame-to-frame change (" + num(ref_change, 5) +
      ", the noise of its 1024 samples; the 1-spp input changes by " + num(input_change, 4) +
      "): an output may flicker as much as a 1024-sample render of the scene does, with a "
      "factor 2 of margin. The bar comes from the reference alone and was set before any "
      "method was measured";
  flicker.bar = "<= " + num(flicker_bar, 5);
  flicker.reading =
      "A method without history redraws every frame from new 1-spp noise, and what its filter "
      "leaves of that noise changes every frame (`gaussian`, the OpenCV filters); the a-trous "
      "wavelet smooths enough to stay under the bar without history. SVGF and BMFR change less "
      "than the reference's own noise does; the JBF, with its short history, about as much.";

  ScenarioResult firefly;
  firefly.name = "fireflies";
  firefly.title = "Fireflies";
  const Frame& hit = seq.frames[kFireflyFrame];
  // The image centre, a surface of the room; the sample is 1000x the converged radiance there.
  const int fx = hit.width() / 2, fy = hit.height() / 2;
  firefly.input = seq.description + "; frame 6's sample at pixel (" + std::to_string(fx) + ", " +
                  std::to_string(fy) + ") set to 1000x that pixel's reference";
  firefly.measure =
      "the same sequence denoised clean and with the outlier (metrics/outlier_spread.h): how "
      "far, the largest distance (Chebyshev, pixels) from the outlier of a pixel whose error "
      "exceeds twice the clean run's (and 1e-3 relative), over frames 6 onwards, with the most "
      "such pixels in one frame; how long, the frames until the relMSE over the 33x33 window "
      "around the outlier is back within 0.1 dB of the clean run's (a window, not the whole "
      "image, where a speck of a few pixels would vanish in the mean)";
  firefly.threshold =
      "radius at most 2 pixels and back within 2 frames (issue 13 names the measure, not a bar; "
      "these are this suite's: a real-time denoiser should keep one bad sample to the 5x5 "
      "neighbourhood it would be clamped against and to the lag bar of issue 12)";
  firefly.bar = "radius <= 2 px, <= 2 frames";
  firefly.reading =
      "No method of the suite rejects outliers before filtering (the sanitize stage replaces only "
      "non-finite, negative or > 1e8 samples). Filters that weigh by colour keep the outlier in its"
      " pixel (the JBF, the bilateral, the wavelet's luminance stop); a linear blur spreads it over"
      " its footprint (`gaussian`: its 6 px radius); SVGF's variance-guided a-trous spreads it "
      "10-17 px, and BMFR's per-block regression over its whole 32x32 block. A history keeps it: "
      "SVGF's defaults flush it the next frame (the statistics anti-lag sees the history disagree),"
      " `svgf converge`, `svgf paper` and BMFR keep it past the sequence's end. A firefly clamp "
      "against the neighbourhood, as production denoisers have, is what would pass.";

  StabilitySequence injected = seq;
  if (hit.mesh_id[static_cast<size_t>(fy) * hit.width() + fx] == 0)
    throw std::invalid_argument("stability: the firefly pixel of cornell-static is background");
  for (int c = 0; c < 3; ++c)
    injected.frames[kFireflyFrame].color.at(fx, fy, c) =
        static_cast<float>(kFireflyGain * hit.reference.at(fx, fy, c));

  metrics::PixelMask window;  // the 33x33 pixels around the outlier
  window.inside.assign(hit.reference.pixel_count(), 0);
  const int x0 = std::max(0, fx - kFireflyWindow);
  const int x1 = std::min(hit.width() - 1, fx + kFireflyWindow);
  const int y0 = std::max(0, fy - kFireflyWindow);
  const int y1 = std::min(hit.height() - 1, fy + kFireflyWindow);
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      window.inside[static_cast<size_t>(y) * hit.width() + x] = 1;
      ++window.count;
    }

  flicker.shown_frame = static_cast<int>(n) - 1;  // the last frame
  firefly.shown_frame = kFireflyFrame;             // the frame with the outlier
  // One clean run per method serves both scenarios.
  for (const StabilityMethod& m : suite.methods()) {
    if (!suite.options().quiet)
      std::fprintf(stderr, "  flicker, fireflies: %s\n", m.name.c_str());
    StabilityRow flicker_row, firefly_row;
    flicker_row.method = firefly_row.method = m.name;
    try {
      const std::vector<Image> clean = denoise_sequence(m.config, seq);
      double change = 0;
      std::vector<double> per;
      for (size_t k = kSettled; k < n; ++k) {
        per.push_back(mean_abs_change(clean[k], clean[k - 1]));
        change += per.back() / static_cast<double>(n - kSettled);
      }
      flicker_row.value =
          num(change, 5) + " (" + num(change / ref_change, 1) + "x the reference's)";
      flicker_row.verdict = verdict(change <= flicker_bar);
      flicker_row.data = {{"output_change", change}, {"per_frame", array(per)},
                          {"reference_change", ref_change}};
      keep_if_failed(flicker, m, flicker_row, seq, clean);
      if (firefly_wanted) {
        const std::vector<Image> dirty = denoise_sequence(m.config, injected);
        int radius = -1;
        size_t most = 0;
        std::vector<double> e_clean, e_dirty;
        for (size_t k = 0; k < n; ++k) {
          e_clean.push_back(db(metrics::relmse_in(clean[k], seq.frames[k].reference, window)));
          e_dirty.push_back(db(metrics::relmse_in(dirty[k], seq.frames[k].reference, window)));
          if (k < static_cast<size_t>(kFireflyFrame)) continue;
          const metrics::OutlierSpread sp =
              metrics::outlier_spread(dirty[k], clean[k], seq.frames[k].reference, fx, fy);
          radius = std::max(radius, sp.radius);
          most = std::max(most, sp.pixels);
        }
        const int lasts = metrics::lag_frames(e_dirty, e_clean, kFireflyFrame, 0.1);
        firefly_row.value = "radius " + std::to_string(radius) + " px (" +
                            std::to_string(most) + (most == 1 ? " pixel" : " pixels") +
                            "), " +
                            (lasts >= 0 ? "gone after " + frames_text(lasts)
                                        : "still there " + frames_text(static_cast<long>(n) - 1 -
                                                                       kFireflyFrame) + " later");
        firefly_row.verdict = verdict(radius <= 2 && lasts >= 0 && lasts <= kMaxLag);
        firefly_row.data = {{"radius", radius},        {"pixels", most},
                            {"frames", lasts},          {"error_db", array(e_dirty)},
                            {"clean_error_db", array(e_clean)}};
        keep_if_failed(firefly, m, firefly_row, injected, dirty);
      }
    } catch (const std::exception& e) {
      flicker_row.value = firefly_row.value = std::string("did not run: ") + e.what();
      flicker_row.verdict = firefly_row.verdict = Outcome::NotMeasured;
    }
    flicker.rows.push_back(flicker_row);
    firefly.rows.push_back(firefly_row);
  }
  std::vector<ScenarioResult> out;
  if (flicker_wanted) out.push_back(flicker);
  if (firefly_wanted) out.push_back(firefly);
  return out;
}

}  // namespace

namespace {

// Bars of the detail scenarios (issue 13 names the measures, not the bars).
constexpr double kMinEdgeCorrelation = 0.8;
constexpr double kMinDetailRatio = 0.8, kMaxDetailRatio = 1.25;

// thin (edges) and textured (high frequencies): both measures in both tables, the verdict on
// the scene's own.
ScenarioResult detail(Suite& suite, const std::string& scene, bool edges) {
  ScenarioResult r;
  r.name = edges ? "thin-edges" : "texture-detail";
  r.title = edges ? "Thin geometry" : "Texture";
  const StabilitySequence& seq = suite.fixture(scene);
  r.input = seq.description;
  const size_t n = seq.frames.size();
  if (n <= static_cast<size_t>(kSettled))
    throw std::invalid_argument("stability: " + scene + " needs more than 4 frames");
  r.measure =
      std::string("mean over frames 4..") + std::to_string(n - 1) +
      " of (metrics/detail.h, clamped luminance) the edge preservation: the correlation of the "
      "output's Sobel gradient magnitudes with the reference's over the reference's strongest "
      "10% (the edge pixels), and the high-frequency ratio: the energy of luminance minus its "
      "3x3 mean, output over reference (1: detail kept, < 1: blurred, > 1: noise left). " +
      (edges ? "The verdict is on the edge preservation" : "The verdict is on the ratio");
  if (edges) {
    r.threshold = "edge correlation at least 0.8 (issue 13 names the measure; the bar is this "
                  "suite's: at 0.8 the output's edge strengths explain two thirds of the "
                  "reference's variation, 1 - 0.8^2 = 0.36 left to blur and noise)";
    r.bar = ">= 0.8";
  } else {
    r.threshold = "high-frequency ratio 0.8 to 1.25 (issue 13 names the measure; the bar is "
                  "this suite's: within 1 dB of the reference's detail energy, lost or added)";
    r.bar = "0.8..1.25";
  }
  r.reading =
      "Filters that stop at the G-buffer's edges (normal, depth, mesh) keep a thin object's "
      "outline; a texture lives in the albedo, which SVGF and BMFR divide out before filtering "
      "and multiply back after, while the JBF and the Gaussian blur the radiance, texture "
      "included (ratios 0.01-0.09 on `textured`). Residual 1-spp noise counts as high-frequency "
      "energy too: the bilateral and NL-means keep so much noise (ratios above 1.25) that their "
      "edges drown. The wavelet and BMFR sit just under 0.8 on `thin`.";
  r.shown_frame = static_cast<int>(seq.frames.size()) - 1;  // the last frame
  suite.each_method(r, seq, [&](const StabilityMethod&, const std::vector<Image>& out) {
    double corr = 0, ratio = 0;
    std::vector<double> corr_k, ratio_k;
    for (size_t k = kSettled; k < n; ++k) {
      corr_k.push_back(metrics::edge_preservation(out[k], seq.frames[k].reference));
      ratio_k.push_back(metrics::high_frequency_ratio(out[k], seq.frames[k].reference));
      corr += corr_k.back() / static_cast<double>(n - kSettled);
      ratio += ratio_k.back() / static_cast<double>(n - kSettled);
    }
    StabilityRow row;
    row.value = edges ? "edges " + num(corr, 3) + " (high frequencies " + num(ratio, 2) + ")"
                      : "high frequencies " + num(ratio, 2) + " (edges " + num(corr, 3) + ")";
    row.verdict = edges ? verdict(corr >= kMinEdgeCorrelation)
                        : verdict(ratio >= kMinDetailRatio && ratio <= kMaxDetailRatio);
    row.data = {{"edge_preservation", finite_or_null(corr)},
                {"high_frequency_ratio", finite_or_null(ratio)},
                {"edge_preservation_per_frame", array(corr_k)},
                {"high_frequency_ratio_per_frame", array(ratio_k)}};
    return row;
  });
  return r;
}

}  // namespace

RenderedSizes reduced_sizes() { return {}; }

RenderedSizes full_sizes() {
  RenderedSizes z;
  z.shadow_width = 384;
  z.shadow_height = 216;
  z.shadow_frames = 16;
  z.shadow_reference_spp = 256;
  z.static_size = 128;
  z.static_frames = 64;
  z.static_reference_spp = 32;
  return z;
}

std::vector<StabilityMethod> stability_methods(Backend backend, int threads) {
  std::vector<StabilityMethod> v;
  const auto project = [&](const std::string& name, const std::string& method) {
    RunConfig c = run_config(method);
    c.denoiser.backend = backend;
    c.denoiser.threads = threads;
    v.push_back({name, c});
    return &v.back().config;
  };
  project("svgf", "svgf");
  for (const char* preset : {"falcor", "paper", "converge"})
    project(std::string("svgf ") + preset, "svgf")->denoiser.svgf = svgf_preset(preset);
  for (const char* method : {"gaussian", "wavelet", "jbf", "jbf-atrous", "bmfr"})
    project(method, method);
  if (baselines_available() && backend == Backend::Cpu)
    for (const Baseline& b : default_baselines())
      v.push_back({b.label(), baseline_config(b, threads)});
  return v;
}

std::vector<std::string> stability_method_names() {
  std::vector<std::string> names;
  for (const StabilityMethod& m : stability_methods(Backend::Cpu, 1)) names.push_back(m.name);
  return names;
}

std::vector<std::string> stability_scenario_names() {
  return {"moving-shadow", "light-switch", "static-convergence", "camera-cut", "disocclusion",
          "flicker",       "fireflies",    "thin-edges",         "texture-detail"};
}

const char* to_string(Outcome v) {
  switch (v) {
    case Outcome::Pass: return "pass";
    case Outcome::Fail: return "fail";
    case Outcome::NotMeasured: return "not measured";
  }
  return "?";
}

void check_stability_options(const StabilityOptions& options) {
  const auto check = [](const std::vector<std::string>& asked,
                        const std::vector<std::string>& known, const char* what) {
    for (const std::string& a : asked)
      if (std::find(known.begin(), known.end(), a) == known.end()) {
        std::string list;
        for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
        throw std::invalid_argument(std::string("stability: unknown ") + what + " '" + a +
                                    "' (known: " + list + ")");
      }
  };
  check(options.methods, stability_method_names(), "method");
  check(options.scenarios, stability_scenario_names(), "scenario");
  for (const std::string& path : {options.out_md, options.out_json}) {
    if (path.empty()) continue;
    const fs::path parent = fs::absolute(path).parent_path();
    if (!fs::is_directory(parent))
      throw std::invalid_argument("stability: cannot write " + path + ": no folder " +
                                  parent.string());
  }
}

std::vector<ScenarioResult> run_stability(const StabilityOptions& options) {
  check_stability_options(options);
  const auto wanted = [&](const char* s) {
    return options.scenarios.empty() ||
           std::find(options.scenarios.begin(), options.scenarios.end(), s) !=
               options.scenarios.end();
  };
  Suite suite(options);
  std::vector<ScenarioResult> results;
  const auto progress = [&](const char* s) {
    if (!options.quiet) std::fprintf(stderr, "stability: %s\n", s);
  };
  if (wanted("moving-shadow")) {
    progress("moving-shadow");
    results.push_back(moving_shadow(suite));
  }
  if (wanted("light-switch")) {
    progress("light-switch");
    results.push_back(light_switch(suite));
  }
  if (wanted("static-convergence")) {
    progress("static-convergence");
    results.push_back(static_convergence(suite));
  }
  if (wanted("camera-cut")) {
    progress("camera-cut");
    results.push_back(camera_cut(suite));
  }
  if (wanted("disocclusion")) {
    progress("disocclusion");
    results.push_back(disocclusion(suite));
  }
  if (wanted("flicker") || wanted("fireflies")) {
    progress("flicker, fireflies");
    for (ScenarioResult& r : static_fixture(suite, wanted("flicker"), wanted("fireflies")))
      results.push_back(std::move(r));
  }
  if (wanted("thin-edges")) {
    progress("thin-edges");
    results.push_back(detail(suite, "thin", true));
  }
  if (wanted("texture-detail")) {
    progress("texture-detail");
    results.push_back(detail(suite, "textured", false));
  }
  return results;
}

}  // namespace svgf::bench

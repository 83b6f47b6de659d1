#pragma once
// One SVGF frame, written once for every backend and mode. An Engine runs a pixel kernel over
// the image wherever it lives: `engine.run(stage, kernel, width, height)` (kernel(x, y) per
// pixel). The CPU engine loops with TBB, the CUDA engine launches; the
// Flavor (methods/svgf/flavors.h) picks exact or fast arithmetic and storage, and whether
// stages are fused into one launch. The kernels and this data flow are the same code on every
// backend, which is what makes exact mode bitwise.
#include <type_traits>

#include "core/copy.h"
#include "core/fuse.h"
#include "core/previous_depth.h"
#include "core/taa.h"
#include "core/views.h"
#include "methods/svgf/atrous.h"
#include "methods/svgf/demodulate.h"
#include "methods/svgf/flavors.h"
#include "methods/svgf/gradient.h"
#include "methods/svgf/gradient_tile.h"
#include "methods/svgf/params.h"
#include "methods/svgf/remodulate.h"
#include "methods/svgf/reproject.h"
#include "methods/svgf/sinks.h"
#include "methods/svgf/split_sum.h"
#include "methods/svgf/stages.h"
#include "methods/svgf/variance.h"

namespace svgf {

// Every buffer one frame touches, as views on the engine's side (host or device memory).
struct SvgfFrameBuffers {
  // Inputs of this frame.
  GuideView guides;
  GuideView prev_guides;  // the previous frame's depth, normal and mesh id (no more is kept)
  // The packed flavors: the previous frame's packed_guides (its depth and normal; prev_guides
  // then holds its mesh ids, and depth and normal only where a backend keeps them too).
  const float* prev_packed_guides = nullptr;
  // The depth this frame's points had in the previous camera (the reprojection's depth test).
  PreviousViewDepth previous_depth;
  ConstRgbView color;
  ConstRgbView albedo;
  ConstRgbView emission;  // optional (no planes: no emitters in view)
  // History read (left by the previous frame) and written (for the next).
  ConstRgbView prev_color;
  const float* prev_moment1 = nullptr;
  const float* prev_moment2 = nullptr;
  const float* prev_history = nullptr;
  RgbView next_color;
  // The color history has one slot (next_color is prev_color), overwritten only after the
  // reprojection has read it all (SvgfDenoiser::color_history_slots): without a fed-back
  // iteration the accumulation's color is then copied there by the variance stage instead of
  // written there by the reprojection.
  bool color_history_in_place = false;
  float* next_moment1 = nullptr;
  float* next_moment2 = nullptr;
  float* next_history = nullptr;
  // Scratch.
  RgbView illumination;
  // Whether the illumination is read back after the frame (the keep_scratch debug buffer):
  // else the packed flavors' first kernel passes it on in registers and stores none.
  bool illumination_read_back = true;
  IllumVarView accumulated;
  // The a-trous ping-pong: 4 floats a pixel each, 16-byte aligned. SvgfExact uses them as four
  // planes (filtered[k]), the packed flavors as packed pixels (packed[k]).
  float* signal[2] = {nullptr, nullptr};
  float* packed_guides = nullptr;  // packed flavors: 4 floats a pixel (depth, normal)
  // A-SVGF (methods/svgf/gradient.h): this frame's gradient samples (no planes: the frame has
  // none, or the anti-lag mode does not read them) and kGradientStratumPlanes planes of the
  // stratum image, strata_along(width) x strata_along(height) floats each.
  GradientSampleView gradient_samples;
  float* strata = nullptr;
  // Where lambda lies apart from the other stratum planes (the denoiser's scratch in the history,
  // SvgfDenoiser::scratch_in_history): the reprojection reads it while it writes where they lie.
  float* lambda = nullptr;
  // Output: the denoised, remodulated color.
  RgbView output;
  // With TAA (p.taa): remodulation writes `remodulated`; TAA blends it with the previous TAA
  // output `prev_taa` and writes `next_taa` (the next frame's) and `output`.
  RgbView remodulated;
  ConstRgbView prev_taa;
  RgbView next_taa;
  // The inputs' sanitize rule, in place, where the backend left it to the frame (FrameInputs::
  // sanitize_pending): run first, or fused into the first pixel kernel (run_svgf_frame).
  bool sanitize_pending = false;
  SanitizeInputs sanitize;

  size_t pixels() const { return static_cast<size_t>(guides.width) * guides.height; }
  size_t stratum_count() const {
    return static_cast<size_t>(strata_along(guides.width)) * strata_along(guides.height);
  }
  float* stratum_plane(int k) const { return strata + static_cast<size_t>(k) * stratum_count(); }
  // The gradient a-trous ping-pong, k = 0 or 1.
  GradientPlanes<float> gradient_signal(int k) const {
    return {stratum_plane(3 * k), stratum_plane(3 * k + 1), stratum_plane(3 * k + 2)};
  }
  float* stratum_guides() const { return stratum_plane(6); }
  float* gradient_lambda() const { return lambda ? lambda : stratum_plane(7); }
  IllumVarView filtered(int k) const {
    float* p = signal[k];
    const size_t n = pixels();
    return {{p, p + n, p + 2 * n}, p + 3 * n};
  }
  PackedIllumVar<Packed4> packed(int k) const {
    return PackedIllumVar<Packed4>(reinterpret_cast<Packed4*>(signal[k]));
  }
};

// How a flavor stores the a-trous signal and the guides: planes (SvgfExact), or packed pixels
// (the packed flavors; the guides packed by the demodulation stage into b.packed_guides).
template <class Flavor>
inline constexpr bool kPacksSignal =
    std::is_same_v<typename Flavor::Signal, PackedIllumVar<Packed4>>;
template <class Flavor>
inline constexpr bool kPacksGuides = std::is_same_v<typename Flavor::Guides, PackedGuides>;

// The a-trous buffer k as the flavor stores it.
template <class Flavor>
auto signal_buffer(Flavor, const SvgfFrameBuffers& b, int k) {
  if constexpr (kPacksSignal<Flavor>) return b.packed(k);
  else return b.filtered(k);
}

// Guides as the flavor stores them: the planes, or (packed flavors) their depth and normal
// read from `packed` (4 floats a pixel), the rest from the planes.
template <class Flavor>
auto flavor_guides(Flavor, const GuideView& planes, const float* packed) {
  if constexpr (kPacksGuides<Flavor>) {
    PackedGuides g;
    g.width = planes.width;
    g.height = planes.height;
    g.depth_normal_data = reinterpret_cast<const Packed4*>(packed);
    g.depth_dx = planes.depth_dx;
    g.depth_dy = planes.depth_dy;
    g.mesh_id = planes.mesh_id;
    return g;
  } else {
    return planes;
  }
}

// The guides the filter stages read.
template <class Flavor>
auto filter_guides(Flavor flavor, const SvgfFrameBuffers& b) {
  return flavor_guides(flavor, b.guides, b.packed_guides);
}

// The previous frame's guides as the reprojection reads them (packed flavors: the packed
// guides that frame wrote, with its mesh ids).
template <class Flavor>
auto reprojected_guides(Flavor flavor, const SvgfFrameBuffers& b) {
  return flavor_guides(flavor, b.prev_guides, b.prev_packed_guides);
}

// The feedback tap's copy of the filtered color into the color history, from the flavor's
// storage (an unfused pipeline's own pass): a plane copy, or the color of packed pixels.
template <class Flavor>
auto feedback_copy_kernel(Flavor, const SvgfFrameBuffers& b, int k) {
  if constexpr (kPacksSignal<Flavor>)
    return ForwardKernel<PackedIllumVar<const Packed4>, ColorOnlySink>{
        b.guides.width, b.packed(k), ColorOnlySink{b.next_color}};
  else
    return CopyRgbKernel{b.guides.width, b.filtered(k).color, b.next_color};
}

// The first two stages' kernels for a frame (exact arithmetic in every mode: the history
// decisions of fast mode are exact mode's).
inline DemodulateKernel demodulate_kernel_for(const SvgfFrameBuffers& b, const SvgfParams& p) {
  return DemodulateKernel{b.guides.width, b.color,        b.albedo,
                          b.emission,     b.illumination, p.albedo_epsilon};
}

// The stratum image's planes: two a-trous buffers of 3 (delta, normalizer, weight), the guide
// offsets, lambda.
inline constexpr int kGradientStratumPlanes = 8;

// The gradient stages run this frame: A-SVGF asked for, the frame has samples (the denoiser
// passes them only then) and a history to correct.
inline bool runs_gradient_stages(const SvgfFrameBuffers& b, const SvgfParams& p,
                                 bool has_history) {
  return p.antilag == Antilag::Gradient && b.gradient_samples.present() && has_history;
}

inline GradientSamplesKernel gradient_samples_kernel_for(const SvgfFrameBuffers& b) {
  GradientSamplesKernel k;
  k.width = b.guides.width;
  k.height = b.guides.height;
  k.samples = b.gradient_samples;
  k.out = b.gradient_signal(0);
  k.strata_width = strata_along(b.guides.width);
  k.guide_offset = b.stratum_guides();
  return k;
}

inline GradientAtrousKernel gradient_atrous_kernel_for(const SvgfFrameBuffers& b,
                                                       const SvgfParams& p, int in, int step) {
  GradientAtrousKernel k;
  k.guides = b.guides;
  k.at = StratumGuides{b.guides.width, strata_along(b.guides.width), b.stratum_guides()};
  k.strata_height = strata_along(b.guides.height);
  k.in = b.gradient_signal(in);
  k.out = b.gradient_signal(1 - in);
  k.step = step;
  k.phi_depth = p.gradient_phi_depth;
  k.phi_normal = p.gradient_phi_normal;
  k.depth_gradient_floor = p.depth_gradient_floor;
  return k;
}

// The three stages as one block kernel over tiles of strata (methods/svgf/gradient_tile.h).
inline GradientTileKernel gradient_tile_kernel_for(const SvgfFrameBuffers& b,
                                                   const SvgfParams& p) {
  GradientTileKernel k;
  k.samples = gradient_samples_kernel_for(b);
  k.atrous = gradient_atrous_kernel_for(b, p, 0, 1);
  k.lambda = b.gradient_lambda();
  k.iterations = p.gradient_iterations;
  k.radius = p.gradient_lambda_radius;
  k.strata_width = strata_along(b.guides.width);
  k.strata_height = strata_along(b.guides.height);
  return k;
}

// A-SVGF's three stages (methods/svgf/gradient.h), exact arithmetic in every mode: the frame's
// gradient samples -> lambda per stratum (b.gradient_lambda()), which the reprojection reads.
// Where the flavor fuses them and the filter is the default's size, one launch does all three
// (timed as the samples' stage); the stratum planes then hold nothing of the frame.
template <class Flavor, class Engine>
void run_gradient_stages(Engine& engine, const SvgfFrameBuffers& b, const SvgfParams& p) {
  namespace stage = svgf_stage;
  if constexpr (Flavor::kFusedGradient) {
    if (GradientTileKernel::handles(p.gradient_iterations, p.gradient_lambda_radius)) {
      const GradientTileKernel tiles = gradient_tile_kernel_for(b, p);
      engine.run_blocks(stage::kGradient, tiles, tiles.blocks());
      return;
    }
  }
  const int sw = strata_along(b.guides.width);
  const int sh = strata_along(b.guides.height);
  engine.run(stage::kGradient, gradient_samples_kernel_for(b), sw, sh);
  int current = 0;
  for (int it = 0; it < p.gradient_iterations; ++it) {
    engine.run(stage::kGradientAtrous, gradient_atrous_kernel_for(b, p, current, 1 << it), sw,
               sh);
    current = 1 - current;
  }
  engine.run(stage::kGradientLambda,
             GradientLambdaKernel{sw, b.gradient_signal(current), b.gradient_lambda(), sh,
                                  p.gradient_lambda_radius},
             sw, sh);
}

// `gradient_lambda`: A-SVGF's lambda per stratum when the gradient stages ran this frame.
// The previous frame's guides as Flavor stores them (reprojected_guides).
template <class Flavor = SvgfExact>
auto reproject_kernel_for(const SvgfFrameBuffers& b, const SvgfParams& p, bool has_history,
                          const float* gradient_lambda = nullptr) {
  const auto prev_guides = reprojected_guides(Flavor(), b);
  ReprojectKernelT<std::decay_t<decltype(prev_guides)>> k;
  k.guides = b.guides;
  k.prev_guides = prev_guides;
  k.previous_depth = b.previous_depth;
  k.illumination = b.illumination;
  k.color = b.color;
  k.albedo = b.albedo;
  k.emission = b.emission;
  k.prev_color = b.prev_color;
  k.prev_moment1 = b.prev_moment1;
  k.prev_moment2 = b.prev_moment2;
  k.prev_history = b.prev_history;
  k.has_history = has_history;
  k.gradient_lambda = gradient_lambda;
  k.accumulated = b.accumulated;
  k.moment1 = b.next_moment1;
  k.moment2 = b.next_moment2;
  k.history = b.next_history;
  k.params = p;
  return k;
}

// Whether the frame's sanitize stage can ride on the flavor's first pixel kernel (demodulate +
// reproject + guide packing): every stage before it and that kernel read the inputs of their
// own pixel only, or apply the rule where they read (GradientTileKernel). Not where the
// statistics anti-lag reads the neighbourhood's color, where A-SVGF's three passes read the
// guides, or where a second signal (direct and indirect) would read the inputs after it.
// For a flavor that fuses the reprojection and A-SVGF's stages (the packed flavors; the bench
// counts costs by it, bench/stage_cost.cpp).
inline bool sanitize_fusable(const SvgfParams& p, bool has_history, bool gradient, bool split) {
  if (split) return false;
  if (gradient) return GradientTileKernel::handles(p.gradient_iterations, p.gradient_lambda_radius);
  const bool statistics = p.antilag == Antilag::Statistics || p.antilag == Antilag::Gradient;
  return !(has_history && statistics);
}
template <class Flavor>
bool fuses_sanitize(const SvgfParams& p, bool has_history, bool gradient, bool split) {
  return Flavor::kFusedReprojection && Flavor::kFusedGradient &&
         sanitize_fusable(p, has_history, gradient, split);
}

// Stages 1 to 5 for one signal (the frame's color, or its direct or indirect part): its
// history, its variance, its filter; the remodulated result goes to `out`. `lambda`: A-SVGF's
// per-stratum lambda, or null. `sanitize`: the inputs' sanitize rule to fuse into the first
// kernel (its repairs are the frame's tallies), or null.
template <class Flavor, class Engine>
void run_svgf_signal(Engine& engine, const SvgfFrameBuffers& buffers, const SvgfParams& p,
                     bool has_history, const float* lambda, RgbView out,
                     const SanitizeInputs* sanitize = nullptr) {
  namespace stage = svgf_stage;
  // Without a feedback tap in range the next frame's color history is the accumulation itself.
  // With two history slots the reprojection writes its color there, and no pass copies it (the
  // variance reads it from there; the same values, so the same bits): the caller's
  // accumulation color planes are not touched (the denoisers allocate none). With one slot the
  // reprojection is still reading the previous history at other pixels, so the accumulation
  // keeps its own planes and the variance stage, which reads every pixel's, copies it there.
  SvgfFrameBuffers b = buffers;
  const bool history_from_variance = !p.feeds_back_iteration() && b.color_history_in_place;
  if (!p.feeds_back_iteration() && !b.color_history_in_place) b.accumulated.color = b.next_color;
  const int w = b.guides.width;
  const int h = b.guides.height;
  const Flavor flavor;
  const auto signal = [&](int k) { return signal_buffer(flavor, b, k); };
  using Signal = std::decay_t<decltype(signal(0))>;
  using ConstSignal = typename Flavor::ConstSignal;
  const RemodulateSink remodulate{b.albedo, b.emission, out, p.albedo_epsilon};

  // 1. (color - emission) / albedo -> illumination (the inputs are sanitized already).
  // 2. illumination + history -> accumulated color (into the color history when no iteration is
  //    fed back and the history has two slots), moments and history length.
  //    Fused, the same thread first packs its pixel's guides (the filters' and the next
  //    frame's previous guides), then demodulates and reprojects, the illumination passed on
  //    in registers (stored only where it is read back: SvgfFrameBuffers). Packed first: the
  //    normals may lie in the accumulation's planes, which the reprojection writes after
  //    reading its own pixel's (SvgfDenoiser: the frame's normals).
  //    Unfused with packed guides, the demodulation packs them.
  const PackGuidesKernel pack{b.guides, reinterpret_cast<Packed4*>(b.packed_guides)};
  //    With the sanitize stage fused, the same thread first repairs its pixel's inputs in place.
  if constexpr (Flavor::kFusedReprojection) {
    const auto reproject = reproject_kernel_for<Flavor>(b, p, has_history, lambda);
    const DemodulateAndReproject<std::decay_t<decltype(reproject)>> pixel{
        demodulate_kernel_for(b, p), reproject, b.illumination_read_back};
    const auto first = then(pack, pixel);
    if (sanitize) engine.run_tallying(stage::kDemodulate, then(*sanitize, first), w, h);
    else engine.run(stage::kDemodulate, first, w, h);
  } else {
    if constexpr (kPacksGuides<Flavor>)
      engine.run(stage::kDemodulate, then(demodulate_kernel_for(b, p), pack), w, h);
    else
      engine.run(stage::kDemodulate, demodulate_kernel_for(b, p), w, h);
    engine.run(stage::kReproject, reproject_kernel_for<Flavor>(b, p, has_history, lambda), w,
               h);
  }
  const auto guides = filter_guides(flavor, b);

  Flavor::with_normal_power(p.phi_normal, [&](const auto& power) {
    using Power = std::decay_t<decltype(power)>;
    // 3. accumulated -> signal 0 with its variance (spatial estimate for young history); the
    //    accumulated color -> the color history's one slot when no iteration is fed back.
    engine.run(stage::kVariance,
               VarianceEstimate<Flavor, Power>{guides, b.accumulated, b.next_moment1,
                                               b.next_moment2, b.next_history, signal(0), p,
                                               history_from_variance ? b.next_color : RgbView()},
               w, h);

    // 4. a-trous iterations ping-pong between signal 0 and 1; the feedback tap's output becomes
    //    the next frame's color history.
    int current = 0;
    for (int it = 0; it < p.iterations; ++it) {
      const ConstSignal in = signal(current);
      const int step = 1 << it;
      const bool feedback = it == p.feedback_tap;
      const auto iterate = [&](const auto& out) {
        using Out = std::decay_t<decltype(out)>;
        engine.run(stage::kAtrous, AtrousIteration<Flavor, Power, Out>{guides, in, out, step, p},
                   w, h);
      };
      if constexpr (Flavor::kFusedOutputs) {
        // The feedback copy and (last iteration) the remodulation happen as the result is
        // stored; the last iteration's filtered buffer is never written.
        const bool last = it + 1 == p.iterations;
        if (last && feedback) iterate(FeedbackTee<RemodulateSink>{remodulate, b.next_color});
        else if (last) iterate(remodulate);
        else if (feedback) iterate(FeedbackTee<Signal>{signal(1 - current), b.next_color});
        else iterate(signal(1 - current));
      } else {
        iterate(signal(1 - current));
        if (feedback)
          engine.run(stage::kFeedback, feedback_copy_kernel(flavor, b, 1 - current), w, h);
      }
      current = 1 - current;
    }
    // 5. filtered illumination * albedo + emission -> output (fused: done by the last
    //    iteration, unless there was none).
    if (!Flavor::kFusedOutputs || p.iterations <= 0)
      engine.run(stage::kRemodulate,
                 ForwardKernel<ConstSignal, RemodulateSink>{w, signal(current), remodulate}, w,
                 h);
  });
}

// One frame. `indirect` (optional): the frame's color is split into direct (in `b`, with the
// emission) and indirect (issue 12, item 2; docs/svgf.md: Direct and indirect): each signal runs
// stages 1-5 with its own history, moments and variance, so its own edge-stopping; indirect
// (no emission, its own output buffer) is filtered with p.indirect(), then added to direct. The
// signals share the scratch buffers, one after the other; A-SVGF's lambda and TAA are the
// frame's, computed and applied once.
template <class Flavor = SvgfExact, class Engine>
void run_svgf_frame(Engine& engine, const SvgfFrameBuffers& b, const SvgfParams& p,
                    bool has_history, const SvgfFrameBuffers* indirect = nullptr) {
  namespace stage = svgf_stage;
  const int w = b.guides.width;
  const int h = b.guides.height;

  // 0. A-SVGF: the temporal gradients of the frame's re-shaded samples -> lambda per stratum.
  //    Without samples the reprojection falls back to the statistics anti-lag. The samples may
  //    lie in the illumination's planes (the denoiser lends them to a backend that copies its
  //    inputs): these stages run before the demodulation writes the illumination.
  //    Where the backend left the inputs' sanitize stage to the frame, it runs first, or rides
  //    on the demodulation's kernel where nothing before that reads the inputs unsanitized
  //    (fuses_sanitize: the fused gradient launch reads the guides through the rule).
  const bool gradient = runs_gradient_stages(b, p, has_history);
  const bool fused_sanitize =
      b.sanitize_pending && fuses_sanitize<Flavor>(p, has_history, gradient, indirect != nullptr);
  if (b.sanitize_pending && !fused_sanitize)
    engine.run_tallying(kSanitizeStage, b.sanitize, w, h);
  if (gradient) run_gradient_stages<Flavor>(engine, b, p);
  const float* lambda = gradient ? b.gradient_lambda() : nullptr;

  // 1-5. The signal(s) -> the remodulated color (TAA's input when TAA is on).
  const RgbView remodulated = p.taa ? b.remodulated : b.output;
  run_svgf_signal<Flavor>(engine, b, p, has_history, lambda, remodulated,
                          fused_sanitize ? &b.sanitize : nullptr);
  if (indirect) {
    run_svgf_signal<Flavor>(engine, *indirect, p.indirect(), has_history, lambda,
                            indirect->output);
    engine.run(stage::kSplitSum, SplitSumKernel{w, indirect->output, remodulated}, w, h);
  }

  // 6. Optional TAA: the remodulated color blended with the reprojected previous TAA output,
  //    clamped to this frame's neighbourhood (core/taa.h); its history restarts with SVGF's.
  if (p.taa) {
    TemporalAntiAliasing taa;
    taa.guides = b.guides;
    taa.current = b.remodulated;
    taa.history = b.prev_taa;
    taa.history_out = b.next_taa;
    taa.output = b.output;
    taa.has_history = has_history;
    taa.alpha = p.taa_alpha;
    engine.run(stage::kTaa, taa, w, h);
  }
}

}  // namespace svgf

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
#include "core/views.h"
#include "methods/svgf/atrous.h"
#include "methods/svgf/demodulate.h"
#include "methods/svgf/flavors.h"
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
  GuideView prev_guides;  // the previous frame's, kept by the denoiser
  ConstRgbView color;
  ConstRgbView albedo;
  ConstRgbView emission;  // optional (no planes: no emitters in view)
  // History read (left by the previous frame) and written (for the next).
  ConstRgbView prev_color;
  const float* prev_moment1 = nullptr;
  const float* prev_moment2 = nullptr;
  const float* prev_history = nullptr;
  RgbView next_color;
  float* next_moment1 = nullptr;
  float* next_moment2 = nullptr;
  float* next_history = nullptr;
  // Scratch.
  RgbView illumination;
  IllumVarView accumulated;
  // The a-trous ping-pong: 4 floats a pixel each, 16-byte aligned. Exact mode uses them as four
  // planes (filtered[k]), fast mode as packed pixels (packed[k]).
  float* signal[2] = {nullptr, nullptr};
  float* packed_guides = nullptr;  // fast mode: 4 floats a pixel (depth, normal)
  // Output: the denoised, remodulated color.
  RgbView output;

  size_t pixels() const { return static_cast<size_t>(guides.width) * guides.height; }
  IllumVarView filtered(int k) const {
    float* p = signal[k];
    const size_t n = pixels();
    return {{p, p + n, p + 2 * n}, p + 3 * n};
  }
  PackedIllumVar<Packed4> packed(int k) const {
    return PackedIllumVar<Packed4>(reinterpret_cast<Packed4*>(signal[k]));
  }
};

// The a-trous buffer k and the guides as a flavor stores them.
inline IllumVarView signal_buffer(SvgfExact, const SvgfFrameBuffers& b, int k) {
  return b.filtered(k);
}
inline GuideView filter_guides(SvgfExact, const SvgfFrameBuffers& b) { return b.guides; }
#if defined(__CUDACC__)
inline PackedIllumVar<Packed4> signal_buffer(SvgfFast, const SvgfFrameBuffers& b, int k) {
  return b.packed(k);
}
inline PackedGuides filter_guides(SvgfFast, const SvgfFrameBuffers& b) {
  PackedGuides g;
  g.width = b.guides.width;
  g.height = b.guides.height;
  g.depth_normal_data = reinterpret_cast<const Packed4*>(b.packed_guides);
  g.depth_dx = b.guides.depth_dx;
  g.depth_dy = b.guides.depth_dy;
  return g;
}
#endif

// The first two stages' kernels for a frame (exact arithmetic in every mode: the history
// decisions of fast mode are exact mode's).
inline DemodulateKernel demodulate_kernel_for(const SvgfFrameBuffers& b, const SvgfParams& p) {
  return DemodulateKernel{b.guides.width, b.color,        b.albedo,
                          b.emission,     b.illumination, p.albedo_epsilon};
}

inline ReprojectKernel reproject_kernel_for(const SvgfFrameBuffers& b, const SvgfParams& p,
                                            bool has_history) {
  ReprojectKernel k;
  k.guides = b.guides;
  k.prev_guides = b.prev_guides;
  k.illumination = b.illumination;
  k.color = b.color;
  k.albedo = b.albedo;
  k.emission = b.emission;
  k.prev_color = b.prev_color;
  k.prev_moment1 = b.prev_moment1;
  k.prev_moment2 = b.prev_moment2;
  k.prev_history = b.prev_history;
  k.has_history = has_history;
  k.accumulated = b.accumulated;
  k.moment1 = b.next_moment1;
  k.moment2 = b.next_moment2;
  k.history = b.next_history;
  k.params = p;
  return k;
}

template <class Flavor = SvgfExact, class Engine>
void run_svgf_frame(Engine& engine, const SvgfFrameBuffers& b, const SvgfParams& p,
                    bool has_history) {
  namespace stage = svgf_stage;
  const int w = b.guides.width;
  const int h = b.guides.height;
  const Flavor flavor;
  const auto signal = [&](int k) { return signal_buffer(flavor, b, k); };
  using Signal = std::decay_t<decltype(signal(0))>;
  using ConstSignal = typename Flavor::ConstSignal;
  const RemodulateSink remodulate{b.albedo, b.emission, b.output, p.albedo_epsilon};

  // 1. (color - emission) / albedo -> illumination (the inputs are sanitized already).
  // 2. illumination + history -> accumulated color, moments and history length.
  //    Fused, the same thread reprojects the illumination it just wrote, and packs the guides.
  if constexpr (Flavor::kFused) {
    engine.run(stage::kDemodulate,
               then(demodulate_kernel_for(b, p),
                    then(reproject_kernel_for(b, p, has_history),
                         PackGuidesKernel{b.guides, reinterpret_cast<Packed4*>(b.packed_guides)})),
               w, h);
  } else {
    engine.run(stage::kDemodulate, demodulate_kernel_for(b, p), w, h);
    engine.run(stage::kReproject, reproject_kernel_for(b, p, has_history), w, h);
  }
  const auto guides = filter_guides(flavor, b);

  Flavor::with_normal_power(p.phi_normal, [&](const auto& power) {
    using Power = std::decay_t<decltype(power)>;
    // 3. accumulated -> signal 0 with its variance (spatial estimate for young history).
    engine.run(stage::kVariance,
               VarianceEstimate<Flavor, Power>{guides, b.accumulated, b.next_moment1,
                                               b.next_moment2, b.next_history, signal(0), p},
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
      if constexpr (Flavor::kFused) {
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
          engine.run(stage::kFeedback,
                     CopyRgbKernel{w, b.filtered(1 - current).color, b.next_color}, w, h);
      }
      current = 1 - current;
    }
    // No feedback tap in range: the unfiltered accumulation is the history.
    if (p.feedback_tap < 0 || p.feedback_tap >= p.iterations)
      engine.run(stage::kFeedback, CopyRgbKernel{w, b.accumulated.color, b.next_color}, w, h);

    // 5. filtered illumination * albedo + emission -> output (fused: done by the last
    //    iteration, unless there was none).
    if (!Flavor::kFused || p.iterations <= 0)
      engine.run(stage::kRemodulate,
                 ForwardKernel<ConstSignal, RemodulateSink>{w, signal(current), remodulate}, w,
                 h);
  });
}

// A frame whose color is split into direct and indirect (issue 12, item 2; docs/svgf.md: Direct
// and indirect): each signal runs the frame above with its own history, moments and variance,
// and so its own edge-stopping; `direct` holds the emission and writes the frame's output,
// `indirect` (no emission, its own output buffer) is filtered with p.indirect(); then the two
// are added. The signals share the scratch buffers, one after the other.
template <class Flavor = SvgfExact, class Engine>
void run_svgf_split_frame(Engine& engine, const SvgfFrameBuffers& direct,
                          const SvgfFrameBuffers& indirect, const SvgfParams& p,
                          bool has_history) {
  run_svgf_frame<Flavor>(engine, direct, p, has_history);
  run_svgf_frame<Flavor>(engine, indirect, p.indirect(), has_history);
  const int w = direct.guides.width;
  engine.run(svgf_stage::kSplitSum, SplitSumKernel{w, indirect.output, direct.output}, w,
             direct.guides.height);
}

}  // namespace svgf

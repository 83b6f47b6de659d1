#pragma once
// One SVGF frame, written once for every backend. An Engine runs a pixel kernel over the image
// wherever it lives: `engine.run(stage, kernel, width, height)` (kernel(x, y) per pixel) and
// `engine.run_counting(stage, kernel, width, height)` (kernel returns bool; the engine counts
// true results). The CPU engine loops with TBB, the CUDA engine launches; the kernels and this
// data flow are the same code on both, which is what makes exact mode bitwise.
#include "core/atrous.h"
#include "core/copy.h"
#include "core/demodulate.h"
#include "core/params.h"
#include "core/remodulate.h"
#include "core/reproject.h"
#include "core/stage_times.h"
#include "core/variance.h"
#include "core/views.h"

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
  IllumVarView filtered[2];  // a-trous ping-pong
  // Output: the denoised, remodulated color.
  RgbView output;
};

// The first two stages' kernels for a frame (also used by CUDA fast mode, which fuses them).
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

template <class Engine>
void run_svgf_frame(Engine& engine, const SvgfFrameBuffers& b, const SvgfParams& p,
                    bool has_history) {
  const int w = b.guides.width;
  const int h = b.guides.height;

  // 1. (color - emission) / albedo -> illumination (bad samples replaced and counted).
  engine.run_counting(Stage::Demodulate, demodulate_kernel_for(b, p), w, h);

  // 2. illumination + history -> accumulated color, moments and history length.
  engine.run(Stage::Reproject, reproject_kernel_for(b, p, has_history), w, h);

  // 3. accumulated -> filtered[0] with its variance (spatial estimate for young history).
  engine.run(Stage::Variance,
             VarianceKernel{b.guides, b.accumulated, b.next_moment1, b.next_moment2,
                            b.next_history, b.filtered[0], p},
             w, h);

  // 4. a-trous iterations ping-pong between filtered[0] and filtered[1]; the feedback tap's
  //    output becomes the next frame's color history.
  bool fed_back = false;
  int current = 0;
  for (int it = 0; it < p.iterations; ++it) {
    engine.run(Stage::Atrous,
               AtrousKernel{b.guides, b.filtered[current], b.filtered[1 - current], 1 << it, p},
               w, h);
    current = 1 - current;
    if (it == p.feedback_tap) {
      engine.run(Stage::Feedback, CopyRgbKernel{w, b.filtered[current].color, b.next_color}, w,
                 h);
      fed_back = true;
    }
  }
  if (!fed_back)  // no feedback tap in range: the unfiltered accumulation is the history
    engine.run(Stage::Feedback, CopyRgbKernel{w, b.accumulated.color, b.next_color}, w, h);

  // 5. filtered illumination * albedo + emission -> output.
  engine.run(Stage::Remodulate,
             RemodulateKernel{w, b.filtered[current].color, b.albedo, b.emission, b.output,
                              p.albedo_epsilon},
             w, h);
}

}  // namespace svgf

#pragma once
// The joint bilateral filter (GAMES202 homework 5) behind the Denoiser interface, written once
// over a backend (kernels_cpu/cpu_backend.h). A frame's data flow (the spatial filter; the
// homework's temporal accumulation is not built yet, docs/jbf.md):
//   sanitize  the backend's: bad input repaired and counted (core/sanitize.h)
//   filter    full window: color -> filtered, one pass of radius taps either side
//   atrous    or: color -> signal 0 -> signal 1 -> ... -> filtered, 5x5 taps at 1, 2, 4, ...
//   temporal  filtered + the reprojected, clamped history -> accumulated = output
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "core/denoiser.h"
#include "core/frame_inputs.h"
#include "methods/jbf/filter.h"
#include "methods/jbf/params.h"
#include "methods/jbf/temporal.h"

namespace svgf {

namespace jbf_stage {
inline constexpr const char* kFilter = "filter";  // the full window
inline constexpr const char* kAtrous = "atrous";  // the a-trous levels
inline constexpr const char* kTemporal = "temporal";
}  // namespace jbf_stage

namespace jbf_buffer {
inline constexpr const char* kFiltered = "filtered";        // this frame's spatial result
inline constexpr const char* kAccumulated = "accumulated";  // the history the next frame reads
}  // namespace jbf_buffer

struct JbfFrameBuffers {
  FrameInputs in;          // with world positions
  GuideView prev_guides;   // the previous frame's
  RgbView signal[2];
  RgbView filtered;
  ConstRgbView prev_accumulated;
  RgbView accumulated;
  RgbView output;
};

template <class Arith, class Engine>
void run_jbf_frame(Engine& engine, const JbfFrameBuffers& b, const JbfParams& p,
                   bool has_history) {
  namespace stage = jbf_stage;
  const GuideView& g = b.in.guides;
  const int w = g.width, h = g.height;
  const JbfScales scales = JbfScales::of(p);
  if (!p.atrous()) {
    engine.run(stage::kFilter,
               JbfPass<Arith>{g, b.in.position, b.in.color, b.filtered, p.radius, 1, false,
                              scales},
               w, h);
  } else {
    ConstRgbView in = b.in.color;
    for (int level = 0; level < p.levels; ++level) {
      const RgbView out = level + 1 == p.levels ? b.filtered : b.signal[level % 2];
      engine.run(stage::kAtrous,
                 JbfPass<Arith>{g, b.in.position, in, out, 2, 1 << level, true, scales}, w, h);
      in = out;
    }
  }
  // Exact arithmetic in every mode: a few operations a pixel besides the 7x7 moments.
  JbfTemporal t;
  t.guides = g;
  t.prev_guides = b.prev_guides;
  t.filtered = b.filtered;
  t.prev_accumulated = b.prev_accumulated;
  t.accumulated = b.accumulated;
  t.output = b.output;
  t.has_history = has_history && p.alpha < 1.f;
  t.alpha = p.alpha;
  t.clamp_k = p.clamp_k;
  engine.run(stage::kTemporal, t, w, h);
}

template <class Backend>
class JbfDenoiser final : public DenoiserOver<JbfDenoiser<Backend>, Backend> {
 public:
  JbfDenoiser(const JbfParams& params, const EngineConfig& config)
      : params_(params), mode_(config.mode), backend_(config) {
    params_.validate();
    backend_.set_method_planes(3 + 6 + (params_.atrous() ? 6 : 0));
  }

  void reset() override { has_history_ = false; }
  const FrameReport& last_report() const override { return report_.of(backend_.engine()); }
  std::string description() const override {
    return (params_.atrous() ? "jbf-atrous " + std::to_string(params_.levels) + " levels "
                             : "jbf r" + std::to_string(params_.radius) + " ") +
           backend_.description();
  }
  std::vector<std::string> stages() const override {
    return {kSanitizeStage, params_.atrous() ? jbf_stage::kAtrous : jbf_stage::kFilter,
            jbf_stage::kTemporal};
  }
  std::vector<std::string> debug_buffers() const override {
    return {jbf_buffer::kFiltered, jbf_buffer::kAccumulated};
  }
  Image read_buffer(std::string_view name) const override {
    const typename Backend::Buffer* buffer =
        name == jbf_buffer::kFiltered      ? &filtered_
        : name == jbf_buffer::kAccumulated ? &accumulated_[slot_]  // written by the last frame
                                           : nullptr;
    if (!buffer) throw unknown_buffer("jbf", name, debug_buffers());
    if (backend_.width() == 0) return Image();
    return backend_.read(*buffer);
  }

 private:
  friend class DenoiserOver<JbfDenoiser<Backend>, Backend>;  // calls denoise_frame
  // One frame, either path: a Frame into an Image, or a DeviceFrame into a DeviceTarget (the
  // backend's overloads move the data; the frame is the same).
  template <class Source, class Target>
  void denoise_frame(const Source& in, Target& out) {
    report_.frame_started();
    check_frame(in, out);
    if (in.position.empty())
      throw std::invalid_argument("frame " + std::to_string(in.index) +
                                  ": jbf needs the 'position' channel (world positions)");
    if (backend_.resize(in.width(), in.height())) {
      backend_.allocate(filtered_, 3, "jbf filtered color");
      for (int s = 0; s < 2; ++s) backend_.allocate(accumulated_[s], 3, "jbf accumulation");
      has_history_ = false;
      if (params_.atrous()) {
        backend_.allocate(signal_[0], 3, "jbf a-trous signal 0");
        backend_.allocate(signal_[1], 3, "jbf a-trous signal 1");
      }
    }
    auto& engine = backend_.engine();
    backend_.begin_frame(in, out);
    JbfFrameBuffers b;
    b.in = backend_.inputs(in, /*position=*/true);
    b.prev_guides = backend_.previous_guides();
    b.filtered = backend_.rgb(filtered_);
    b.prev_accumulated = backend_.rgb(accumulated_[slot_]);
    b.accumulated = backend_.rgb(accumulated_[1 - slot_]);
    if (params_.atrous()) {
      b.signal[0] = backend_.rgb(signal_[0]);
      b.signal[1] = backend_.rgb(signal_[1]);
    }
    b.output = backend_.output(out);
#if defined(__CUDACC__)
    if (mode_ == Mode::Fast)
      run_jbf_frame<FastArith>(engine, b, params_, has_history_);
    else
#endif
      run_jbf_frame<ExactArith>(engine, b, params_, has_history_);
    backend_.finish(in, out);  // the host path waits here, the device path does not
    slot_ = 1 - slot_;
    has_history_ = true;
    report_.frame_done(engine);
  }

  JbfParams params_;
  Mode mode_;
  Backend backend_;
  typename Backend::Buffer filtered_, accumulated_[2], signal_[2];
  int slot_ = 0;  // accumulated_[slot_] is the history the next frame reads
  bool has_history_ = false;
  LastReport report_;
};

}  // namespace svgf

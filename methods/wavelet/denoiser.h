#pragma once
// The CIS 565 wavelet filter behind the Denoiser interface, written once over a backend
// (kernels_cpu/cpu_backend.h). A frame's data flow (single frame: no history):
//   demodulate  color, albedo, emission -> illumination = (color - emission) / (albedo + eps)
//               and its luma L; bad samples replaced by 0 and counted
//   spread      L -> sqrt(|mean(L^2) - mean(L)^2|) over 3x3
//   deviation   spread -> Dev = clamp(g3x3(spread), eps, 1)
//   atrous      illumination -> signal 0 -> signal 1 -> ..., passes at steps 1, 2, 4, ...
//   remodulate  last signal -> output = filtered * (albedo + eps) + emission
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "core/copy.h"
#include "core/denoiser.h"
#include "core/frame_inputs.h"
#include "core/normal_weight.h"
#include "methods/wavelet/atrous.h"
#include "methods/wavelet/demodulate.h"
#include "methods/wavelet/deviation.h"
#include "methods/wavelet/params.h"

namespace svgf {

namespace wavelet_stage {
inline constexpr const char* kDemodulate = "demodulate";
inline constexpr const char* kSpread = "spread";
inline constexpr const char* kDeviation = "deviation";
inline constexpr const char* kAtrous = "atrous";
inline constexpr const char* kRemodulate = "remodulate";
}  // namespace wavelet_stage

namespace wavelet_buffer {
inline constexpr const char* kIllumination = "illumination";
inline constexpr const char* kLuma = "luma";
inline constexpr const char* kDeviation = "deviation";
inline constexpr const char* kFiltered = "filtered";  // the last pass's result
}  // namespace wavelet_buffer

// Every buffer one frame touches, on the engine's side.
struct WaveletFrameBuffers {
  FrameInputs in;
  RgbView illumination;
  float* luma = nullptr;
  float* spread = nullptr;
  float* deviation = nullptr;
  RgbView signal[2];
  RgbView output;
};

// The pass that wrote the frame's filtered illumination: 0 the demodulated input (no pass),
// else signal (passes - 1) % 2.
inline ConstRgbView wavelet_filtered(const WaveletFrameBuffers& b, int passes) {
  if (passes <= 0) return b.illumination;
  return b.signal[(passes - 1) % 2];
}

template <class Arith, class Engine>
void run_wavelet_frame(Engine& engine, const WaveletFrameBuffers& b, const WaveletParams& p) {
  namespace stage = wavelet_stage;
  const GuideView& g = b.in.guides;
  const int w = g.width, h = g.height;
  engine.run(stage::kDemodulate,
             WaveletDemodulateKernel{w, b.in.color, b.in.albedo, b.in.emission, b.illumination,
                                     b.luma, p.epsilon},
             w, h);
  engine.run(stage::kSpread, WaveletSpreadKernel{w, h, b.luma, b.spread}, w, h);
  engine.run(stage::kDeviation, WaveletDeviationKernel{w, h, b.spread, b.deviation, p.epsilon},
             w, h);
  using Power = NormalPower<Arith>;
  ConstRgbView in = b.illumination;
  for (int pass = 0; pass < p.iterations; ++pass) {
    const RgbView out = b.signal[pass % 2];
    engine.run(stage::kAtrous,
               WaveletIteration<Arith, Power>{g, in, out, b.luma, b.deviation, 1 << pass,
                                              p.kernel_size, 1.f / (p.sigma_depth + p.epsilon),
                                              p.sigma_luma, p.epsilon,
                                              Power::of(p.sigma_normal)},
               w, h);
    in = out;
  }
  engine.run(stage::kRemodulate,
             ForwardKernel<ConstRgbView, WaveletRemodulateSink>{
                 w, in, WaveletRemodulateSink{b.in.albedo, b.in.emission, b.output, p.epsilon}},
             w, h);
}

template <class Backend>
class WaveletDenoiser final : public DenoiserOver<WaveletDenoiser<Backend>, Backend> {
 public:
  WaveletDenoiser(const WaveletParams& params, const EngineConfig& config)
      : params_(params), mode_(config.mode), backend_(config) {
    params_.validate();
    backend_.set_method_planes(3 + 1 + 1 + 1 + 2 * 3);
  }

  void reset() override {}  // no history
  const FrameReport& last_report() const override { return report_.of(backend_.engine()); }
  std::string description() const override {
    return "wavelet " + std::to_string(params_.kernel_size) + "x" +
           std::to_string(params_.kernel_size) + " " + backend_.description();
  }
  std::vector<std::string> stages() const override {
    namespace s = wavelet_stage;
    return {kSanitizeStage, s::kDemodulate, s::kSpread, s::kDeviation, s::kAtrous, s::kRemodulate};
  }
  std::vector<std::string> debug_buffers() const override {
    namespace b = wavelet_buffer;
    return {b::kIllumination, b::kLuma, b::kDeviation, b::kFiltered};
  }
  Image read_buffer(std::string_view name) const override {
    namespace b = wavelet_buffer;
    const typename Backend::Buffer* buffer =
        name == b::kIllumination ? &illumination_
        : name == b::kLuma       ? &luma_
        : name == b::kDeviation  ? &deviation_
        : name == b::kFiltered   ? (params_.iterations > 0
                                        ? &signal_[(params_.iterations - 1) % 2]
                                        : &illumination_)
                                 : nullptr;
    if (!buffer) throw unknown_buffer("wavelet", name, debug_buffers());
    if (backend_.width() == 0) return Image();
    return backend_.read(*buffer);
  }

 private:
  friend class DenoiserOver<WaveletDenoiser<Backend>, Backend>;  // calls denoise_frame
  // One frame, either path: a Frame into an Image, or a DeviceFrame into a DeviceTarget (the
  // backend's overloads move the data; the frame is the same).
  template <class Source, class Target>
  void denoise_frame(const Source& in, Target& out) {
    report_.frame_started();
    check_frame(in, out);
    if (backend_.resize(in.width(), in.height())) {
      backend_.allocate(illumination_, 3, "wavelet illumination");
      backend_.allocate(luma_, 1, "wavelet luma");
      backend_.allocate(spread_, 1, "wavelet spread");
      backend_.allocate(deviation_, 1, "wavelet deviation");
      backend_.allocate(signal_[0], 3, "wavelet signal 0");
      backend_.allocate(signal_[1], 3, "wavelet signal 1");
    }
    auto& engine = backend_.engine();
    backend_.begin_frame(in, out);
    WaveletFrameBuffers b;
    b.in = backend_.inputs(in);
    b.illumination = backend_.rgb(illumination_);
    b.luma = backend_.plane(luma_, 0);
    b.spread = backend_.plane(spread_, 0);
    b.deviation = backend_.plane(deviation_, 0);
    b.signal[0] = backend_.rgb(signal_[0]);
    b.signal[1] = backend_.rgb(signal_[1]);
    b.output = backend_.output(out);
#if defined(__CUDACC__)
    if (mode_ == Mode::Fast)
      run_wavelet_frame<FastArith>(engine, b, params_);
    else
#endif
      run_wavelet_frame<ExactArith>(engine, b, params_);
    backend_.finish(in, out);  // the host path waits here, the device path does not
    report_.frame_done(engine);
  }

  WaveletParams params_;
  Mode mode_;
  Backend backend_;
  typename Backend::Buffer illumination_, luma_, spread_, deviation_, signal_[2];
  LastReport report_;
};

}  // namespace svgf

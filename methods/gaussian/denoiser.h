#pragma once
// The Gaussian baseline behind the Denoiser interface, written once over a backend
// (kernels_cpu/cpu_backend.h). A frame's data flow:
//   sanitize  the backend's: bad input repaired and counted (core/sanitize.h)
//   blur_x    color -> blurred, along rows
//   blur_y    blurred -> output, along columns
#include <string>
#include <string_view>
#include <vector>

#include "core/denoiser.h"
#include "core/frame_inputs.h"
#include "methods/gaussian/blur.h"
#include "methods/gaussian/params.h"

namespace svgf {

namespace gaussian_stage {
inline constexpr const char* kBlurX = "blur_x";
inline constexpr const char* kBlurY = "blur_y";
}  // namespace gaussian_stage

template <class Arith, class Engine>
void run_gaussian_frame(Engine& engine, ConstRgbView color, RgbView blurred, RgbView output, int w,
                        int h, const GaussianParams& p) {
  namespace stage = gaussian_stage;
  GaussianPass<Arith> pass{w, h, color, blurred, 1, 0, p.effective_radius(),
                           -1.f / (2.f * p.sigma * p.sigma)};
  engine.run(stage::kBlurX, pass, w, h);
  pass.in = blurred;
  pass.out = output;
  pass.dx = 0;
  pass.dy = 1;
  engine.run(stage::kBlurY, pass, w, h);
}

template <class Backend>
class GaussianDenoiser final : public DenoiserOver<GaussianDenoiser<Backend>, Backend> {
 public:
  GaussianDenoiser(const GaussianParams& params, const EngineConfig& config)
      : params_(params), mode_(config.mode), backend_(config) {
    params_.validate();
    backend_.set_method_planes(3);
  }

  void reset() override {}  // no history
  const FrameReport& last_report() const override { return report_.of(backend_.engine()); }
  std::string description() const override { return "gaussian " + backend_.description(); }
  std::vector<std::string> stages() const override {
    return {kSanitizeStage, gaussian_stage::kBlurX, gaussian_stage::kBlurY};
  }
  std::vector<std::string> debug_buffers() const override { return {"blurred_x"}; }
  Image read_buffer(std::string_view name) const override {
    if (name != "blurred_x") throw unknown_buffer("gaussian", name, debug_buffers());
    if (backend_.width() == 0) return Image();
    return backend_.read(blurred_);
  }

 private:
  friend class DenoiserOver<GaussianDenoiser<Backend>, Backend>;  // calls denoise_frame
  // One frame, either path: a Frame into an Image, or a DeviceFrame into a DeviceTarget (the
  // backend's overloads move the data; the frame is the same).
  template <class Source, class Target>
  void denoise_frame(const Source& in, Target& out) {
    report_.frame_started();
    check_frame(in, out);
    if (backend_.resize(in.width(), in.height())) backend_.allocate(blurred_, 3, "blurred rows");
    auto& engine = backend_.engine();
    backend_.begin_frame(in, out);
    const FrameInputs cur = backend_.inputs(in);
    const RgbView output = backend_.output(out);
#if defined(__CUDACC__)
    if (mode_ == Mode::Fast)
      run_gaussian_frame<FastArith>(engine, cur.color, backend_.rgb(blurred_), output,
                                    in.width(), in.height(), params_);
    else
#endif
      run_gaussian_frame<ExactArith>(engine, cur.color, backend_.rgb(blurred_), output,
                                     in.width(), in.height(), params_);
    backend_.finish(in, out);  // the host path waits here, the device path does not
    report_.frame_done(engine);
  }

  GaussianParams params_;
  Mode mode_;
  Backend backend_;
  typename Backend::Buffer blurred_;
  LastReport report_;
};

}  // namespace svgf

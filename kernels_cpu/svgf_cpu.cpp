#include "kernels_cpu/svgf_cpu.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/svgf_pipeline.h"
#include "kernels_cpu/cpu_engine.h"

namespace svgf::cpu {
namespace {

class SvgfCpuDenoiser final : public Denoiser {
 public:
  explicit SvgfCpuDenoiser(const DenoiserConfig& config)
      : params_(config.svgf), engine_(config.threads) {}

  void denoise(const Frame& in, Image& out) override {
    check_frame_consistent(in);
    ensure_size(in.width(), in.height());
    out.ensure_shape(width_, height_, 3);  // every pixel is written by remodulate
    engine_.begin_frame();

    const int prev = slot_;
    const int next = 1 - slot_;
    SvgfFrameBuffers b;
    b.guides = in.guides();
    b.prev_guides = prev_guides_.view(width_, height_);
    b.color = in.color.rgb();
    b.albedo = in.albedo.rgb();
    if (!in.emission.empty()) b.emission = in.emission.rgb();
    b.prev_color = color_history_[prev].rgb();
    b.prev_moment1 = moments_[prev].plane(0);
    b.prev_moment2 = moments_[prev].plane(1);
    b.prev_history = history_[prev].plane(0);
    b.next_color = color_history_[next].rgb();
    b.next_moment1 = moments_[next].plane(0);
    b.next_moment2 = moments_[next].plane(1);
    b.next_history = history_[next].plane(0);
    b.illumination = illumination_.rgb();
    b.accumulated = {accumulated_.rgb(), accumulated_.plane(3)};
    b.filtered[0] = {filtered_[0].rgb(), filtered_[0].plane(3)};
    b.filtered[1] = {filtered_[1].rgb(), filtered_[1].plane(3)};
    b.output = out.rgb();
    run_svgf_frame(engine_, b, params_, has_history_);

    prev_guides_.assign(in);
    slot_ = next;
    has_history_ = true;
    report_.times = engine_.times();
    report_.replaced_samples = engine_.counted();
  }

  void reset() override { has_history_ = false; }
  const FrameReport& last_report() const override { return report_; }

  std::string description() const override {
    return "svgf cpu exact, " + std::to_string(engine_.threads()) + " threads";
  }

  Image read_buffer(DebugBuffer which) const override {
    switch (which) {
      case DebugBuffer::Illumination: return illumination_;
      case DebugBuffer::Accumulated: return accumulated_;
      case DebugBuffer::Moments: return moments_[slot_];
      case DebugBuffer::HistoryLength: return history_[slot_];
      case DebugBuffer::ColorHistory: return color_history_[slot_];
    }
    throw std::invalid_argument("read_buffer: unknown buffer");
  }

 private:
  // The previous frame's guides: the current frame's are read in place from the input.
  struct GuideCopy {
    Image planes;  // depth, depth_dx, depth_dy, normal xyz, motion xy
    std::vector<uint32_t> mesh_id;
    void allocate(int w, int h) {
      planes = Image(w, h, 8);
      mesh_id.assign(static_cast<size_t>(w) * h, 0u);
    }
    void assign(const Frame& f) {
      const size_t n = f.color.pixel_count();
      auto copy = [&](const float* src, int plane) { std::copy(src, src + n, planes.plane(plane)); };
      copy(f.depth.plane(0), 0);
      copy(f.depth_gradient.plane(0), 1);
      copy(f.depth_gradient.plane(1), 2);
      for (int c = 0; c < 3; ++c) copy(f.normal.plane(c), 3 + c);
      copy(f.motion.plane(0), 6);
      copy(f.motion.plane(1), 7);
      mesh_id = f.mesh_id;
    }
    GuideView view(int w, int h) const {
      GuideView g;
      g.width = w;
      g.height = h;
      g.depth = planes.plane(0);
      g.depth_dx = planes.plane(1);
      g.depth_dy = planes.plane(2);
      g.normal = planes.rgb(3);
      g.mesh_id = mesh_id.data();
      g.motion_x = planes.plane(6);
      g.motion_y = planes.plane(7);
      return g;
    }
  };

  void ensure_size(int w, int h) {
    if (w == width_ && h == height_) return;
    check_frame_size_unchanged(width_, height_, w, h);
    width_ = w;
    height_ = h;
    prev_guides_.allocate(w, h);
    for (int s = 0; s < 2; ++s) {
      color_history_[s] = Image(w, h, 3);
      moments_[s] = Image(w, h, 2);
      history_[s] = Image(w, h, 1);
      filtered_[s] = Image(w, h, 4);
    }
    illumination_ = Image(w, h, 3);
    accumulated_ = Image(w, h, 4);
    has_history_ = false;
  }

  SvgfParams params_;
  CpuEngine engine_;
  int width_ = 0, height_ = 0;
  int slot_ = 0;  // history slot the next frame reads
  bool has_history_ = false;
  GuideCopy prev_guides_;
  Image color_history_[2], moments_[2], history_[2];
  Image illumination_, accumulated_, filtered_[2];
  FrameReport report_;
};

}  // namespace

std::unique_ptr<Denoiser> make_svgf_denoiser(const DenoiserConfig& config) {
  if (config.mode != Mode::Exact)
    throw std::invalid_argument("fast mode exists on the CUDA backend only; the CPU is exact");
  return std::make_unique<SvgfCpuDenoiser>(config);
}

}  // namespace svgf::cpu

#pragma once
// The CPU backend of a denoiser written once (methods/<method>/denoiser.h): the TBB engine,
// host buffers, and a frame's inputs read in place. What a backend provides:
//   Engine& engine()                       runs pixel kernels (run, run_counting), times stages
//   using Buffer; allocate(buffer, channels, what)  a planar float buffer of the frame's size
//   set_method_planes(n)                   how many planes the method allocates (for errors)
//   float* plane(buffer, c); RgbView rgb(buffer, first); Image read(buffer)
//                                          its planes as views; a host copy
//   bool resize(w, h)                      frame size (true when buffers must be reallocated)
//   FrameInputs inputs(frame, position)    this frame's inputs on the backend's side (world
//                                          positions only when asked for)
//   GuideView previous_guides()            the guides of the frame before (valid after one frame)
//   RgbView output(out)                    where the frame's output goes
//   void finish(frame, out)                after the frame: output to the host, guides kept
#include <algorithm>
#include <string>
#include <vector>

#include "core/denoiser.h"
#include "core/frame.h"
#include "core/frame_inputs.h"
#include "kernels_cpu/cpu_engine.h"

namespace svgf::cpu {

class CpuBackend {
 public:
  using Engine = CpuEngine;
  using Buffer = Image;

  explicit CpuBackend(const EngineConfig& config) : engine_(config.threads) {
    if (config.mode != Mode::Exact)
      throw std::invalid_argument("fast mode exists on the CUDA backend only; the CPU is exact");
  }

  Engine& engine() { return engine_; }
  std::string description() const {
    return "cpu exact, " + std::to_string(engine_.threads()) + " threads";
  }

  int width() const { return width_; }
  int height() const { return height_; }
  bool resize(int w, int h) {
    if (w == width_ && h == height_) return false;
    check_frame_size_unchanged(width_, height_, w, h);
    width_ = w;
    height_ = h;
    return true;
  }
  void release() { width_ = height_ = 0; }

  void set_method_planes(int) {}
  void allocate(Buffer& b, int channels, const char*) { b = Image(width_, height_, channels); }
  float* plane(Buffer& b, int c) const { return b.plane(c); }
  // Three planes of a buffer from `first_plane` on, as a color view.
  RgbView rgb(Buffer& b, int first_plane = 0) const { return b.rgb(first_plane); }
  Image read(const Buffer& b) const { return b; }

  // `position`: the method reads world positions (read in place: free here).
  FrameInputs inputs(const Frame& f, bool position = false) const {
    FrameInputs in;
    in.guides = f.guides();
    in.color = f.color.rgb();
    in.albedo = f.albedo.rgb();
    if (!f.emission.empty()) in.emission = f.emission.rgb();
    if (position) in.position = f.position.rgb();
    return in;
  }

  // The previous frame's guides: a copy taken by finish(), since the caller's frame may not
  // outlive the call. Only a method that asks for them pays for the copy (the first call
  // allocates it; the first frame has no history, so its planes are not read).
  GuideView previous_guides() {
    if (prev_planes_.width() != width_ || prev_planes_.height() != height_) {
      prev_planes_ = Image(width_, height_, 8);
      prev_mesh_id_.assign(static_cast<size_t>(width_) * height_, 0u);
    }
    GuideView g;
    g.width = width_;
    g.height = height_;
    g.depth = prev_planes_.plane(0);
    g.depth_dx = prev_planes_.plane(1);
    g.depth_dy = prev_planes_.plane(2);
    g.normal = prev_planes_.rgb(3);
    g.mesh_id = prev_mesh_id_.data();
    g.motion_x = prev_planes_.plane(6);
    g.motion_y = prev_planes_.plane(7);
    return g;
  }

  RgbView output(Image& out) {
    out.ensure_shape(width_, height_, 3);  // every pixel is written by the frame
    return out.rgb();
  }

  void finish(const Frame& f, Image&) {
    if (prev_planes_.empty()) return;  // no method here reads the previous guides
    const size_t n = f.color.pixel_count();
    auto copy = [&](const float* src, int plane) {
      std::copy(src, src + n, prev_planes_.plane(plane));
    };
    copy(f.depth.plane(0), 0);
    copy(f.depth_gradient.plane(0), 1);
    copy(f.depth_gradient.plane(1), 2);
    for (int c = 0; c < 3; ++c) copy(f.normal.plane(c), 3 + c);
    copy(f.motion.plane(0), 6);
    copy(f.motion.plane(1), 7);
    prev_mesh_id_ = f.mesh_id;
  }

 private:
  CpuEngine engine_;
  int width_ = 0, height_ = 0;
  Image prev_planes_;  // depth, depth_dx, depth_dy, normal xyz, motion xy
  std::vector<uint32_t> prev_mesh_id_;
};

}  // namespace svgf::cpu

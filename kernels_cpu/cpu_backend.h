#pragma once
// The CPU backend of a denoiser written once (methods/<method>/denoiser.h): the TBB engine,
// host buffers, and a frame's inputs read in place. What a backend provides:
//   Engine& engine()                       runs pixel kernels (run, run_tallying), times stages
//   kDeviceFrames                          whether frames in GPU memory can be denoised where
//                                          they lie (the CUDA backend; DeviceFrame overloads
//                                          of begin_frame, inputs, output, finish)
//   kPackedStorage                         whether exact mode filters over packed pixels
//                                          (SVGF's SvgfExactPacked) instead of planes
//   void begin_frame(frame, out)           the frame's bookkeeping starts (engine.begin_frame)
//   using Buffer; allocate(buffer, channels, what)  a planar float buffer of the frame's size,
//                                          zero-filled
//   set_method_planes(n)                   how many planes the method allocates (for errors)
//   float* plane(buffer, c); RgbView rgb(buffer, first); Image read(buffer)
//                                          its planes as views; a host copy
//   bool resize(w, h)                      frame size (true when buffers must be reallocated)
//   FrameInputs inputs(frame, position, split, gradient_into, defer_sanitize, normals_into,
//                      motion_into)
//                                          this frame's inputs, sanitized unless the method
//                                          may run that stage itself and the backend lets it;
//                                          on the backend's side (world positions, direct and
//                                          indirect, and the gradient samples only when asked
//                                          for; split: the frame carries both; gradient_into:
//                                          3 planes the method lends for the gradient samples,
//                                          where a backend that copies them puts them;
//                                          normals_into: likewise for the normals, after
//                                          keep_previous_mesh_ids_only; motion_into: for the
//                                          motion's 2 planes, after keep_motion_in_lent_planes)
//   GuideView previous_guides()            the frame before's depth, normal and mesh id (valid
//                                          after one frame; its depth gradient and motion are
//                                          not kept: null)
//   keep_previous_mesh_ids_only()          the method keeps the frame before's depth and
//                                          normal itself: previous_guides() has its mesh ids
//   keep_motion_in_lent_planes()           the frame's motion goes to planes the method lends
//   RgbView output(out)                    where the frame's output goes
//   set_output_over_color()                the method reads the input color only before it
//                                          writes the output: the output may take its planes
//   void finish(frame, out)                after the frame: output to the host, guides kept
#include <algorithm>
#include <string>
#include <vector>

#include "core/denoiser.h"
#include "core/frame.h"
#include "core/frame_inputs.h"
#include "core/sanitize.h"
#include "core/stage_times.h"
#include "kernels_cpu/cpu_engine.h"
#include "kernels_cpu/sanitize_rows.h"

// Compiled outside the variants (not in this project): the includer's own flags.
#if !defined(SVGF_CPU_VARIANT_NAME)
#define SVGF_CPU_VARIANT_NAME "x86-64 (the includer's flags)"
#endif

namespace svgf::cpu {

class CpuBackend {
 public:
  using Engine = CpuEngine;
  using Buffer = Image;
  static constexpr bool kDeviceFrames = false;
  // Exact mode over planes: the row drivers stream them (kernels_cpu/svgf_rows.cpp).
  static constexpr bool kPackedStorage = false;

  explicit CpuBackend(const EngineConfig& config) : engine_(config.threads) {
    if (config.mode != Mode::Exact)
      throw std::invalid_argument("fast mode exists on the CUDA backend only; the CPU is exact");
  }

  Engine& engine() { return engine_; }
  const Engine& engine() const { return engine_; }
  void begin_frame(const Frame&, const Image&) { engine_.begin_frame(); }
  // E.g. "cpu exact, x86-64-v3, 2 threads": the instruction-set variant this code was compiled
  // into (kernels_cpu/CMakeLists.txt defines its name for each variant's objects).
  std::string description() const {
    return std::string("cpu exact, ") + SVGF_CPU_VARIANT_NAME + ", " +
           std::to_string(engine_.threads()) + " threads";
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

  // The frame's inputs, sanitized (core/sanitize.h), as the stages read them: in place when the
  // read-only scan finds nothing wrong (the common case: one read of the inputs), else a
  // repaired copy. `position`: the method reads world positions (then they are checked too);
  // `split`: direct and indirect (the frame carries both), checked as color is.
  // `gradient_into`: the method reads A-SVGF's gradient samples (read in place here; the
  // planes it lends are for a backend that copies them). `defer_sanitize`: the method may run
  // the sanitize stage itself (FrameInputs::sanitize_pending); reading the frame in place, this
  // backend runs it here, unless it copies the inputs (copies_inputs_, the tests' stand-in for
  // the CUDA backend's planes).
  // `normals_into`: where the method keeps the previous guides itself, 3 planes it lends for
  // the frame's normals, where a backend that copies them puts them (the copying stand-in
  // below, which holds the method to the lending as the CUDA backend does). `motion_into`:
  // likewise, 2 planes for the motion (keep_motion_in_lent_planes).
  FrameInputs inputs(const Frame& f, bool position = false, bool split = false,
                     float* gradient_into = nullptr, bool defer_sanitize = false,
                     float* normals_into = nullptr, float* motion_into = nullptr) {
    FrameInputs in;
    lent_color_ = {};
    lent_normals_ = normals_into;
    lent_motion_ = motion_into;
    if (defer_sanitize && copies_inputs_) {
      in = copied_inputs(f, position, split);
      in.sanitize_pending = true;
      if (output_over_color_) lent_color_ = repaired_.rgb(kColor);
    } else {
      SanitizeInputs scan{width_, input_planes(f, position, split), {}};
      engine_.run_tallying(kSanitizeStage, scan, width_, height_);
      in.guides = f.guides();
      in.color = f.color.rgb();
      in.albedo = f.albedo.rgb();
      if (!f.emission.empty()) in.emission = f.emission.rgb();
      if (position) in.position = f.position.rgb();
      if (split) {
        in.direct = f.direct.rgb();
        in.indirect = f.indirect.rgb();
      }
      if (engine_.tallies().any()) in = repaired_inputs(f, position, split);
    }
    if (gradient_into) in.gradient = gradient_samples(f);
    current_guides_ = in.guides;
    return in;
  }

  // The previous frame's depth, normal and mesh id (what the methods read of it: SVGF's
  // reprojection, the JBF's temporal pass; its depth gradient and motion are not kept, as on
  // CUDA): a copy taken by finish(), since the caller's frame may not outlive the call. Only a
  // method that asks for them pays for the copy (the first call allocates it; the first frame
  // has no history, so its planes are not read).
  GuideView previous_guides() {
    const size_t n = static_cast<size_t>(width_) * height_;
    if (prev_mesh_id_.size() != n) prev_mesh_id_.assign(n, 0u);
    if (!mesh_ids_only_ && (prev_planes_.width() != width_ || prev_planes_.height() != height_))
      prev_planes_ = Image(width_, height_, 4);
    GuideView g;
    g.width = width_;
    g.height = height_;
    if (!mesh_ids_only_) {
      g.depth = prev_planes_.plane(0);
      g.normal = prev_planes_.rgb(1);
    }
    g.mesh_id = prev_mesh_id_.data();
    return g;
  }
  void keep_previous_mesh_ids_only() { mesh_ids_only_ = true; }
  // The frame's motion goes to the 2 planes the method lends (inputs()' motion_into) where this
  // backend copies the inputs, as on CUDA (kernels_cuda/cuda_backend.h).
  void keep_motion_in_lent_planes() {}

  // The CUDA backend lends the output the input color's planes where the method asks
  // (kernels_cuda/cuda_backend.h). This one reads the frame in place and writes the output
  // into the caller's image; its copying stand-in for CUDA (copies_inputs_) lends its copy of
  // the color, so that the CPU tests hold the method to the order the lending relies on.
  void set_output_over_color() { output_over_color_ = true; }
  RgbView output(Image& out) {
    out.ensure_shape(width_, height_, 3);  // every pixel is written by the frame
    return lent_color_.r ? lent_color_ : out.rgb();
  }

  void finish(const Frame& f, Image& out) {
    const size_t n = f.color.pixel_count();  // mesh_id's size too (check_frame)
    if (lent_color_.r)
      engine_.copy_planes<float>({{lent_color_.r, out.plane(0)},
                                  {lent_color_.g, out.plane(1)},
                                  {lent_color_.b, out.plane(2)}},
                                 n);
    if (prev_mesh_id_.empty()) return;  // no method here reads the previous guides
    prev_mesh_id_.resize(n);
    engine_.copy_planes<uint32_t>({{f.mesh_id.data(), prev_mesh_id_.data()}}, n);
    if (mesh_ids_only_) return;
    const GuideView& g = current_guides_;  // sanitized
    engine_.copy_planes<float>({{g.depth, prev_planes_.plane(0)},
                                {g.normal.r, prev_planes_.plane(1)},
                                {g.normal.g, prev_planes_.plane(2)},
                                {g.normal.b, prev_planes_.plane(3)}},
                               n);
  }

 private:
  // The gradient samples, in place (the sanitize stage does not read them).
  static GradientSampleView gradient_samples(const Frame& f) {
    GradientSampleView g;
    if (f.gradient.empty()) return g;
    g.previous = f.gradient.plane(0);
    g.current = f.gradient.plane(1);
    g.mask = f.gradient.plane(2);
    return g;
  }

  static InputPlanes input_planes(const Frame& f, bool position, bool split) {
    InputPlanes p;
    if (split) {
      p.direct = f.direct.rgb();
      p.indirect = f.indirect.rgb();
    }
    p.color = f.color.rgb();
    p.albedo = f.albedo.rgb();
    if (!f.emission.empty()) p.emission = f.emission.rgb();
    p.normal = f.normal.rgb();
    if (position) p.position = f.position.rgb();
    p.depth = f.depth.plane(0);
    p.depth_dx = f.depth_gradient.plane(0);
    p.depth_dy = f.depth_gradient.plane(1);
    p.motion_x = f.motion.plane(0);
    p.motion_y = f.motion.plane(1);
    return p;
  }

  // A copy of the frame's inputs with the bad pixels repaired (the same kernel, writing).
  FrameInputs repaired_inputs(const Frame& f, bool position, bool split) {
    FrameInputs r = copied_inputs(f, position, split);
    engine_.run(kSanitizeStage, r.sanitize, width_, height_);
    return r;
  }

  // The planes of repaired_.
  enum CopiedPlane : int { kColor = 0, kAlbedo = 3, kNormal = 6, kDepth = 9, kDepthDx, kDepthDy,
                           kMotionX, kMotionY, kEmission = 14, kPosition = 17, kDirect = 20,
                           kIndirect = 23, kPlanes = 26 };
  // A copy of the frame's inputs, and the sanitize rule in place over it (not run).
  FrameInputs copied_inputs(const Frame& f, bool position, bool split) {
    if (repaired_.width() != width_ || repaired_.height() != height_)
      repaired_ = Image(width_, height_, kPlanes);
    const size_t n = f.color.pixel_count();
    auto copy = [&](const float* src, int plane) {
      std::copy(src, src + n, repaired_.plane(plane));
    };
    // The normals go to the planes the method lent, where it did.
    const RgbView normal = lent_normals_ ? RgbView{lent_normals_, lent_normals_ + n,
                                                   lent_normals_ + 2 * n}
                                         : repaired_.rgb(kNormal);
    float* const normal_planes[3] = {normal.r, normal.g, normal.b};
    for (int c = 0; c < 3; ++c) {
      copy(f.color.plane(c), kColor + c);
      copy(f.albedo.plane(c), kAlbedo + c);
      std::copy(f.normal.plane(c), f.normal.plane(c) + n, normal_planes[c]);
      if (!f.emission.empty()) copy(f.emission.plane(c), kEmission + c);
      if (position) copy(f.position.plane(c), kPosition + c);
      if (split) {
        copy(f.direct.plane(c), kDirect + c);
        copy(f.indirect.plane(c), kIndirect + c);
      }
    }
    copy(f.depth.plane(0), kDepth);
    copy(f.depth_gradient.plane(0), kDepthDx);
    copy(f.depth_gradient.plane(1), kDepthDy);
    // The motion likewise.
    float* const motion_x = lent_motion_ ? lent_motion_ : repaired_.plane(kMotionX);
    float* const motion_y = lent_motion_ ? lent_motion_ + n : repaired_.plane(kMotionY);
    std::copy(f.motion.plane(0), f.motion.plane(0) + n, motion_x);
    std::copy(f.motion.plane(1), f.motion.plane(1) + n, motion_y);

    InputPlanesOut out;
    out.color = repaired_.rgb(kColor);
    out.albedo = repaired_.rgb(kAlbedo);
    out.normal = normal;
    if (!f.emission.empty()) out.emission = repaired_.rgb(kEmission);
    if (position) out.position = repaired_.rgb(kPosition);
    if (split) {
      out.direct = repaired_.rgb(kDirect);
      out.indirect = repaired_.rgb(kIndirect);
    }
    out.depth = repaired_.plane(kDepth);
    out.depth_dx = repaired_.plane(kDepthDx);
    out.depth_dy = repaired_.plane(kDepthDy);
    out.motion_x = motion_x;
    out.motion_y = motion_y;
    InputPlanes in;
    in.color = out.color;
    in.albedo = out.albedo;
    in.emission = out.emission;
    in.normal = out.normal;
    in.position = out.position;
    in.direct = out.direct;
    in.indirect = out.indirect;
    in.depth = out.depth;
    in.depth_dx = out.depth_dx;
    in.depth_dy = out.depth_dy;
    in.motion_x = out.motion_x;
    in.motion_y = out.motion_y;

    FrameInputs r;
    r.sanitize = SanitizeInputs{width_, in, out};
    r.guides.width = width_;
    r.guides.height = height_;
    r.guides.depth = out.depth;
    r.guides.depth_dx = out.depth_dx;
    r.guides.depth_dy = out.depth_dy;
    r.guides.normal = out.normal;
    r.guides.mesh_id = f.mesh_id.data();
    r.guides.motion_x = out.motion_x;
    r.guides.motion_y = out.motion_y;
    r.color = out.color;
    r.albedo = out.albedo;
    r.emission = out.emission;
    r.position = out.position;
    r.direct = out.direct;
    r.indirect = out.indirect;
    return r;
  }

  CpuEngine engine_;
  int width_ = 0, height_ = 0;
  Image prev_planes_;  // depth, normal xyz
  Image repaired_;     // the inputs of a frame that needed repairs, or copied (copies_inputs_)
  GuideView current_guides_;
  std::vector<uint32_t> prev_mesh_id_;
  bool output_over_color_ = false;  // set_output_over_color
  bool mesh_ids_only_ = false;      // keep_previous_mesh_ids_only
  RgbView lent_color_;              // this frame's output, where it is the copied color
  float* lent_normals_ = nullptr;   // inputs()' normals_into
  float* lent_motion_ = nullptr;    // inputs()' motion_into

 protected:
  // Copy every frame's inputs and leave the sanitize stage to a method that asks to run it
  // (inputs()' defer_sanitize), as the CUDA backend does: how the CPU tests run SVGF's fused
  // sanitize (tests/svgf_packed_exact_test.cpp).
  bool copies_inputs_ = false;
};

}  // namespace svgf::cpu

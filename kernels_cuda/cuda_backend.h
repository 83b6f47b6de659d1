#pragma once
// The CUDA backend of a denoiser written once (the concept is described in
// kernels_cpu/cpu_backend.h): the CUDA engine, device buffers, and a frame's way in and out:
// the host path (a Frame: one pinned upload of its inputs, one download of its output, waited
// for) or the device path (a DeviceFrame already on the GPU: copied from the caller's buffers
// and back on the caller's stream, nothing waited for; Denoiser::denoise_device). Either way
// the inputs land in the same planes; the two guide slots alternate, so the previous frame's
// inputs are this frame's previous guides (no copy). Host-compilable.
#include <cstring>
#include <stdexcept>
#include <string>

#include "core/denoiser.h"
#include "core/device_frame.h"
#include "core/frame.h"
#include "core/frame_inputs.h"
#include "core/sanitize.h"
#include "core/stage_times.h"
#include "kernels_cuda/cuda_engine.h"
#include "kernels_cuda/cuda_handles.h"
#include "kernels_cuda/device_array.h"
#include "kernels_cuda/host_staging.h"
#include "kernels_cuda/strided_copy.h"

namespace svgf::cuda {

class CudaBackend {
 public:
  using Engine = CudaEngine;
  using Buffer = DeviceArray<float>;
  // Frames in device memory can be denoised where they lie (the methods' denoise_device).
  static constexpr bool kDeviceFrames = true;
  // Exact mode filters over packed pixels too (methods/svgf/flavors.h: SvgfExactPacked): fewer
  // load instructions a tap, the same bits.
  static constexpr bool kPackedStorage = true;

  explicit CudaBackend(const EngineConfig& config)
      : mode_(config.mode), engine_(checked_shape(config)), host_copies_(config.threads) {
    SVGF_CUDA_CHECK(cudaGetDevice(&device_), "cudaGetDevice");
  }

  Engine& engine() { return engine_; }
  const Engine& engine() const { return engine_; }

  std::string description() const {
    cudaDeviceProp prop{};
    const bool named = cudaGetDeviceProperties(&prop, device_) == cudaSuccess;
    if (!named) (void)cudaGetLastError();
    const LaunchShape s = engine_.shape();
    return std::string("cuda ") + to_string(mode_) + ", " +
           (named ? std::string(prop.name) : "device " + std::to_string(device_)) + ", block " +
           std::to_string(s.block_x) + "x" + std::to_string(s.block_y);
  }

  int width() const { return width_; }
  int height() const { return height_; }
  size_t pixels() const { return static_cast<size_t>(width_) * static_cast<size_t>(height_); }

  // Also makes this denoiser's device current for the frame.
  bool resize(int w, int h) {
    SVGF_CUDA_CHECK(cudaSetDevice(device_), "cudaSetDevice");
    if (w == width_ && h == height_) return false;
    check_frame_size_unchanged(width_, height_, w, h);
    width_ = w;
    height_ = h;
    try {
      for (int s = 0; s < 2; ++s)
        allocate(guides_[s], mesh_ids_only_ ? 1 : kKeptPlanes,
                 mesh_ids_only_ ? "frame mesh ids" : "frame guides");
      if (mesh_ids_only_) allocate(depth_, 1, "frame depth");
      allocate(shading_, shading_planes(), "frame inputs");
      if (!output_over_color_) allocate(output_, 3, "output");
      staging_in_.resize(kInputPlanes * pixels(), "the pinned input staging buffer");
      staging_out_.resize(3 * pixels(), "the pinned output staging buffer");
    } catch (...) {
      release();
      throw;
    }
    return true;
  }
  void release() {
    for (int s = 0; s < 2; ++s) guides_[s].resize(0);
    depth_.resize(0);
    shading_.resize(0);
    output_.resize(0);
    position_.resize(0);
    staging_position_.resize(0, "");
    split_.resize(0);
    staging_split_.resize(0, "");
    staging_in_.resize(0, "");
    staging_out_.resize(0, "");
    width_ = height_ = 0;
  }

  // How many float planes of the frame's size the method allocates (for the error message).
  void set_method_planes(int planes) { method_planes_ = planes; }
  // The method reads the input color only in stages that have finished before it writes any
  // pixel of the output (SVGF: the demodulation and the reprojection), so the output may take
  // the color's planes and the backend keeps none of its own: 3 planes fewer (issue 14 item
  // 5). Set before the first frame (the denoiser's constructor).
  void set_output_over_color() { output_over_color_ = true; }
  // The method keeps the previous frame's depth and normal itself (SVGF's packed flavors: the
  // packed guides a frame writes are the next one's previous guides, methods/svgf/denoiser.h),
  // so the backend keeps the previous frame's mesh ids only: previous_guides() has no depth or
  // normal, a frame's depth has a plane of its own and its normals land in the 3 planes the
  // method lends (inputs()' normals_into). 7 planes fewer here (issue 14 item 5). Set before
  // the first frame (the denoiser's constructor).
  void keep_previous_mesh_ids_only() { mesh_ids_only_ = true; }
  // The frame's motion lands in the 2 planes the method lends (inputs()' motion_into): SVGF's
  // next moments, which its first pixel kernel writes over the motion pixel by pixel after
  // reading it (methods/svgf/denoiser.h). 2 planes fewer here (issue 14 item 5). Set before the
  // first frame (the denoiser's constructor).
  void keep_motion_in_lent_planes() { motion_lent_ = true; }

  // `what` and what the whole frame size needs name the buffer in an out-of-memory error.
  // Zero-filled, as the CPU's: a buffer a method fills only in part (BMFR's per-block data)
  // reads back defined.
  void allocate(Buffer& b, int channels, const char* what) {
    const size_t planes = static_cast<size_t>((mesh_ids_only_ ? 2 + 1 : 2 * kKeptPlanes) +
                                              shading_planes() + (output_over_color_ ? 0 : 3) +
                                              method_planes_);
    const size_t mib = (planes * pixels() * sizeof(float) + (1u << 20) - 1) >> 20;
    const std::string named = std::string(what) + " (" + std::to_string(width_) + "x" +
                              std::to_string(height_) + " frames need about " +
                              std::to_string(mib) + " MiB of device memory in all)";
    b.resize(static_cast<size_t>(channels) * pixels(), named.c_str());
    SVGF_CUDA_CHECK(cudaMemset(b.get(), 0, b.size() * sizeof(float)), named);
    // cudaMemset may still run when it returns, and the frames' streams (ours, non-blocking, or
    // the caller's) are not ordered after it: wait, once per buffer and sequence.
    SVGF_CUDA_CHECK(cudaStreamSynchronize(nullptr), named);
  }
  float* plane(const Buffer& b, int c) const { return b.get() + static_cast<size_t>(c) * pixels(); }
  // Three planes of a buffer from `first_plane` on, as a color view.
  RgbView rgb(const Buffer& a, int first_plane = 0) const {
    return {plane(a, first_plane), plane(a, first_plane + 1), plane(a, first_plane + 2)};
  }
  Image read(const Buffer& b) const {
    SVGF_CUDA_CHECK(cudaSetDevice(device_), "cudaSetDevice");
    engine_.wait_frame();
    Image im(width_, height_, static_cast<int>(b.size() / pixels()));
    b.download(im.data().data(), im.data().size());
    return im;
  }

  // The host path's frame runs on the engine's own stream.
  void begin_frame(const Frame&, const Image&) { engine_.begin_frame(); }
  // The device path's on the caller's stream, once every address it names is device memory
  // this denoiser can use (checked before anything is enqueued).
  void begin_frame(const DeviceFrame& in, const DeviceTarget& out) {
    for_each_device_channel(in, [&](const char* name, const DeviceImageView& v, int, bool) {
      if (!v.empty()) check_device_memory(v.data, in.index, std::string("channel '") + name + "'");
    });
    check_device_memory(out.image.data, in.index, "the output");
    engine_.begin_frame(static_cast<cudaStream_t>(out.stream));
  }

  // Uploads the frame: its planes copied into pinned memory on the host's cores (HostStaging),
  // then one DMA transfer, timed as the engine's upload stage.
  // `position`: the method reads world positions, uploaded into a buffer of their own (made on
  // the first request), so the methods that do not read them do not pay for them. `split`:
  // direct and indirect (the frame carries both), likewise in a buffer of their own.
  // `gradient_into`: the method reads A-SVGF's gradient samples, uploaded (when the frame has
  // them) into the 3 planes it lends there (memory it does not use until its gradient stage
  // has read them: no planes of the backend's own); null: not wanted. `normals_into`: the 3
  // planes the frame's normals go to where the method keeps the previous guides itself
  // (keep_previous_mesh_ids_only; required there, null otherwise); `motion_into` likewise, the
  // 2 planes of its motion (keep_motion_in_lent_planes).
  FrameInputs inputs(const Frame& in, bool position = false, bool split = false,
                     float* gradient_into = nullptr, bool defer_sanitize = false,
                     float* normals_into = nullptr, float* motion_into = nullptr) {
    lend_normals(normals_into);
    lend_motion(motion_into);
    const size_t n = pixels();
    float* staging = staging_in_.get();
    auto stage = [&](const float* src, int plane) {
      host_copies_.add(staging + plane * n, src, n * sizeof(float));
    };
    for (int c = 0; c < 3; ++c) {
      stage(in.color.plane(c), kColor + c);
      stage(in.albedo.plane(c), kAlbedo + c);
      stage(in.normal.plane(c), kNormal + c);
    }
    stage(in.depth.plane(0), kDepth);
    stage(in.depth_gradient.plane(0), kDepthDx);
    stage(in.depth_gradient.plane(1), kDepthDy);
    stage(in.motion.plane(0), kMotionX);
    stage(in.motion.plane(1), kMotionY);
    host_copies_.add(staging + kMeshId * n, in.mesh_id.data(), n * sizeof(uint32_t));
    const bool emission = !in.emission.empty();
    if (emission)
      for (int c = 0; c < 3; ++c) stage(in.emission.plane(c), kEmission + c);
    const bool gradient = gradient_into != nullptr && !in.gradient.empty();
    if (gradient)
      for (int c = 0; c < 3; ++c) stage(in.gradient.plane(c), kGradient + c);
    // The optional emission comes last in the shading buffer: the upload stops after the last
    // plane the frame has.
    const int planes = emission ? kGradient : kRequiredPlanes;
    if (position) {
      ensure_position();
      staging_position_.resize(3 * n, "the pinned position staging buffer");
      host_copies_.add(staging_position_.get(), in.position.plane(0), 3 * n * sizeof(float));
    }
    if (split) {
      ensure_split();
      staging_split_.resize(6 * n, "the pinned direct and indirect staging buffer");
      host_copies_.add(staging_split_.get(), in.direct.plane(0), 3 * n * sizeof(float));
      host_copies_.add(staging_split_.get() + 3 * n, in.indirect.plane(0), 3 * n * sizeof(float));
    }
    host_copies_.run();
    engine_.mark(kUploadStage);
    // The guides the next frame reads go to this frame's slot (the mesh ids alone, and the
    // depth and normals to their planes, where the method keeps the rest), the rest to the one
    // shading buffer, the gradient samples to the planes the method lent (transfers from one
    // staging buffer).
    if (mesh_ids_only_) {
      upload(input_plane(kDepth), staging + kDepth * n, n, "upload of the depth");
      upload(input_plane(kNormal), staging + kNormal * n, 3 * n, "upload of the normals");
      upload(input_plane(kMeshId), staging + kMeshId * n, n, "upload of the mesh ids");
    } else {
      guides_[slot_].upload_async(staging, kKeptPlanes * n, engine_.stream());
    }
    if (motion_lent_) {
      upload(input_plane(kDepthDx), staging + kDepthDx * n, 2 * n, "upload of the depth gradient");
      upload(input_plane(kMotionX), staging + kMotionX * n, 2 * n, "upload of the motion");
      upload(input_plane(kColor), staging + kColor * n, (planes - kColor) * n,
             "upload of the frame's shading inputs");
    } else {
      shading_.upload_async(staging + kKeptPlanes * n, (planes - kKeptPlanes) * n,
                            engine_.stream());
    }
    if (gradient)
      upload(gradient_into, staging + kGradient * n, 3 * n, "upload of the gradient samples");
    if (position) position_.upload_async(staging_position_.get(), 3 * n, engine_.stream());
    if (split) split_.upload_async(staging_split_.get(), 6 * n, engine_.stream());
    return landed_inputs(emission, gradient ? gradient_into : nullptr, position, split,
                         defer_sanitize);
  }

  // The device path: every channel of the caller's frame copied into the same planes as an
  // upload's, in one launch on the caller's stream (timed as copy_in); the caller's buffers
  // are only read.
  FrameInputs inputs(const DeviceFrame& in, bool position = false, bool split = false,
                     float* gradient_into = nullptr, bool defer_sanitize = false,
                     float* normals_into = nullptr, float* motion_into = nullptr) {
    lend_normals(normals_into);
    lend_motion(motion_into);
    if (position) ensure_position();
    if (split) ensure_split();
    StridedCopy copy;
    // Channel c of view v goes to plane_of(c).
    auto add = [&](const DeviceImageView& v, int channels, auto plane_of) {
      for (int c = 0; c < channels; ++c)
        copy.add(StridedCopy::from_view(v, c, plane_of(c), width_));
    };
    auto input = [this](int first) {
      return [this, first](int c) { return input_plane(first + c); };
    };
    add(in.depth, 1, input(kDepth));
    add(in.depth_gradient, 2, input(kDepthDx));
    add(in.normal, 3, input(kNormal));
    add(in.motion, 2, input(kMotionX));
    add(in.mesh_id, 1, input(kMeshId));
    add(in.color, 3, input(kColor));
    add(in.albedo, 3, input(kAlbedo));
    const bool emission = !in.emission.empty();
    if (emission) add(in.emission, 3, input(kEmission));
    const bool gradient = gradient_into != nullptr && !in.gradient.empty();
    const size_t n = pixels();
    if (gradient) add(in.gradient, 3, [gradient_into, n](int c) { return gradient_into + c * n; });
    if (position) add(in.position, 3, [this](int c) { return plane(position_, c); });
    if (split) {
      add(in.direct, 3, [this](int c) { return plane(split_, c); });
      add(in.indirect, 3, [this](int c) { return plane(split_, 3 + c); });
    }
    engine_.run(kCopyInStage, copy, width_, height_);
    return landed_inputs(emission, gradient ? gradient_into : nullptr, position, split,
                         defer_sanitize);
  }

  // The previous frame's depth, normal and mesh id: what the methods read of it (SVGF's
  // reprojection, the JBF's temporal pass). Its depth gradient and motion are not kept (null),
  // nor its depth and normal where the method keeps them (keep_previous_mesh_ids_only).
  GuideView previous_guides() const {
    GuideView g;
    g.width = width_;
    g.height = height_;
    const Buffer& prev = guides_[1 - slot_];
    if (!mesh_ids_only_) {
      g.depth = plane(prev, kDepth);
      g.normal = rgb(prev, kNormal);
    }
    g.mesh_id = reinterpret_cast<const uint32_t*>(plane(prev, mesh_ids_only_ ? 0 : kMeshId));
    return g;
  }
  RgbView output(Image&) { return output_view(); }
  RgbView output(const DeviceTarget&) { return output_view(); }

  // Downloads the output and waits for the frame (raising any fault of its kernels).
  void finish(const Frame&, Image& out) {
    const size_t n = pixels();
    engine_.mark(kDownloadStage);
    SVGF_CUDA_CHECK(cudaMemcpyAsync(staging_out_.get(), output_plane(0), 3 * n * sizeof(float),
                                    cudaMemcpyDeviceToHost, engine_.stream()),
                    "download of the output");
    engine_.end_frame();
    out.ensure_shape(width_, height_, 3);  // overwritten whole by the copy below
    host_copies_.add(out.data().data(), staging_out_.get(), 3 * n * sizeof(float));
    host_copies_.run();
    slot_ = 1 - slot_;
  }
  // The device path: the output copied into the caller's (timed as copy_out), and the frame's
  // end recorded on the caller's stream; nothing waits (the report is read when asked for).
  void finish(const DeviceFrame&, const DeviceTarget& out) {
    StridedCopy copy;
    for (int c = 0; c < 3; ++c)
      copy.add(StridedCopy::to_view(output_plane(c), width_, out.image, c));
    engine_.run(kCopyOutStage, copy, width_, height_);
    engine_.end_frame_async();
    slot_ = 1 - slot_;
  }

 private:
  // Where this frame's normals (keep_previous_mesh_ids_only) and motion
  // (keep_motion_in_lent_planes) go: planes the method must lend where it asked for it, none
  // otherwise.
  void lend_normals(float* planes) { lent_normals_ = lent(planes, mesh_ids_only_, "normals"); }
  void lend_motion(float* planes) { lent_motion_ = lent(planes, motion_lent_, "motion"); }
  static float* lent(float* planes, bool asked, const char* what) {
    if (asked != (planes != nullptr))
      throw std::logic_error(std::string("cuda backend: ") +
                             (asked ? "the method must lend the planes for the frame's "
                                    : "planes lent for the frame's ") +
                             what + (asked ? "" : ", which the backend keeps itself"));
    return planes;
  }
  // shading_'s planes: the depth gradient to the emission, but for a lent motion.
  int shading_planes() const { return kShadingPlanes - (motion_lent_ ? 2 : 0); }
  void upload(float* device, const float* host, size_t floats, const char* what) {
    SVGF_CUDA_CHECK(cudaMemcpyAsync(device, host, floats * sizeof(float), cudaMemcpyHostToDevice,
                                    engine_.stream()),
                    what);
  }

  // The buffers of the optional inputs, made on the first frame that asks for them.
  void ensure_position() {
    if (position_.size() != 3 * pixels()) allocate(position_, 3, "world positions");
  }
  void ensure_split() {
    if (split_.size() != 6 * pixels()) allocate(split_, 6, "direct and indirect");
  }

  // The frame's inputs in the backend's planes, sanitized: what both paths hand the method.
  // `gradient`: where the gradient samples landed (null: none). `defer`: the sanitize stage is
  // left to the method (FrameInputs::sanitize_pending).
  FrameInputs landed_inputs(bool emission, const float* gradient, bool position, bool split,
                            bool defer) {
    FrameInputs f;
    f.guides = current_guides();
    f.color = input_rgb(kColor);
    f.albedo = input_rgb(kAlbedo);
    if (emission) f.emission = input_rgb(kEmission);
    if (position) f.position = rgb(position_, 0);
    if (gradient) {
      f.gradient.previous = gradient;
      f.gradient.current = gradient + pixels();
      f.gradient.mask = gradient + 2 * pixels();
    }
    if (split) {
      f.direct = rgb(split_, 0);
      f.indirect = rgb(split_, 3);
    }
    f.sanitize = sanitize_kernel(f, emission, position, split);
    f.sanitize_pending = defer;
    if (!defer) engine_.run_tallying(kSanitizeStage, f.sanitize, width_, height_);
    return f;
  }

  // std::invalid_argument unless `p` is device (or managed) memory of this denoiser's device:
  // a host address would fault inside a kernel, long after the call returned.
  void check_device_memory(const void* p, int frame, const std::string& what) const {
    cudaPointerAttributes a{};
    const cudaError_t e = cudaPointerGetAttributes(&a, p);
    if (e != cudaSuccess) (void)cudaGetLastError();
    const bool device = e == cudaSuccess && (a.type == cudaMemoryTypeDevice ||
                                             a.type == cudaMemoryTypeManaged);
    const std::string where = "frame " + std::to_string(frame) + " (device): " + what;
    if (!device)
      throw std::invalid_argument(where + " is not device memory (" +
                                  (e != cudaSuccess ? std::string(cudaGetErrorString(e))
                                   : a.type == cudaMemoryTypeHost ? "pinned host memory"
                                                                  : "host memory") +
                                  "); the host path is denoise()");
    if (a.type == cudaMemoryTypeDevice && a.device != device_)
      throw std::invalid_argument(where + " is memory of CUDA device " + std::to_string(a.device) +
                                  ", this denoiser runs on device " + std::to_string(device_));
  }

  // The sanitize stage (core/sanitize.h), in place on the uploaded planes: a clean pixel is
  // only read.
  SanitizeInputs sanitize_kernel(const FrameInputs& f, bool emission, bool position,
                                 bool split) {
    InputPlanesOut out;
    out.color = input_rgb(kColor);
    out.albedo = input_rgb(kAlbedo);
    if (emission) out.emission = input_rgb(kEmission);
    out.normal = input_rgb(kNormal);
    if (position) out.position = rgb(position_, 0);
    if (split) {
      out.direct = rgb(split_, 0);
      out.indirect = rgb(split_, 3);
    }
    out.depth = input_plane(kDepth);
    out.depth_dx = input_plane(kDepthDx);
    out.depth_dy = input_plane(kDepthDy);
    out.motion_x = input_plane(kMotionX);
    out.motion_y = input_plane(kMotionY);
    InputPlanes in;
    in.color = f.color;
    in.albedo = f.albedo;
    in.emission = f.emission;
    in.normal = out.normal;
    in.position = f.position;
    in.direct = f.direct;
    in.indirect = f.indirect;
    in.depth = out.depth;
    in.depth_dx = out.depth_dx;
    in.depth_dy = out.depth_dy;
    in.motion_x = out.motion_x;
    in.motion_y = out.motion_y;
    return SanitizeInputs{width_, in, out};
  }

  // Planes of one frame's upload, in order; mesh_id travels as raw 32-bit words. The guides
  // the next frame reads come first (planes 0 to 4, the slot of guides_ that is this frame's:
  // previous_guides()); the optional emission and gradient samples come last, so a frame
  // without them uploads kRequiredPlanes only. The gradient samples are staged here but land
  // in the planes the method lends (inputs()' gradient_into), not in shading_.
  enum InputPlane : int {
    kDepth = 0,
    kNormal = 1,    // 3
    kMeshId = 4,
    kKeptPlanes = 5,
    kDepthDx = 5,   // from here on in shading_, at plane - kKeptPlanes (input_plane)
    kDepthDy = 6,
    kMotionX = 7,
    kMotionY = 8,
    kColor = 9,     // 3
    kAlbedo = 12,   // 3
    kRequiredPlanes = 15,
    kEmission = 15,  // 3, optional
    kGradient = 18,  // 3, optional: A-SVGF's previous, current luminance and mask
    kInputPlanes = 21,
    kShadingPlanes = kGradient - kKeptPlanes  // shading_: depth gradient to emission
  };

  static LaunchShape checked_shape(const EngineConfig& config) {
    const LaunchShape s{config.block_x, config.block_y};
    if (s.block_x < 1 || s.block_y < 1)
      throw std::invalid_argument("CUDA block shape " + std::to_string(s.block_x) + "x" +
                                  std::to_string(s.block_y) + " is empty");
    int device = 0, max_threads = 0;
    SVGF_CUDA_CHECK(cudaGetDevice(&device), "cudaGetDevice");
    SVGF_CUDA_CHECK(cudaDeviceGetAttribute(&max_threads, cudaDevAttrMaxThreadsPerBlock, device),
                    "cudaDeviceGetAttribute");
    if (static_cast<long long>(s.block_x) * s.block_y > max_threads)
      throw std::invalid_argument("CUDA block shape " + std::to_string(s.block_x) + "x" +
                                  std::to_string(s.block_y) + " has more than the device's " +
                                  std::to_string(max_threads) + " threads per block");
    return s;
  }


  // This frame's guides, from its slot and the shading buffer.
  GuideView current_guides() const {
    GuideView g;
    g.width = width_;
    g.height = height_;
    g.depth = input_plane(kDepth);
    g.depth_dx = input_plane(kDepthDx);
    g.depth_dy = input_plane(kDepthDy);
    g.normal = input_rgb(kNormal);
    g.mesh_id = reinterpret_cast<const uint32_t*>(input_plane(kMeshId));
    g.motion_x = input_plane(kMotionX);
    g.motion_y = input_plane(kMotionY);
    return g;
  }
  // The output's planes: the input color's (set_output_over_color; three neighbouring planes
  // of shading_, so the host path downloads them in one copy) or the backend's own.
  static_assert(kColor >= kKeptPlanes, "the color's planes lie in shading_, one after another");
  float* output_plane(int c) const {
    return output_over_color_ ? input_plane(kColor + c) : plane(output_, c);
  }
  RgbView output_view() const { return {output_plane(0), output_plane(1), output_plane(2)}; }
  // An input plane of this frame, in whichever buffer holds it.
  float* input_plane(int p) const {
    if (p >= kKeptPlanes) {
      if (!motion_lent_ || p < kMotionX) return plane(shading_, p - kKeptPlanes);
      if (p <= kMotionY) return lent_motion_ + static_cast<size_t>(p - kMotionX) * pixels();
      return plane(shading_, p - kKeptPlanes - 2);
    }
    if (!mesh_ids_only_) return plane(guides_[slot_], p);
    if (p == kMeshId) return plane(guides_[slot_], 0);
    if (p == kDepth) return plane(depth_, 0);
    return lent_normals_ + static_cast<size_t>(p - kNormal) * pixels();
  }
  RgbView input_rgb(int p) const { return {input_plane(p), input_plane(p + 1), input_plane(p + 2)}; }

  Mode mode_;
  int device_ = 0;
  CudaEngine engine_;
  int width_ = 0, height_ = 0;
  int slot_ = 0;  // input slot the next frame is uploaded into
  int method_planes_ = 0;
  bool output_over_color_ = false;  // set_output_over_color
  bool mesh_ids_only_ = false;      // keep_previous_mesh_ids_only
  float* lent_normals_ = nullptr;   // this frame's normals there (inputs()' normals_into)
  bool motion_lent_ = false;        // keep_motion_in_lent_planes
  float* lent_motion_ = nullptr;    // this frame's motion there (inputs()' motion_into)
  // The depth, normal and mesh id of this frame and the previous one (the methods read those
  // of the previous frame through previous_guides(), nothing else of it), and this frame's
  // other inputs once but for the gradient samples (in the method's lent planes): 2 x 5 + 13
  // planes instead of 2 x 21 (docs/benchmarks.md, "Where the 618 MiB go").
  // (keep_previous_mesh_ids_only: the slots hold the mesh ids, depth_ the frame's depth.)
  Buffer guides_[2], depth_, shading_, output_, position_, split_;
  PinnedBuffer<float> staging_in_, staging_out_, staging_position_, staging_split_;
  HostStaging host_copies_;
};

}  // namespace svgf::cuda

// SVGF on the GPU behind the Denoiser interface. The structure mirrors kernels_cpu/svgf_cpu.cpp:
// history slots ping-pong, the same size rules and debug buffers. Differences: the frame's
// inputs travel in one pinned upload, and the previous frame's guides need no copy (the two
// input slots alternate, so last frame's upload is this frame's prev_guides).
#include "kernels_cuda/svgf_cuda.h"

#include <cstring>
#include <stdexcept>
#include <string>

#include "core/svgf_pipeline.h"
#include "kernels_cuda/cuda_engine.h"
#include "kernels_cuda/cuda_handles.h"
#include "kernels_cuda/device_array.h"
#include "kernels_cuda/svgf_fast.h"

namespace svgf::cuda {
namespace {

// Planes of one frame's upload, in order; mesh_id travels as raw 32-bit words. The optional
// emission comes last, so a frame without it uploads kRequiredPlanes only.
enum InputPlane : int {
  kColor = 0,     // 3
  kAlbedo = 3,    // 3
  kNormal = 6,    // 3
  kDepth = 9,
  kDepthDx = 10,
  kDepthDy = 11,
  kMotionX = 12,
  kMotionY = 13,
  kMeshId = 14,
  kRequiredPlanes = 15,
  kEmission = 15,  // 3, optional
  kInputPlanes = 18
};

class SvgfCudaDenoiser final : public Denoiser {
 public:
  explicit SvgfCudaDenoiser(const DenoiserConfig& config)
      : mode_(config.mode), params_(config.svgf), engine_(checked_shape(config)) {
    SVGF_CUDA_CHECK(cudaGetDevice(&device_), "cudaGetDevice");
  }

  void denoise(const Frame& in, Image& out) override {
    check_frame_consistent(in);
    SVGF_CUDA_CHECK(cudaSetDevice(device_), "cudaSetDevice");
    ensure_size(in.width(), in.height());
    const size_t n = pixels();
    engine_.begin_frame();

    // Upload: copy the frame's planes into pinned memory, then one DMA transfer.
    const int cur = input_slot_;
    float* staging = staging_in_.get();
    auto stage = [&](const float* src, int plane) {
      std::memcpy(staging + plane * n, src, n * sizeof(float));
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
    std::memcpy(staging + kMeshId * n, in.mesh_id.data(), n * sizeof(uint32_t));
    const bool emission = !in.emission.empty();
    if (emission)
      for (int c = 0; c < 3; ++c) stage(in.emission.plane(c), kEmission + c);
    engine_.mark(Stage::Upload, "upload");
    inputs_[cur].upload_async(staging, (emission ? kInputPlanes : kRequiredPlanes) * n,
                              engine_.stream());

    const int prev = slot_;
    const int next = 1 - slot_;
    SvgfFrameBuffers b;
    b.guides = guides(cur);
    b.prev_guides = guides(1 - cur);
    b.color = rgb(inputs_[cur], kColor);
    b.albedo = rgb(inputs_[cur], kAlbedo);
    if (emission) b.emission = rgb(inputs_[cur], kEmission);
    b.prev_color = rgb(color_history_[prev], 0);
    b.prev_moment1 = moments_[prev].get();
    b.prev_moment2 = moments_[prev].get() + n;
    b.prev_history = history_[prev].get();
    b.next_color = rgb(color_history_[next], 0);
    b.next_moment1 = moments_[next].get();
    b.next_moment2 = moments_[next].get() + n;
    b.next_history = history_[next].get();
    b.illumination = rgb(illumination_, 0);
    b.accumulated = {rgb(accumulated_, 0), accumulated_.get() + 3 * n};
    b.filtered[0] = {rgb(filtered_[0], 0), filtered_[0].get() + 3 * n};
    b.filtered[1] = {rgb(filtered_[1], 0), filtered_[1].get() + 3 * n};
    b.output = rgb(output_, 0);
    if (mode_ == Mode::Exact) {
      run_svgf_frame(engine_, b, params_, has_history_);
    } else {
      // Fast mode reuses the a-trous ping-pong buffers as packed float4 planes (same size).
      fast::FastBuffers f;
      f.packed[0] = filtered_[0].get();
      f.packed[1] = filtered_[1].get();
      f.guides = packed_guides_.get();
      fast::run_frame(engine_, b, f, params_, has_history_);
    }

    engine_.mark(Stage::Download, "download");
    output_.download_async(staging_out_.get(), 3 * n, engine_.stream());
    engine_.end_frame();  // waits; raises any fault of this frame's kernels
    out.ensure_shape(width_, height_, 3);  // overwritten whole by the copy below
    std::memcpy(out.data().data(), staging_out_.get(), 3 * n * sizeof(float));

    input_slot_ = 1 - cur;
    slot_ = next;
    has_history_ = true;
    report_.times = engine_.times();
    report_.replaced_samples = engine_.counted();
  }

  void reset() override { has_history_ = false; }
  const FrameReport& last_report() const override { return report_; }

  std::string description() const override {
    cudaDeviceProp prop{};
    const bool named = cudaGetDeviceProperties(&prop, device_) == cudaSuccess;
    if (!named) (void)cudaGetLastError();
    const LaunchShape s = engine_.shape();
    return std::string("svgf cuda ") + to_string(mode_) + ", " +
           (named ? std::string(prop.name) : "device " + std::to_string(device_)) + ", block " +
           std::to_string(s.block_x) + "x" + std::to_string(s.block_y);
  }

  Image read_buffer(DebugBuffer which) const override {
    if (width_ == 0) return Image();
    SVGF_CUDA_CHECK(cudaSetDevice(device_), "cudaSetDevice");
    SVGF_CUDA_CHECK(cudaStreamSynchronize(engine_.stream()), "read_buffer: cudaStreamSynchronize");
    switch (which) {
      case DebugBuffer::Illumination: return download(illumination_, 3);
      case DebugBuffer::Accumulated: return download(accumulated_, 4);
      case DebugBuffer::Moments: return download(moments_[slot_], 2);
      case DebugBuffer::HistoryLength: return download(history_[slot_], 1);
      case DebugBuffer::ColorHistory: return download(color_history_[slot_], 3);
    }
    throw std::invalid_argument("read_buffer: unknown buffer");
  }

 private:
  static LaunchShape checked_shape(const DenoiserConfig& config) {
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

  size_t pixels() const { return static_cast<size_t>(width_) * static_cast<size_t>(height_); }

  RgbView rgb(const DeviceArray<float>& a, int first_plane) const {
    float* base = a.get() + static_cast<size_t>(first_plane) * pixels();
    return {base, base + pixels(), base + 2 * pixels()};
  }

  GuideView guides(int slot) const {
    const size_t n = pixels();
    float* base = inputs_[slot].get();
    GuideView g;
    g.width = width_;
    g.height = height_;
    g.depth = base + kDepth * n;
    g.depth_dx = base + kDepthDx * n;
    g.depth_dy = base + kDepthDy * n;
    g.normal = rgb(inputs_[slot], kNormal);
    g.mesh_id = reinterpret_cast<const uint32_t*>(base + kMeshId * n);
    g.motion_x = base + kMotionX * n;
    g.motion_y = base + kMotionY * n;
    return g;
  }

  Image download(const DeviceArray<float>& a, int channels) const {
    Image im(width_, height_, channels);
    a.download(im.data().data(), im.data().size());
    return im;
  }

  void ensure_size(int w, int h) {
    if (w == width_ && h == height_) return;
    check_frame_size_unchanged(width_, height_, w, h);
    const size_t n = static_cast<size_t>(w) * static_cast<size_t>(h);
    // Every allocation's error names the buffer and what the whole frame size needs.
    const std::string need = " (" + std::to_string(w) + "x" + std::to_string(h) +
                             " frames need about " +
                             std::to_string((bytes_per_pixel() * n + (1u << 20) - 1) >> 20) +
                             " MiB of device memory in all)";
    auto named = [&](const char* what) { return (what + need); };
    try {
      for (int s = 0; s < 2; ++s) {
        inputs_[s].resize(kInputPlanes * n, named("frame inputs").c_str());
        color_history_[s].resize(3 * n, named("color history").c_str());
        moments_[s].resize(2 * n, named("moments").c_str());
        history_[s].resize(n, named("history length").c_str());
        filtered_[s].resize(4 * n, named("a-trous buffers").c_str());
      }
      illumination_.resize(3 * n, named("illumination").c_str());
      accumulated_.resize(4 * n, named("accumulation").c_str());
      output_.resize(3 * n, named("output").c_str());
      if (mode_ == Mode::Fast) packed_guides_.resize(4 * n, named("packed guides").c_str());
      staging_in_.resize(kInputPlanes * n, "the pinned input staging buffer");
      staging_out_.resize(3 * n, "the pinned output staging buffer");
    } catch (...) {
      release_buffers();  // nothing half-made stays; a later frame may try again
      throw;
    }
    width_ = w;
    height_ = h;
    has_history_ = false;
  }

  size_t bytes_per_pixel() const {
    const size_t floats = 2 * (kInputPlanes + 3 + 2 + 1 + 4) + 3 + 4 + 3 +
                          (mode_ == Mode::Fast ? 4 : 0);
    return floats * sizeof(float);
  }

  void release_buffers() {
    for (int s = 0; s < 2; ++s) {
      inputs_[s].resize(0);
      color_history_[s].resize(0);
      moments_[s].resize(0);
      history_[s].resize(0);
      filtered_[s].resize(0);
    }
    illumination_.resize(0);
    accumulated_.resize(0);
    output_.resize(0);
    packed_guides_.resize(0);
    staging_in_.resize(0, "");
    staging_out_.resize(0, "");
  }

  Mode mode_;
  SvgfParams params_;
  int device_ = 0;
  CudaEngine engine_;
  int width_ = 0, height_ = 0;
  int slot_ = 0;        // history slot the next frame reads
  int input_slot_ = 0;  // input slot the next frame is uploaded into
  bool has_history_ = false;
  DeviceArray<float> inputs_[2];
  DeviceArray<float> color_history_[2], moments_[2], history_[2];
  DeviceArray<float> illumination_, accumulated_, filtered_[2], output_, packed_guides_;
  PinnedBuffer<float> staging_in_, staging_out_;
  FrameReport report_;
};

}  // namespace

std::unique_ptr<Denoiser> make_svgf_denoiser(const DenoiserConfig& config) {
  std::string why;
  if (!device_available(&why)) throw std::runtime_error("backend cuda: " + why);
  return std::make_unique<SvgfCudaDenoiser>(config);
}

}  // namespace svgf::cuda

#pragma once
// The one interface every method and backend sits behind (docs/architecture.md). Method-neutral:
// a method names its own stages and debug buffers; pipeline/make_denoiser.h picks the method.
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "core/device_frame.h"
#include "core/frame.h"
#include "core/image.h"
#include "core/sanitize.h"
#include "core/stage_times.h"
#include "core/tallies.h"

namespace svgf {

enum class Backend { Cpu, Cuda, Auto };  // Auto: CUDA when a device is present, else CPU
enum class Mode { Exact, Fast };         // Fast exists on CUDA only

const char* to_string(Backend b);
const char* to_string(Mode m);
// Parse "cpu|cuda|auto", "exact|fast"; throw std::invalid_argument naming the value.
Backend parse_backend(const std::string& s);
Mode parse_mode(const std::string& s);

// Where and how a method runs: the same for every method.
struct EngineConfig {
  Backend backend = Backend::Cpu;
  Mode mode = Mode::Exact;
  int threads = 0;   // CPU worker threads; 0: all cores
  int block_x = 32;  // CUDA block shape (any shape gives the same bits; kernels_cuda/launch_shape.h)
  int block_y = 8;
  // The CPU kernels' instruction-set variant (kernels_cpu/cpu_variant.h): "auto" (the widest
  // this CPU runs), "v2", "v3", "v4"; empty: the environment variable SVGF_CPU_ISA, else auto.
  std::string cpu_isa;
  // Keep a method's frame scratch in buffers of its own, so that read_buffer() can return it
  // after the frame (SVGF: the illumination and the accumulation). Off, a method may place
  // that scratch in memory a later stage of the same frame overwrites (SVGF: its a-trous
  // buffers, 4 planes of the frame's size less, 5 with A-SVGF's stratum image) and
  // debug_buffers() leaves it out, and may overwrite a history in place where the frame reads
  // it all before it writes the next (SVGF: the color history, 3 planes less).
  // The output and every other buffer are the same bits either way.
  bool keep_scratch = false;
};

// Pixels of one frame whose inputs the sanitize stage repaired, per kind (core/sanitize.h has
// the rule for each).
struct InputRepairs {
  int64_t color = 0;     // a component NaN, Inf, negative or > kMaxRadiance: set to 0
  int64_t albedo = 0;    // outside [0, 1]: clamped (NaN: 1)
  int64_t emission = 0;  // as color
  int64_t normal = 0;    // a surface normal of the wrong length: renormalized
  int64_t surface = 0;   // bad depth, gradient, normal or position: made background
  int64_t motion = 0;    // non-finite or huge: clamped off the image (no history)

  static InputRepairs from(const Tallies& t) {
    InputRepairs r;
    r.color = t.count[tally_bit(kRepairColor)];
    r.albedo = t.count[tally_bit(kRepairAlbedo)];
    r.emission = t.count[tally_bit(kRepairEmission)];
    r.normal = t.count[tally_bit(kRepairNormal)];
    r.surface = t.count[tally_bit(kRepairSurface)];
    r.motion = t.count[tally_bit(kRepairMotion)];
    return r;
  }
  int64_t total() const { return color + albedo + emission + normal + surface + motion; }
  InputRepairs& operator+=(const InputRepairs& o) {
    color += o.color; albedo += o.albedo; emission += o.emission;
    normal += o.normal; surface += o.surface; motion += o.motion;
    return *this;
  }
};

// What one denoise() call did.
struct FrameReport {
  StageTimes times;
  InputRepairs repairs;
  int64_t replaced_samples = 0;  // pixels whose color was replaced (repairs.color)
  // Pixels whose filter fell back (kTallyFilterFallback; BMFR: a block with nothing to fit, the
  // pixel kept its accumulated color). 0 for methods without such a case.
  int64_t fallback_pixels = 0;
};

// The report of the frame an engine has just finished (after the backend's finish()).
template <class Engine>
FrameReport frame_report(const Engine& engine) {
  FrameReport r;
  r.times = engine.times();
  r.repairs = InputRepairs::from(engine.tallies());
  r.replaced_samples = r.repairs.color;
  r.fallback_pixels = engine.tallies().count[tally_bit(kTallyFilterFallback)];
  return r;
}

// The report of a denoiser's last frame. A frame on the host path is read at once; a device
// frame (denoise_device) has not finished when the call returns, so its report is read from the
// engine when first asked for, which waits for that frame's work. A frame that failed leaves
// an empty report.
class LastReport {
 public:
  void frame_started() {
    report_ = FrameReport{};
    unread_ = false;
  }
  template <class Engine>
  void frame_done(const Engine& engine) {
    unread_ = engine.frame_pending();
    if (!unread_) report_ = frame_report(engine);
  }
  template <class Engine>
  const FrameReport& of(const Engine& engine) const {
    if (unread_) {
      report_ = frame_report(engine);
      unread_ = false;
    }
    return report_;
  }

 private:
  mutable FrameReport report_;
  mutable bool unread_ = false;
};

// One denoiser per sequence: it owns the history. Frames must all have the first frame's size.
// Not thread-safe: one thread at a time calls it.
class Denoiser {
 public:
  virtual ~Denoiser() = default;
  // Denoises `in` into `out` (resized to width x height x 3, linear HDR).
  virtual void denoise(const Frame& in, Image& out) = 0;
  // The device path (docs/api.md, "Frames on the GPU"): denoises a frame whose buffers live in
  // GPU memory into `out`, on the caller's CUDA stream `cuda_stream` (a cudaStream_t; nullptr:
  // the legacy default stream), with the same bits as denoise() on the same values. Returns
  // once the frame's work is enqueued: no host round trip, no synchronization. The frame's
  // buffers are read, and `out` written, in stream order: reuse them after work enqueued later
  // on that stream. Bad layouts and host addresses are std::invalid_argument before anything is
  // enqueued; last_report() waits for the frame (its event, not the stream) and raises any
  // fault of its kernels. Host and device frames may alternate on one denoiser. A CPU
  // denoiser throws std::logic_error.
  virtual void denoise_device(const DeviceFrame& in, const DeviceOutputView& out,
                              void* cuda_stream) = 0;
  // Forget the history (camera cut); the next frame starts afresh.
  virtual void reset() = 0;
  virtual const FrameReport& last_report() const = 0;
  // E.g. "svgf cpu exact, 2 threads" or "svgf cuda fast, NVIDIA H100 80GB HBM3".
  virtual std::string description() const = 0;
  // The method's stages, in the order a frame runs them (names used in last_report().times).
  virtual std::vector<std::string> stages() const = 0;
  // Internal buffers a caller may read back by name, for tests and tools.
  virtual std::vector<std::string> debug_buffers() const = 0;
  // Empty before the first frame; std::invalid_argument for a name not in debug_buffers().
  virtual Image read_buffer(std::string_view name) const = 0;
};

// Every backend's rule for a sequence: all frames have the first frame's size. A denoiser that
// has seen a width x height frame (0 x 0: none yet) throws std::invalid_argument for another.
inline void check_frame_size_unchanged(int width, int height, int w, int h) {
  if (width == 0 || (w == width && h == height)) return;
  throw std::invalid_argument("frame size changed mid-sequence from " + std::to_string(width) +
                              "x" + std::to_string(height) + " to " + std::to_string(w) + "x" +
                              std::to_string(h) + " (use a new denoiser for a new sequence)");
}

// What a denoiser whose backend cannot read device memory throws from denoise_device.
inline std::logic_error device_frames_unsupported(const std::string& description) {
  return std::logic_error("denoise_device: '" + description +
                          "' runs on the CPU; frames in GPU memory need a CUDA denoiser "
                          "(Backend::Cuda)");
}

// Both paths' input checks, before anything is written (a method's denoise_frame calls the one
// its source needs).
inline void check_frame(const Frame& f, const Image&) { check_frame_consistent(f); }
inline void check_frame(const DeviceFrame& f, const DeviceTarget& out) {
  check_device_frame(f, out.image);
}

// A method's two entry points, written once: Derived (the method's denoiser over Backend) has
//   template <class Source, class Target> void denoise_frame(const Source&, Target&);
// over Frame / Image, and over DeviceFrame / DeviceTarget where Backend::kDeviceFrames; a
// backend without device frames refuses them (device_frames_unsupported).
template <class Derived, class Backend>
class DenoiserOver : public Denoiser {
 public:
  void denoise(const Frame& in, Image& out) final { self().denoise_frame(in, out); }
  void denoise_device(const DeviceFrame& in, const DeviceOutputView& out,
                      void* cuda_stream) final {
    if constexpr (Backend::kDeviceFrames) {
      DeviceTarget target{out, cuda_stream};
      self().denoise_frame(in, target);
    } else {
      throw device_frames_unsupported(description());
    }
  }

 private:
  Derived& self() { return static_cast<Derived&>(*this); }
};

inline std::invalid_argument unknown_buffer(std::string_view method, std::string_view name,
                                            const std::vector<std::string>& known) {
  std::string list;
  for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
  return std::invalid_argument(std::string(method) + ": no debug buffer '" + std::string(name) +
                               "' (known: " + list + ")");
}

}  // namespace svgf

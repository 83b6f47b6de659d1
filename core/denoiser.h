#pragma once
// The one interface every method and backend sits behind (docs/architecture.md). Method-neutral:
// a method names its own stages and debug buffers; pipeline/make_denoiser.h picks the method.
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "core/frame.h"
#include "core/image.h"
#include "core/stage_times.h"

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
};

// What one denoise() call did.
struct FrameReport {
  StageTimes times;
  int64_t replaced_samples = 0;  // color samples that were NaN, Inf or negative (set to 0)
};

// One denoiser per sequence: it owns the history. Frames must all have the first frame's size.
class Denoiser {
 public:
  virtual ~Denoiser() = default;
  // Denoises `in` into `out` (resized to width x height x 3, linear HDR).
  virtual void denoise(const Frame& in, Image& out) = 0;
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

inline std::invalid_argument unknown_buffer(std::string_view method, std::string_view name,
                                            const std::vector<std::string>& known) {
  std::string list;
  for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
  return std::invalid_argument(std::string(method) + ": no debug buffer '" + std::string(name) +
                               "' (known: " + list + ")");
}

}  // namespace svgf

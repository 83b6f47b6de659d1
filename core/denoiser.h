#pragma once
// The one interface every method and backend sits behind (docs/architecture.md).
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>

#include "core/frame.h"
#include "core/image.h"
#include "core/params.h"
#include "core/stage_times.h"

namespace svgf {

enum class Method { Svgf };
enum class Backend { Cpu, Cuda, Auto };  // Auto: CUDA when a device is present, else CPU
enum class Mode { Exact, Fast };         // Fast exists on CUDA only

const char* to_string(Method m);
const char* to_string(Backend b);
const char* to_string(Mode m);
// Parse "svgf", "cpu|cuda|auto", "exact|fast"; throw std::invalid_argument naming the value.
Method parse_method(const std::string& s);
Backend parse_backend(const std::string& s);
Mode parse_mode(const std::string& s);

struct DenoiserConfig {
  Method method = Method::Svgf;
  Backend backend = Backend::Cpu;
  Mode mode = Mode::Exact;
  SvgfParams svgf;
  int threads = 0;      // CPU worker threads; 0: all cores
  int block_x = 16;     // CUDA block shape (any shape gives the same bits)
  int block_y = 8;
};

// What one denoise() call did.
struct FrameReport {
  StageTimes times;
  int64_t replaced_samples = 0;  // color samples that were NaN, Inf or negative (set to 0)
};

// Internal buffers a caller may read back, for tests and tools.
enum class DebugBuffer {
  Illumination,     // 3: demodulated input
  Accumulated,      // 4: temporally accumulated color + temporal variance
  Moments,          // 2: E[l], E[l^2] after accumulation
  HistoryLength,    // 1
  ColorHistory,     // 3: what the next frame reprojects (the feedback tap)
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
  virtual Image read_buffer(DebugBuffer which) const = 0;
};

// Every backend's rule for a sequence: all frames have the first frame's size. A denoiser that
// has seen a width x height frame (0 x 0: none yet) throws std::invalid_argument for another.
inline void check_frame_size_unchanged(int width, int height, int w, int h) {
  if (width == 0 || (w == width && h == height)) return;
  throw std::invalid_argument("frame size changed mid-sequence from " + std::to_string(width) +
                              "x" + std::to_string(height) + " to " + std::to_string(w) + "x" +
                              std::to_string(h) + " (use a new denoiser for a new sequence)");
}

// Throws std::invalid_argument for an impossible combination (fast mode on the CPU) and
// std::runtime_error when CUDA is asked for but absent. Backend::Auto never throws for lack of
// a device: it falls back to the CPU, and description() says which it chose.
std::unique_ptr<Denoiser> make_denoiser(const DenoiserConfig& config);

// True when this build has the CUDA backend and a CUDA device is present.
bool cuda_available(std::string* why_not = nullptr);

}  // namespace svgf

#pragma once
// Renders complete frames: G-buffer, 1-spp color (split into direct and indirect) and an
// optional high-spp reference. Pixels are independent and their random numbers are keyed by
// pixel, so the output is the same for any thread count or scheduling.
#include <atomic>
#include <cstdint>
#include <limits>

#include "core/frame.h"
#include "gbuffer/frame_scene.h"
#include "gbuffer/path_tracer.h"
#include "gbuffer/scene.h"

namespace svgf::gbuffer {

inline constexpr int kMaxImageSide = 16384;  // pixel keys hold x and y in 16 bits each
inline constexpr int kMaxSpp = 1 << 20;

struct RenderSettings {
  int width = 128;
  int height = 128;
  int spp = 1;            // samples of `color` (and `direct`, `indirect`)
  int reference_spp = 0;  // 0: no reference
  uint64_t seed = 1;
  PathSettings path;
  bool split = true;      // also fill `direct` and `indirect`
  // Also fill `gradient` (gradient_samples.h): all zeros at frame 0 and at camera cuts.
  bool gradients = false;
};

// Throws std::invalid_argument naming the first bad setting.
void validate(const RenderSettings& settings);

// Shared with a progress display while a frame renders. Rows count every finished image row.
struct RenderCounters {
  std::atomic<uint64_t> rays{0};
  std::atomic<uint64_t> rows{0};
  std::atomic<bool> cancel{false};  // set from outside: render() stops and throws
};

// How far one frame's reference is from the true image, as the mean squared error PSNR measures
// (values clamped to [0, 1], mean over pixels and RGB), estimated from the reference's own
// samples: its two halves, samples [0, n1) and [n1, n) with n1 = n/2, are independent estimates
// a and b, so E[(a - b)^2] n1 (n - n1) / n^2 is the variance of their mean, the reference
// (exact where the clamp does not act). A method's MSE against the reference is its MSE against
// the true image plus this (independent noise), so quality reports subtract it
// (bench/eval_quality.cpp). NaN without a reference of at least 2 samples.
// Where a half is above 1 the clamp cuts its difference and the estimate comes out low (against
// two references rendered with two seeds, `svgf-fixtures reference-noise`: within 0.1 dB where
// under 3% of the estimate comes from such values, 0.65 and 1.5 dB low at 20% and 32%), so
// `clamped_share` says how much of it does.
struct ReferenceNoise {
  double mse = std::numeric_limits<double>::quiet_NaN();
  // Standard error of `mse` from the spread of the per-value estimates (pixels independent).
  double standard_error = std::numeric_limits<double>::quiet_NaN();
  // The part of `mse` from channel values where a half is above 1, over `mse` (0 to 1).
  double clamped_share = std::numeric_limits<double>::quiet_NaN();
};

class Renderer {
 public:
  // Renders `frame` of `scene`. The TBB arena of the caller decides the thread count. `noise`,
  // when given, receives the reference's noise estimate (same for any thread count).
  Frame render(const SceneDesc& scene, int frame, const RenderSettings& settings,
               RenderCounters* counters = nullptr, ReferenceNoise* noise = nullptr) const;
  const EmbreeDevice& device() const { return device_; }

 private:
  EmbreeDevice device_;
};

// Sample key of (settings.seed, pixel, frame, sample, stream).
SampleKey sample_key(const RenderSettings& settings, int x, int y, int frame, int sample,
                     Stream stream);

}  // namespace svgf::gbuffer

#pragma once
// Renders complete frames: G-buffer, 1-spp color (split into direct and indirect) and an
// optional high-spp reference. Pixels are independent and their random numbers are keyed by
// pixel, so the output is the same for any thread count or scheduling.
#include <atomic>
#include <cstdint>

#include "core/frame.h"
#include "gbuffer/frame_scene.h"
#include "gbuffer/path_tracer.h"
#include "gbuffer/reference_noise.h"
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

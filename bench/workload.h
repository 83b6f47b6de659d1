#pragma once
// The frames a benchmark run feeds the denoiser: a fixture sequence, or frames rendered at a
// requested size by the Embree renderer (gbuffer/), cached on disk so the next run reads them.
#include <string>
#include <vector>

#include "core/frame.h"

namespace svgf::bench {

struct FrameSet {
  std::string source;  // "fixture", "rendered" or "synthetic"
  std::string scene;
  std::string description;  // one line for reports
  int width = 0, height = 0;
  std::vector<Frame> frames;  // distinct frames; timing runs play them in order, cyclically
  std::vector<int> cuts;      // frame numbers where the camera cuts (history resets)
  bool has_reference() const { return !frames.empty() && frames.front().has_reference(); }
  // Whether every frame carries the `gradient` group (A-SVGF's samples; rendered frames do, the
  // first frame and cuts with no sample in it). Without it `--antilag gradient` runs the
  // statistics rule (docs/svgf.md).
  bool gradient_samples() const;
  bool is_cut(int k) const;
  // Share of pixels with a surface (depth > 0), over all frames: the rest is background, which
  // the filters pass through (bench/stage_cost.h).
  double surface_fraction() const;
};

// "720p", "1080p", "4k", "256" (square) or "WxH".
void parse_size(const std::string& text, int& width, int& height);

// Reads a fixture folder (manifest.json + frame_NNNN.exr); max_frames <= 0: all. The direct and
// indirect channels are dropped unless `split` (only SVGF's --svgf-split on reads them).
FrameSet load_fixture(const std::string& dir, int max_frames = 0, bool split = false);

// `count` distinct frames 0..count-1 of `scene` at width x height, 1 spp, no reference, with
// A-SVGF's gradient samples; `split`: with the direct and indirect channels (cached apart).
// With the renderer (svgf_gbuffer linked), frames come from the cache folder when present there,
// else are rendered and stored (cache_dir empty: no cache); a cached frame without the world
// positions or the gradient samples (an older cache) is rendered again. Without it, a synthetic moving scene
// (tests/synthetic_sequence.h) stands in, and `source` says so.
FrameSet generate_frames(const std::string& scene, int width, int height, int count,
                         const std::string& cache_dir, bool split = false);

// Whether this build can render (svgf_gbuffer was linked).
bool renderer_available();

// Fixture folders (those holding a manifest.json) under `root`, sorted by name.
std::vector<std::string> fixture_dirs(const std::string& root);

}  // namespace svgf::bench

#pragma once
// What each pipeline stage must move and compute per pixel: the one place the benchmark's
// bandwidth, roofline floor and docs/benchmarks.md numbers come from. stage_cost.cpp lists, per
// kernel, the planes it reads and writes (4-byte floats or mesh ids) and a hand count of its
// floating-point operations. Counted: every SVGF stage (A-SVGF's gradient stages, TAA and the
// split frame's sum included) and every BMFR stage (frame floors); of the other methods the
// filter stage alone (the JBF's full window or a-trous levels, the wavelet's a-trous passes), so
// they have per-stage floors and per-tap costs but no frame floor. A split SVGF frame (direct and
// indirect filtered apart) counts only the stages it runs once: the gradient stages, split_sum
// and taa.
//
// Checked: exact mode's plane counts, surface and background pixel, by
// tests/bench_stage_cost_test.cpp, which runs each stage functor on the CPU and finds the planes
// its output depends on and the planes it stores (BMFR's regression: the planes its block's
// weights depend on and the per-block values it stores; the gradient stages: per stratum). Not
// checked: the operation counts (hand counts), and fast mode (SvgfFast and FastArith exist only
// under nvcc; their kernels are counted from the same functors by hand).
#include <optional>
#include <string>

#include "core/stage_times.h"
#include "methods/bmfr/params.h"
#include "methods/jbf/params.h"
#include "methods/svgf/params.h"
#include "methods/wavelet/params.h"
#include "methods/svgf/stages.h"
#include "pipeline/make_denoiser.h"

namespace svgf::bench {

// SVGF's stages (methods/svgf/stages.h) and the CUDA engine's transfers, as the cost model
// indexes them.
enum class Stage : int { Sanitize = 0, Gradient, GradientAtrous, GradientLambda, Demodulate,
                         Reproject, Variance, Atrous, Feedback, Remodulate, SplitSum, Taa, Upload,
                         Download, Count };
constexpr int kStageCount = static_cast<int>(Stage::Count);
inline const char* stage_name(Stage s) {
  switch (s) {
    case Stage::Sanitize: return kSanitizeStage;
    case Stage::Gradient: return svgf_stage::kGradient;
    case Stage::GradientAtrous: return svgf_stage::kGradientAtrous;
    case Stage::GradientLambda: return svgf_stage::kGradientLambda;
    case Stage::Demodulate: return svgf_stage::kDemodulate;
    case Stage::Reproject: return svgf_stage::kReproject;
    case Stage::Variance: return svgf_stage::kVariance;
    case Stage::Atrous: return svgf_stage::kAtrous;
    case Stage::Feedback: return svgf_stage::kFeedback;
    case Stage::Remodulate: return svgf_stage::kRemodulate;
    case Stage::SplitSum: return svgf_stage::kSplitSum;
    case Stage::Taa: return svgf_stage::kTaa;
    case Stage::Upload: return kUploadStage;
    case Stage::Download: return kDownloadStage;
    default: return "?";
  }
}

// The cost model's stage named `name` (SVGF's stage names and the transfers); none for another
// name.
inline std::optional<Stage> svgf_cost_stage(const std::string& name) {
  for (int s = 0; s < kStageCount; ++s)
    if (name == stage_name(static_cast<Stage>(s))) return static_cast<Stage>(s);
  return std::nullopt;
}

struct StageCost {
  double read = 0;     // bytes read from memory per pixel, each plane once
  double written = 0;  // bytes written per pixel, each plane once
  double ops = 0;      // floating-point operations per pixel on the steady-state path
  double taps = 0;     // neighbour taps per pixel (edge-stopping filters; the centre excluded)
  std::string planes;  // which planes, for the docs
  double bytes() const { return read + written; }
};

// What the frames carry and their size, where a stage's cost depends on them.
struct FrameTraits {
  bool emission = false;          // the optional emission planes
  bool gradient_samples = false;  // the `gradient` group: --antilag gradient runs its stages
  bool split = false;             // SVGF filters direct and indirect apart (split_sum runs)
  double surface_fraction = 1.0;  // the share of pixels with a surface
  // The share of surface pixels whose history is younger than spatial_variance_history, where
  // the variance stage takes its 7x7 estimate instead of passing the temporal variance through
  // (disocclusions, a camera's motion: 10 to 18% at 720p camera-pan). 0: the steady state.
  double young_fraction = 0.0;
  int width = 0, height = 0;      // the stratum image's share of pixels; 0: a ninth
  // Exact mode over packed pixels, as the CUDA engine runs it (methods/svgf/flavors.h:
  // SvgfExactPacked): demodulate + reproject + guide packing in one kernel, the filter reads
  // packed pixels, the feedback copy and the remodulation ride on the a-trous iterations.
  bool packed_exact = false;
  // The feedback copy and the remodulation ride on the a-trous iterations whose results they
  // are (methods/svgf/flavors.h, kFusedOutputs), as every engine runs SVGF: the runner sets it.
  // Without it (and without packed_exact, which implies it) they are counted as the passes of
  // their own that the stage kernels are (tests/bench_stage_cost_test.cpp compares those).
  bool fused_outputs = false;
};

// Cost of `stage` in one frame, all a-trous iterations together for Stage::Atrous and
// Stage::GradientAtrous. Upload and Download give the bytes crossing the host link (their ops are
// 0). Fast mode and CUDA's exact mode (f.packed_exact) fuse stages: demodulate + reproject run
// as one kernel, timed and counted as Demodulate (Reproject is then empty); feedback and
// remodulate ride on the a-trous iterations. `f.emission`: the frames carry the optional
// emission planes, which demodulate subtracts and remodulate adds back. `f.surface_fraction`:
// the share of pixels with a surface; background pixels (no surface) skip the history, the
// edge-stopping taps and the planes those read, and cost much less (for the gradient stages:
// the share of strata with a sample).
// `f.young_fraction`: of the surface pixels, those whose variance is the 7x7 estimate (its
// (2r + 1)^2 taps, counted in StageCost::taps); the others pass through. A stage
// the configuration does not run costs nothing: the gradient stages without --antilag gradient
// or without gradient samples, TAA without --svgf-taa on, split_sum on unsplit frames. The
// gradient stages work on the stratum image, ceil(w/3) x ceil(h/3) values a plane: their counts
// are per stratum times strata_per_px(width, height); the same functors in both modes.
StageCost stage_cost(Mode mode, Stage stage, const SvgfParams& p, const FrameTraits& f);
// Frames without gradient samples, not split, strata a ninth of the pixels.
StageCost stage_cost(Mode mode, Stage stage, const SvgfParams& p, bool emission,
                     double surface_fraction);

// Sum over the filtering stages (transfers excluded).
StageCost frame_cost(Mode mode, const SvgfParams& p, const FrameTraits& f);
StageCost frame_cost(Mode mode, const SvgfParams& p, bool emission, double surface_fraction);

// Strata (A-SVGF's 3x3 pixel blocks, partial ones at the right and bottom) per pixel of a
// width x height frame: 1/9 at 1920x1080; 1/9 for a size of 0.
double strata_per_px(int width, int height);

// TAA after remodulation (core/taa.h), the same functor for SVGF and BMFR, per pixel with
// history.
StageCost taa_cost();

// The JBF's spatial filter in one frame (methods/jbf/filter.h): the full window of p.radius
// (p.levels 0, stage "filter") or all p.levels a-trous levels (stage "atrous"). Background
// pixels pass through.
StageCost jbf_filter_cost(Mode mode, const JbfParams& p, double surface_fraction);
// The wavelet filter's a-trous passes in one frame (methods/wavelet/atrous.h), all p.iterations.
StageCost wavelet_atrous_cost(Mode mode, const WaveletParams& p, double surface_fraction);

// BMFR's stage `name` (methods/bmfr/: sanitize, accumulate, regression, weighted_sum, post, and
// the CUDA transfers) on width x height frames; none for another name. The regression is counted
// a row of its blocks (1024 rows, each one pixel's features; rows outside the image mirror
// pixels inside) times the rows per pixel, plus each block's own work and output times the
// blocks per pixel (bmfr_blocks_per_px). Its scratch (shared memory on CUDA, task memory on the
// CPU) moves no bytes. Every column is counted as kept: true of the noise strategy in the steady
// state; for skip, whose skipped columns save their reflections, an upper bound.
std::optional<StageCost> bmfr_stage_cost(Mode mode, const BmfrParams& p, const std::string& name,
                                         bool emission, double surface_fraction, int width,
                                         int height);
// Blocks per pixel of BMFR's grid at width x height: the mean over the grid's 16 offsets (the
// grid sticks out of the image by up to a block on each side: about (w/32 + 1)(h/32 + 1) blocks).
double bmfr_blocks_per_px(int width, int height);

// The model's count of stage `name` of the configured method on frames `f`, none where that
// stage has no model (see the top of this file). `d.jbf.levels` is the a-trous form's level
// count as the denoiser runs it (0: the full window).
std::optional<StageCost> method_stage_cost(const DenoiserConfig& d, const std::string& name,
                                           const FrameTraits& f);
// Whether every filtering stage of `m` is counted, so that its frame has a floor.
bool frame_is_costed(Method m);

}  // namespace svgf::bench

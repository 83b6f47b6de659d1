// Bytes and operations per pixel of every SVGF stage, read off the functors in methods/svgf/:
// exact mode (both backends) and the SvgfFast flavor (fast mode, methods/svgf/flavors.h), counted
// by hand, A-SVGF's gradient stages (methods/svgf/gradient.h) and TAA (core/taa.h) once for both;
// of every BMFR stage (methods/bmfr/); and of the filter stage of the JBF (methods/jbf/)
// and of the wavelet filter (methods/wavelet/), in both modes. tests/bench_stage_cost_test.cpp
// checks exact mode's plane counts (bytes) against the kernels; the operation counts, and
// everything of fast mode, are not checked (see stage_cost.h). Conventions (docs/benchmarks.md):
//  - bytes: every plane the kernel reads, once, plus every plane it writes, once; 4 bytes a
//    value. Neighbour taps are assumed served by the caches (that is the floor, not a model);
//  - the steady state: a surface pixel whose history is at least spatial_variance_history frames
//    old and whose four bilinear reprojection taps pass (the 3x3 reprojection fallback is rare
//    after the first frames). The young-history 7x7 variance estimate is not rare under a
//    moving camera: the share of surface pixels that take it is a trait of the frames
//    (FrameTraits::young_fraction, counted by the benchmark run), 0 in the steady state;
//  - ops: floating-point operations (add, mul, compare/select, min/max, abs, floor, conversion;
//    a division, square root or special function counts one) from the source. Fast mode is
//    counted with FMA contraction (a multiply-add is one op), as it is compiled.
#include "bench/stage_cost.h"

#include "core/normal_weight.h"
#include "methods/bmfr/denoiser.h"
#include "methods/jbf/denoiser.h"
#include "methods/svgf/gradient_tile.h"
#include "methods/svgf/pipeline.h"
#include "methods/wavelet/denoiser.h"

namespace svgf::bench {
namespace {

constexpr double kFloat = 4.0;

// A share of pixels (surface, young history) kept inside [0, 1].
double unit_share(double v) { return v < 0 ? 0 : (v > 1 ? 1 : v); }
// The 5x5 a-trous grid of SVGF and the JBF without its centre.
constexpr int kGridTaps = 24;

// det_exp_nonpositive (core/det_math.h): clamp 1, k = floor(x log2e + 1/2) 3, Cody-Waite r 4,
// r^2 1, polynomial 8 (det_exp_poly's four Horner steps; five with Cephes' polynomial before
// 2026-12-02), y 3, 2^(k+64)'s exponent field from k 2 (an add, a shift), two scale products 2:
// 24. (Counted as 25 until the polynomial lost its step, when it was 26: so that the floors
// stayed comparable with the form before, which had 31.)
constexpr double kDetExp = 24;
// FastArith's exp (core/arith.h): the scale by log2 e and ex2.approx.
constexpr double kFastExp = 2;

// --- exact mode (core/*.h) ----------------------------------------------------------------
// edge_stopping_weight (edge_stopping.h) with phi_normal = 128: dot 5, max 1, seven squarings 7;
// depth and luminance terms |a-b|/phi 3 + 3; two clamps and the sum 4; det_exp_nonpositive 24;
// times the normal weight and the > 0 select 2.
constexpr double kExactEdgeWeight = 13 + 6 + 4 + kDetExp + 2;  // 49
constexpr double kLuminance = 5;                          // 3 mul, 2 add
// One a-trous tap: the tap's luminance, the weight, tap_distance (3 + sqrt) and phi_z * d 5,
// the B3 product and times it 2, accumulation (weight 1, color 6, variance w*w*v + add 3) 10.
constexpr double kExactAtrousTap = kLuminance + kExactEdgeWeight + 5 + 2 + 10;  // 71
// Per pixel and iteration, outside the 24 taps: 3x3 variance prefilter 9 x 4 + division 37;
// phi_l 4; phi_z 5; centre luminance 5; centre terms 5; final normalization 5.
constexpr double kExactAtrousCentre = 37 + 4 + 5 + 5 + 5 + 5;  // 61
constexpr double kExactAtrousIteration = kGridTaps * kExactAtrousTap + kExactAtrousCentre;

// reproject.h, four bilinear taps kept: position, range check, floors, fractions and the four
// bilinear weights 22; per tap the consistency test (fwidth 3, tolerance 3, depth test 3,
// normal dot and test 6) 15 and the accumulation 13; normalization 7; blend (luminance 5,
// length 2, both alphas 4, color 9, moments 7, variance 3) 30.
constexpr double kReproject = 22 + 4 * (15 + 13) + 7 + 30;  // 171
// Without history (background, disocclusion): the blend with alpha = 1, luminance 5, color 9,
// moments 7, variance 3, length and alpha selects 2.
constexpr double kReprojectNoHistory = 26;
// core/sanitize.h on a clean pixel (every mode): range tests of color 6, albedo 6, motion 4,
// the guides' bounds 12, the normal's squared length 5 and its range 2.
constexpr double kSanitize = 35;
// demodulate.h: albedo clamp 3, three divisions 3.
constexpr double kDemodulate = 6;
// variance.h on the steady-state path: the history and surface tests, then a copy.
constexpr double kVarianceSteady = 2;
// variance.h's 7x7 estimate (rare_path), one tap: its luminance 5, the edge-stopping weight 50,
// tap_depth_scale (2 conversions, 2 products, sum, sqrt, division, product) 8, the sums (weight
// 1, color 3 mul + 3 add, moments 2 mul + 2 add) 11. The centre tap is one of the (2r + 1)^2.
constexpr double kExactVarianceTap = kLuminance + kExactEdgeWeight + 8 + 11;  // 73
// Outside the taps: the history and surface tests 2, the centre's luminance 5,
// inv_depth_tolerance (fwidth: 2 abs, max; the floor's max, product, division) 6, 1 / phi_l 1,
// the weight's max 1, the five divisions by it 5, spatial_variance (m1^2, difference, max,
// svh / history, 2 products; variance_of_mean_scale: min, test, division) 9.
constexpr double kExactVarianceYoung = 2 + 5 + 6 + 1 + 1 + 5 + 9;  // 29
// remodulate.h: albedo clamp 3, product 3 (plus 3 adds with emission).
constexpr double kRemodulate = 6;
// With emission planes, demodulate's subtraction and clamp: 3 + 3.
constexpr double kEmission = 6;

// --- the anti-lag in the reprojection (reproject.h), a surface pixel with history ------------
// A-SVGF: lambda < 1 and > 0 tests 2, the two alpha' = min(1, (1 - lambda) alpha + lambda) 8,
// the length min(length, 1 / alpha') 2.
constexpr double kLambdaBlend = 12;
// The statistics rule (history_discrepancy, antilag_drop) over the (2r + 1)^2 neighbourhood, N
// pixels: per pixel the mesh and surface tests 2, the count, sum and sum of squares 4; per
// neighbour but the centre its luminance again, demodulated (emission subtracted 3, max 3, the
// albedo clamp 3, divisions 3) 12 and luminance 5; then the mean 1, the spread (n > 1, the
// product, difference, max, division) 5, the history's luminance 5, the tolerance (two
// divisions, max, sum, sqrt, two max, product, sum) 9, |difference| / tolerance 3; the drop
// (test, (d - low) / (high - low) 3, min) 5; the length scaled by 1 - drop and tested 3.
double statistics_antilag_ops(int radius) {
  const int n = (2 * radius + 1) * (2 * radius + 1);
  return n * 6.0 + (n - 1) * (12.0 + kLuminance) + 1 + 5 + kLuminance + 9 + 3 + 5 + 3;
}

// --- A-SVGF's gradient stages (gradient.h), per stratum; exact arithmetic in every mode -------
// Samples: the mask tests up to the sample (5 on average; a stratum without one: all 9), the
// two radiance tests 4 (>= 0, <= max), delta 1, the normalizer's max 1, the weight select and
// the guide offset's conversion 2.
constexpr double kGradientSamples = 5 + 4 + 1 + 1 + 2;  // 13
constexpr double kGradientSamplesNone = 9 + 1;
// A-trous step: the centre's fwidth (2 abs, max) 3 and 1 / phi_z (test, max, product,
// division) 4; per neighbour tap with data the weight test 1, tap_depth_scale (2 conversions,
// 2 products, sum, sqrt, division, product) 8, the edge-stopping weight 52 and the accumulation
// (weight sum 1, delta and normalizer mul + add 4) 5; the centre tap the test and accumulation
// 6; the normalization (test, 2 divisions, 2 selects) 5. A stratum without data: the centre's
// 7, nine weight tests, the normalization.
constexpr int kGradientTaps = 8;
constexpr double kGradientAtrousTap = 1 + 8 + kExactEdgeWeight + 5;  // 63
constexpr double kGradientAtrousStratum = 7 + kGradientTaps * kGradientAtrousTap + 6 + 5;  // 522
constexpr double kGradientAtrousNone = 7 + 9 + 5;
// Lambda: the weight test, the normalizer test, |delta|, the division, the min 5; without data
// the weight test. It is taken over the (2r + 1)^2 strata around (gradient_lambda_radius), each
// with its bounds test 4 and the max 1; their data come through the cache, so the bytes stay
// one stratum's.
constexpr double kGradientLambda = 5;
constexpr double kGradientLambdaNone = 1;
constexpr double kGradientLambdaNeighbour = 4 + 1;

// --- TAA (core/taa.h), a pixel with history -------------------------------------------------
// x + motion with conversions 4; the bilinear taps' position 6; per tap its weight 2, the total
// 1, the weighted history 6 (4 x 9); the total test 1; per 3x3 neighbour YCoCg 9 and the box's
// min and max 6, for the five of the cross their min and max 6 (165); the bounds' midpoints
// 2 x 6; the history's division by the total 3 and YCoCg 9; the clamp 6; back to RGB 8; the
// blend (c alpha 3, 1 - alpha 1, clamped (1 - alpha) 3, sum 3, max 3) 13.
constexpr double kTaa = 4 + 6 + 4 * 9 + 1 + (9 * (9 + 6) + 5 * 6) + 12 + 12 + 6 + 8 + 13;  // 263

// --- fast mode (SvgfFast) -----------------------------------------------------------------
// One tap: luminance 3 and normal dot 3 (mul + 2 FMA each), max 1, seven squarings 7, depth and
// luminance terms 3 + 3, their sum 1, __expf 2 (scale + ex2), times normal weight 1, select 1,
// times B3 weight 1, inv_phi_z * inv_dist 1, accumulation (weight 1, color 3 FMA, w*w and FMA 2) 6.
constexpr double kFastAtrousTap = 3 + 3 + 1 + 7 + 3 + 3 + 1 + 2 + 1 + 1 + 1 + 1 + 6;  // 33
// Outside the taps: 3x3 prefilter (9 FMA, 9 weight adds, divide 2) 20, phi_l and its reciprocal
// 6, phi_z and its reciprocal 6, centre luminance 3, centre terms 5, final normalization 6.
constexpr double kFastAtrousCentre = 20 + 6 + 6 + 3 + 5 + 6;  // 46
constexpr double kFastAtrousIteration = kGridTaps * kFastAtrousTap + kFastAtrousCentre;
// The variance's 7x7 estimate, one tap: the a-trous tap's weight (luminance 3, normal dot 3,
// max 1, squarings 7, the two terms 3 + 3, sum 1, __expf 2, times the normal weight 1, select
// 1) 25, the depth scale 1 (the constant 1 / distance of an unrolled tap), the sums (weight 1,
// color 3 FMA, moments 2 FMA) 6.
constexpr double kFastVarianceTap = 25 + 1 + 6;  // 32
// Outside the taps: the tests 2, centre luminance 3, the depth tolerance and its reciprocal 6,
// 1 / phi_l 1, the weight's max and reciprocal 2, five products 5, spatial_variance 9.
constexpr double kFastVarianceYoung = 2 + 3 + 6 + 1 + 2 + 5 + 9;  // 28

// A surface pixel's variance stage `steady` (the pass-through) mixed with the young-history
// estimate by f.young_fraction. A young pixel reads its length, the accumulated color 3 (not its
// variance), the moments 2, depth and normal 4 (planar or packed alike) and depth dx/dy 2 (its
// neighbours' through the caches), writes the same 4, and computes (2r + 1)^2 taps of `tap`
// operations and `centre` outside them.
StageCost with_young_variance(StageCost steady, const SvgfParams& p, const FrameTraits& f,
                              double tap, double centre) {
  const double y = unit_share(f.young_fraction);
  if (y <= 0) return steady;
  const double side = 2.0 * p.spatial_variance_radius + 1;
  const double taps = side * side;
  const double young_read = (1 + 3 + 2 + 4 + 2) * kFloat;
  steady.read = (1 - y) * steady.read + y * young_read;
  steady.ops = (1 - y) * steady.ops + y * (centre + taps * tap);
  steady.taps = y * taps;
  const std::string young = "young history: R length 1, color 3, moments 2, depth + normal 4, "
                            "depth dx/dy 2, " + std::to_string(static_cast<int>(taps)) +
                            " taps; W 4";
  steady.planes = y >= 1 ? young : steady.planes + "; " + young;
  return steady;
}

// The sanitize stage reads every input plane the pipeline uses and, on clean input, writes
// nothing (the same kernel in both modes). `position`: the method reads world positions (BMFR),
// which sanitize checks too: 6 more bound tests.
StageCost sanitize_cost(bool emission, bool position = false) {
  const double e = emission ? 3 : 0, p = position ? 3 : 0;
  StageCost c;
  c.read = (3 + 3 + e + 3 + p + 1 + 2 + 2) * kFloat;
  c.ops = kSanitize + (emission ? 6 : 0) + (position ? 6 : 0);
  c.planes = std::string("R color 3, albedo 3, emission 3 (if any), normal 3, ") +
             (position ? "position 3, " : "") + "depth, gradient 2, motion 2";
  return c;
}

StageCost download_cost() {
  StageCost c;
  c.written = 3 * kFloat;
  c.planes = "device to host: output 3";
  return c;
}

// The frame's upload to the device (kernels_cuda/cuda_backend.h): the input planes in one copy,
// then the world positions when the method reads them. `gradient`: the method reads the frame's
// gradient samples, which come after the emission planes: those are sent along even when the
// frame has none.
StageCost upload_cost(bool emission, bool position, bool gradient = false) {
  StageCost c;
  c.read = (15 + (gradient ? 3 + 3 : emission ? 3 : 0) + (position ? 3 : 0)) * kFloat;
  c.planes = std::string(
                 "host to device: color 3, albedo 3, normal 3, depth, depth dx/dy 2, motion 2, "
                 "mesh id, emission 3 (if any") +
             (gradient ? " or gradient samples), gradient samples 3" : ")") +
             (position ? ", position 3" : "");
  return c;
}

bool gradient_runs(const SvgfParams& p, const FrameTraits& f) {
  return p.antilag == Antilag::Gradient && f.gradient_samples;
}
// The statistics rule runs where asked, and for A-SVGF on frames without samples.
bool statistics_runs(const SvgfParams& p, const FrameTraits& f) {
  return p.antilag == Antilag::Statistics || (p.antilag == Antilag::Gradient && !f.gradient_samples);
}

// What the anti-lag adds to the reprojection of a surface pixel. `inputs_read`: the stage does
// not read this frame's color, albedo and emission otherwise (exact mode; fast mode's fused
// kernel has them from the demodulation, the neighbours' from the caches).
StageCost antilag_extra(const SvgfParams& p, const FrameTraits& f, bool surface,
                        bool inputs_read) {
  StageCost c;
  if (!surface) return c;  // no history: neither rule looks
  if (gradient_runs(p, f)) {
    c.read = strata_per_px(f.width, f.height) * kFloat;  // lambda, a value a stratum
    c.ops = kLambdaBlend;
    c.planes = ", gradient: lambda a stratum";
  } else if (statistics_runs(p, f)) {
    c.read = inputs_read ? 0 : (3 + 3 + (f.emission ? 3 : 0)) * kFloat;
    c.ops = statistics_antilag_ops(p.antilag_radius);
    c.planes = inputs_read ? ", statistics: the neighbourhood's color, albedo, emission (cached)"
                           : ", statistics: color 3, albedo 3, emission 3 (if any)";
  }
  return c;
}

StageCost plus(StageCost a, const StageCost& b) {
  a.read += b.read;
  a.written += b.written;
  a.ops += b.ops;
  a.taps += b.taps;
  a.planes += b.planes;
  return a;
}

// The stages both modes run the same functors for: A-SVGF's three (per stratum, scaled by the
// strata a pixel), split_sum and TAA. Zero where the configuration does not run them.
StageCost shared_cost(Stage stage, const SvgfParams& p, const FrameTraits& f, bool surface) {
  const double r = strata_per_px(f.width, f.height);
  StageCost c;
  switch (stage) {
    case Stage::Gradient:
      if (!gradient_runs(p, f)) break;
      // The mask at the stratum's 9 pixels (the scan stops at its sample, but they share its
      // cache lines); the sample's previous and current luminance; the stratum's delta,
      // normalizer, weight and guide offset written.
      c.read = (9 + (surface ? 2 : 0)) * r * kFloat;
      c.written = 4 * r * kFloat;
      c.ops = (surface ? kGradientSamples : kGradientSamplesNone) * r;
      c.planes =
          "per stratum R mask at its 9 pixels, previous and current at the sample (no sample: "
          "the mask); W delta, normalizer, weight, guide offset";
      break;
    case Stage::GradientAtrous: {
      if (!gradient_runs(p, f)) break;
      // Per step and stratum: delta, normalizer, weight, guide offset and its guide pixel's
      // depth, depth dx/dy, normal 3, mesh id (the taps' are their strata's own); without data
      // in reach the delta and normalizer are not read. 3 written.
      const int n = p.gradient_iterations;
      c.read = n * (surface ? 11 : 9) * r * kFloat;
      c.written = n * 3 * r * kFloat;
      c.ops = n * (surface ? kGradientAtrousStratum : kGradientAtrousNone) * r;
      c.taps = surface ? n * kGradientTaps * r : 0;
      c.planes =
          "per step and stratum R delta, normalizer, weight, guide offset, its pixel's depth, "
          "depth dx/dy 2, normal 3, mesh id (no data: not delta, normalizer); W delta, "
          "normalizer, weight";
      break;
    }
    case Stage::GradientLambda:
      if (!gradient_runs(p, f)) break;
      c.read = (surface ? 3 : 1) * r * kFloat;
      c.written = r * kFloat;
      {
        const double taps = (2.0 * p.gradient_lambda_radius + 1) * (2 * p.gradient_lambda_radius + 1);
        c.ops = taps * ((surface ? kGradientLambda : kGradientLambdaNone) + kGradientLambdaNeighbour) * r;
      }
      c.planes = "per stratum R weight, delta, normalizer (no data: weight); W lambda";
      break;
    case Stage::SplitSum:
      if (!f.split) break;
      c.read = (3 + 3) * kFloat;
      c.written = 3 * kFloat;
      c.ops = 3;
      c.planes = "R direct's output 3, indirect's 3; W output 3 (in place)";
      break;
    case Stage::Taa:
      if (p.taa) c = taa_cost();
      break;
    default:
      break;
  }
  return c;
}

// A-SVGF's three stages as one block kernel over tiles of strata (methods/svgf/gradient_tile.h:
// fast mode and CUDA's exact mode, where the filter is the default's size), timed and counted as
// Gradient: the three stages' operations, and of their bytes only what leaves or enters the
// block: the samples' reads, each stratum's guide pixel (depth, depth dx/dy 2, normal 3, mesh
// id) when a step filters, the lambda written. The halo the tiles compute twice is not counted
// (the floor is the work, not the tiling's overlap).
bool gradient_fused(Mode mode, const SvgfParams& p, const FrameTraits& f) {
  return (mode == Mode::Fast || f.packed_exact) &&
         GradientTileKernel::handles(p.gradient_iterations, p.gradient_lambda_radius);
}
StageCost fused_gradient_cost(Stage stage, const SvgfParams& p, const FrameTraits& f,
                              bool surface) {
  StageCost c;
  if (stage != Stage::Gradient || !gradient_runs(p, f)) return c;
  const double r = strata_per_px(f.width, f.height);
  for (Stage s : {Stage::Gradient, Stage::GradientAtrous, Stage::GradientLambda}) {
    const StageCost part = shared_cost(s, p, f, surface);
    c.ops += part.ops;
    c.taps += part.taps;
  }
  const bool steps = p.gradient_iterations > 0;
  c.read = ((9 + (surface ? 2 : 0)) + (steps && surface ? 7 : 0)) * r * kFloat;
  c.written = r * kFloat;
  c.planes = std::string("per stratum R mask at its 9 pixels, previous and current at the sample") +
             (steps ? ", its guide pixel's depth, depth dx/dy 2, normal 3, mesh id" : "") +
             "; W lambda (the samples and filtered strata stay in the block)";
  return c;
}

// Whether the sanitize stage rides on the demodulation's kernel in a steady frame (fast mode
// and CUDA's exact mode: methods/svgf/pipeline.h, fuses_sanitize); it is then counted there.
bool sanitize_fused(Mode mode, const SvgfParams& p, const FrameTraits& f) {
  return (mode == Mode::Fast || f.packed_exact) &&
         sanitize_fusable(p, /*has_history=*/true, gradient_runs(p, f), f.split);
}

// Whether the packed flavors' accumulation has a variance plane: only from a split frame on.
// Otherwise the CUDA denoiser keeps the frame's scratch in the history (methods/svgf/denoiser.h:
// scratch_in_history): the first kernel writes the accumulated color only, and the variance
// stage derives the variance from the moments (1 float more read there).
bool packed_variance_plane(const FrameTraits& f) { return f.split; }

// Demodulate + reproject + guide packing in one kernel (fast mode, and CUDA's exact mode:
// kFusedReprojection in methods/svgf/flavors.h), timed and counted as Demodulate. The
// illumination stays in the thread's registers. Background pixels read depth and normal
// only (to pack them), besides color and albedo. `sanitize`: the sanitize stage rides on it:
// its tests, and on background the planes only it reads (depth dx/dy, motion 2).
StageCost fused_reprojection_cost(const SvgfParams& p, const FrameTraits& f, bool surface,
                                  bool sanitize) {
  StageCost c;
  c.read = (3 + 3 + (f.emission ? 3 : 0) + (surface ? 9 + 5 + 6 : sanitize ? 8 : 4)) * kFloat;
  // The illumination stays in registers (stored for the keep_scratch debug buffer only).
  const double accumulated = packed_variance_plane(f) ? 4 : 3;
  c.written = (accumulated + 2 + 1 + 4) * kFloat;  // + packed guides (depth, normal)
  c.ops = kDemodulate + (f.emission ? kEmission : 0) + (surface ? kReproject : kReprojectNoHistory);
  c.planes =
      "R color 3, albedo 3, emission 3 (if any), guides 9, previous guides 5 (packed depth + "
      "normal 4, mesh id), history 6 (background: depth, normal); W accumulated 4 (3 without a "
      "split frame), moments 2, length 1, packed guides 4 (the illumination in registers)";
  if (sanitize) {
    c.ops += sanitize_cost(f.emission).ops;
    c.planes += "; the sanitize stage's tests (background: + depth dx/dy, motion 2)";
  }
  return plus(c, antilag_extra(p, f, surface, true));
}

// The a-trous iterations when the feedback copy and the remodulation ride on them (kFusedOutputs
// in methods/svgf/flavors.h: fast mode, and exact mode on both engines): the last iteration
// reads albedo (+ emission) and writes the output 3 instead of the signal's 4 (a packed pixel
// or color + variance planes); the feedback tap's iteration also writes the color history 3.
StageCost with_fused_outputs(StageCost c, const SvgfParams& p, bool emission) {
  if (p.iterations <= 0) return c;
  c.read += (3 + (emission ? 3 : 0)) * kFloat;
  c.written += (-4 + 3 + (p.feeds_back_iteration() ? 3 : 0)) * kFloat;
  c.ops += kRemodulate + (emission ? 3 : 0);
  c.planes += "; last R albedo 3 (+ emission 3), W output 3 (not the signal's 4); tap W history 3";
  return c;
}

// The remodulation as a pass of its own where nothing else does it: no iteration. (Without a
// feedback tap in range no pass copies the history either: the reprojection accumulates into
// it, methods/svgf/pipeline.h.) `packed`: it reads the signal's packed pixel (4 floats), not
// its color planes (3).
StageCost unfused_output_cost(Stage stage, const SvgfParams& p, bool emission, bool packed) {
  StageCost c;
  if (stage == Stage::Remodulate && p.iterations <= 0) {
    c.read = ((packed ? 4 : 3) + 3 + (emission ? 3 : 0)) * kFloat;
    c.written = 3 * kFloat;
    c.ops = kRemodulate + (emission ? 3 : 0);
    c.planes = packed ? "R packed 4, albedo 3, emission 3 (if any); W output 3"
                      : "R color 3, albedo 3, emission 3 (if any); W output 3";
  }
  return c;
}

StageCost exact_cost(Stage stage, const SvgfParams& p, const FrameTraits& f, bool surface) {
  const bool emission = f.emission;
  const bool packed = f.packed_exact;
  const bool fused_outputs = packed || f.fused_outputs;
  const double e = emission ? 3 : 0;  // emission planes, when the frames have them
  StageCost c;
  switch (stage) {
    case Stage::Sanitize:
      if (sanitize_fused(Mode::Exact, p, f)) break;  // in the demodulation's kernel (CUDA)
      return sanitize_cost(emission);
    case Stage::Demodulate:
      if (packed)  // + reproject (CUDA)
        return fused_reprojection_cost(p, f, surface, sanitize_fused(Mode::Exact, p, f));
      c.read = (3 + 3 + e) * kFloat;  // color, albedo, emission
      c.written = 3 * kFloat;         // illumination
      c.ops = kDemodulate + (emission ? kEmission : 0);
      c.planes = "R color 3, albedo 3, emission 3 (if any); W illumination 3";
      break;
    case Stage::Reproject:
      if (packed) break;  // in the demodulation's kernel
      // Surface: this frame's guides: mesh id, depth, depth dx/dy, normal 3, motion 2 (9); the
      // illumination 3; the previous guides at the taps: mesh id, depth, normal 3 (5); the
      // history: color 3, moments 2, length 1 (6). Background: depth and illumination only.
      c.read = (surface ? 9 + 3 + 5 + 6 : 1 + 3) * kFloat;
      c.written = (4 + 2 + 1) * kFloat;  // accumulated color + variance, moments 2, length
      c.ops = surface ? kReproject : kReprojectNoHistory;
      c.planes =
          "R guides 9, illumination 3, previous guides 5, history 6 (background: depth, "
          "illumination); W accumulated 4, moments 2, length 1";
      c = plus(c, antilag_extra(p, f, surface, false));
      break;
    case Stage::Variance:
      // The history length alone sends an old surface pixel down the pass-through (the guides
      // are read on the young-history path only); a background pixel's length is 1, so it
      // reads its depth too.
      // Packed: the background's depth comes with its normal.
      // Packed without a variance plane: the moments instead (packed_variance_plane).
      c.read = (1 + 4 + (packed && !packed_variance_plane(f) ? 1 : 0) +
                (surface ? 0 : packed ? 4 : 1)) *
               kFloat;  // length, accumulated (or its color and the moments), (depth)
      c.written = 4 * kFloat;  // filtered[0] color + variance
      c.ops = kVarianceSteady;
      c.planes = packed ? "R length 1, accumulated 4 or its color 3 and moments 2 (background: + "
                          "packed guides 4); W packed 4"
                        : "R length 1, accumulated 4 (background: + depth 1); W color + variance 4";
      if (surface) c = with_young_variance(c, p, f, kExactVarianceTap, kExactVarianceYoung);
      break;
    case Stage::Atrous:
      // Per iteration: color + variance 4, depth, depth dx/dy, normal 3 (10 read; background
      // pixels pass through: color + variance and depth, 5); 4 written.
      // Packed: the same 10 on a surface; a background pixel reads its packed pixel and guides.
      c.read = p.iterations * (surface ? 10 : packed ? 8 : 5) * kFloat;
      c.written = p.iterations * 4 * kFloat;
      c.ops = surface ? p.iterations * kExactAtrousIteration : 0;
      c.taps = surface ? p.iterations * kGridTaps : 0;
      c.planes = packed ? "per iteration R packed 4, packed guides 4, depth dx/dy 2 (background: "
                          "packed, packed guides); W packed 4"
                        : "per iteration R color + variance 4, depth 1, depth dx/dy 2, normal 3 "
                          "(background: color + variance, depth); W color + variance 4";
      // The feedback copy and the remodulation riding on the iterations (both engines).
      if (fused_outputs) c = with_fused_outputs(c, p, emission);
      break;
    case Stage::Feedback:  // a copy of the tap's output; none without a tap in range
      if (fused_outputs || !p.feeds_back_iteration())
        return unfused_output_cost(stage, p, emission, packed);
      c.read = 3 * kFloat;
      c.written = 3 * kFloat;
      c.planes = "R color 3; W color history 3";
      break;
    case Stage::Remodulate:
      if (fused_outputs) return unfused_output_cost(stage, p, emission, packed);
      c.read = (3 + 3 + e) * kFloat;  // filtered illumination, albedo, emission
      c.written = 3 * kFloat;
      c.ops = kRemodulate + (emission ? 3 : 0);
      c.planes = "R filtered 3, albedo 3, emission 3 (if any); W output 3";
      break;
    default:
      break;
  }
  return c;
}

StageCost fast_cost(Stage stage, const SvgfParams& p, const FrameTraits& f, bool surface) {
  const bool emission = f.emission;
  StageCost c;
  switch (stage) {
    case Stage::Sanitize:
      if (sanitize_fused(Mode::Fast, p, f)) break;  // in the demodulation's kernel
      return sanitize_cost(emission);
    case Stage::Demodulate:
      return fused_reprojection_cost(p, f, surface, sanitize_fused(Mode::Fast, p, f));
    case Stage::Variance:  // the same functor as exact mode's: guides on background only
      // length, accumulated (or its color and the moments), (packed guides)
      c.read = (1 + 4 + (packed_variance_plane(f) ? 0 : 1) + (surface ? 0 : 4)) * kFloat;
      c.written = 4 * kFloat;  // packed color + variance
      c.ops = kVarianceSteady;
      c.planes = "R length 1, accumulated 4 or its color 3 and moments 2 (background: + packed "
                 "guides 4); W packed 4";
      if (surface) c = with_young_variance(c, p, f, kFastVarianceTap, kFastVarianceYoung);
      break;
    case Stage::Atrous:
      if (p.iterations <= 0) break;
      // Per iteration: packed color + variance 4, packed guides 4, depth dx/dy 2 read; packed
      // 4 written, with the outputs fused into the last and the tap's iteration.
      // Background pixels pass through: packed and packed guides only.
      c.read = p.iterations * (surface ? 10 : 8) * kFloat;
      c.written = p.iterations * 4 * kFloat;
      c.ops = surface ? p.iterations * kFastAtrousIteration : 0;
      c.taps = surface ? p.iterations * kGridTaps : 0;
      c.planes =
          "per iteration R packed 4, packed guides 4, depth dx/dy 2 (background: packed, "
          "packed guides); W packed 4";
      c = with_fused_outputs(c, p, emission);
      break;
    case Stage::Feedback:    // rides on the tap's iteration, if any
    case Stage::Remodulate:  // rides on the last iteration, if any
      return unfused_output_cost(stage, p, emission, true);
    default:
      break;
  }
  return c;
}

StageCost pixel_cost(Mode mode, Stage stage, const SvgfParams& p, const FrameTraits& f,
                     bool surface) {
  switch (stage) {
    case Stage::Gradient:
    case Stage::GradientAtrous:
    case Stage::GradientLambda:
      if (gradient_fused(mode, p, f)) return fused_gradient_cost(stage, p, f, surface);
      return shared_cost(stage, p, f, surface);
    case Stage::SplitSum:
    case Stage::Taa:
      return shared_cost(stage, p, f, surface);
    default:
      return mode == Mode::Fast ? fast_cost(stage, p, f, surface)
                                : exact_cost(stage, p, f, surface);
  }
}

// A surface pixel's cost `a` and a background pixel's `b`, weighted by the surface fraction.
StageCost blend(const StageCost& a, const StageCost& b, double surface_fraction) {
  const double s = unit_share(surface_fraction);
  StageCost c = a;
  c.read = s * a.read + (1 - s) * b.read;
  c.written = s * a.written + (1 - s) * b.written;
  c.ops = s * a.ops + (1 - s) * b.ops;
  c.taps = s * a.taps + (1 - s) * b.taps;
  return c;
}

// --- the JBF (methods/jbf/weight.h, filter.h) -----------------------------------------------
// One tap of the full window, exact mode, every tap on a surface (the steady state; a tap
// without a surface stops after its depth test):
//   depth test 1; the squared distance converted to float 1;
//   jbf_guide_exponent 55:
//     color: difference 3, dot 5, times its scale 1 (9);
//     normal: dot 5, clamp to [-1, 1] 2, det_acos on its common branch (n_i . n_j > 1/2:
//       compare 1, sqrt(0.5 - 0.5 x) 3, det_asin_small 12 (x^2 1, polynomial 8, x + x (z p) 3),
//       times 2 1) 17, angle^2 times its scale 2 (26);
//     plane: position difference 3, length (dot 5 + sqrt) 6, len > 0 1, dot 5, division 1,
//       d^2 times its scale 2 (18);
//     the sum of the three 2;
//   jbf_weight: d2 times the coordinate scale plus the exponent 2, 0 - e 1, det_exp 24, the
//     max with 0 1 (28);
//   accumulation: weight 1, color 3 mul + 3 add 6 (7).
constexpr double kJbfExactTap = 1 + 1 + 55 + 28 + 7;  // 92
// Fast mode (FastArith) changes the exponential, the color accumulation (3 FMA) and the four
// dot products (3 FMA-counted instructions instead of 5: 8 fewer); its division is a reciprocal
// and a product (1 more); its square roots are one instruction, as counted above.
constexpr double kJbfFastTap = kJbfExactTap - kDetExp + kFastExp - 3 - 8 + 1;  // 60
// The a-trous form multiplies each tap by its B3 weights: their product and times it, 2; and
// weighs the centre by k0^2, 1 a pixel and pass.
constexpr double kJbfB3Tap = 2;
constexpr double kJbfB3Centre = 1;
// Per pixel and pass, outside the taps: surface test 1, centre sum 3, the normalization (3
// divisions exact; fast: one reciprocal and 3 products, 4).
constexpr double kJbfExactCentre = 1 + 3 + 3;
constexpr double kJbfFastCentre = 1 + 3 + 4;

// --- the wavelet filter (methods/wavelet/atrous.h) ----------------------------------------------
// One tap, exact mode: depth term |Z_p - Z_q| / sigma 3, luma term 3, normal_cosine (dot 5,
// saturate 2) 7, the normal power's squarings m (log2 sigma_N; another sigma_N is det_pow, one
// special function), the two max 2, exp_neg_sum ((-a) - b 2, det_exp 24) 26, times the normal
// weight 1, positive_part 2, times the binomial product 2 (each weight of the 7 and 9 taps
// kernels is a division too: + 2), accumulation 7.
constexpr double kWaveletExactTap = 3 + 3 + 7 + 2 + 2 + kDetExp + 1 + 2 + 2 + 7;  // 53 + m
// Fast: the dot 3 (mul + 2 FMA) with a free saturate, exp_neg_sum (add, scale, ex2) 3, no
// positive_part, accumulation 1 + 3 FMA.
constexpr double kWaveletFastTap = 3 + 3 + 3 + 2 + 3 + 1 + 2 + 4;  // 21 + m
// Per pixel and pass: surface test 1, 1 / (sigma_L Dev + eps) 3, centre weight k0^2 1, centre
// sum 3, the normalization 3 (exact) or 4 (fast).
constexpr double kWaveletExactCentre = 1 + 3 + 1 + 3 + 3;
constexpr double kWaveletFastCentre = 1 + 3 + 1 + 3 + 4;

// Per pass, both filters: a surface pixel reads its input color 3 and guides (JBF: depth,
// normal 3, position 3; wavelet: depth, normal 3, luma, deviation) and writes 3; a background
// pixel reads its depth and color and writes the color through.
constexpr int kJbfGuides = 7;
constexpr int kWaveletGuides = 6;
StageCost filter_pass(int guide_planes, int taps, double ops, bool surface) {
  StageCost c;
  c.read = (surface ? 3 + guide_planes : 1 + 3) * kFloat;
  c.written = 3 * kFloat;
  c.ops = surface ? ops : 0;
  c.taps = surface ? taps : 0;
  return c;
}

StageCost times(StageCost c, int passes) {
  c.read *= passes;
  c.written *= passes;
  c.ops *= passes;
  c.taps *= passes;
  return c;
}

// --- BMFR (methods/bmfr/) -------------------------------------------------------------------
// Accumulate and post are exact functors in both modes (CUDA compiles them with the exact flags);
// fast mode (FastArith) changes the regression and the weighted sum only.
// demodulated() (core/modulation.h), emission or zero: subtraction 3, max 3, albedo clamp 3,
// divisions 3; remodulated(): albedo clamp 3, product 3, sum 3.
constexpr double kBmfrDemodulate = 12;
constexpr double kBmfrRemodulate = 9;
// BilinearTaps::at (core/bilinear_taps.h): floors 2, conversions 2, fractions 2; a tap's
// weight() averages 2 (4 subtractions and 4 products over the four taps).
constexpr double kBilinearAt = 6;
constexpr double kBilinearWeight = 2;
// accumulate.h, a sample with its four taps accepted: demodulation 12; the sample test (surface
// 1, two min 2, compare 1) 4; x + motion with conversions 4; the taps' position 6; per tap the
// history test 1, |dp|^2 and |dn|^2 (3 + 5 each) 16, their limits 2, the weight 2, the
// accumulation (weight 1, length 2, color 6) 9: 30; normalization (test 1, divisions 4) 5;
// blend (n + 1, reciprocal, max 3; color 10) 13; history length (+1, min, select) 3; the
// accepted mask to float 1.
constexpr double kBmfrAccumulate = kBmfrDemodulate + 4 + 4 + kBilinearAt +
                                   4 * (1 + 16 + 2 + kBilinearWeight + 9) + 5 + 13 + 3 + 1;  // 168
// Not a sample (background): demodulation, the surface test 1, x + motion 4, the taps' position,
// the weight test 1, the length select 1, the mask 1.
constexpr double kBmfrAccumulateNoSample = kBmfrDemodulate + 1 + 4 + kBilinearAt + 1 + 1 + 1;  // 26
// post.h, four taps accepted: the mask to int 1, the taps' position 6, per tap the weight 2 and
// the accumulation (weight 1, color 6) 9; test 1; blend (1 / n, max 2; prev / total 3,
// f a + prev (1 - a) 10) 15; remodulation 9. Without history (background): the mask 1 and the
// remodulation.
constexpr double kBmfrPost = 1 + kBilinearAt + 4 * (kBilinearWeight + 7) + 1 + 15 + kBmfrRemodulate;
constexpr double kBmfrPostNoHistory = 1 + kBmfrRemodulate;
// features.h's scaled(): range 1, |range| > 1 2, (v - lo) / range 2 (counted with the division).
constexpr double kBmfrScaled = 5;
// weighted_sum.h on a surface pixel of a fitted block: the surface and rank tests 2, the squared
// positions 3, six scaled features, ten weight x feature products into the sum (exact: mul + add
// for 3 channels, 6; fast: 3 FMA), the clamp at 0 3. Background: the surface test.
constexpr double kBmfrWeightedSumBase = 2 + 3 + bmfr::kScaled * kBmfrScaled + 3;
constexpr double kBmfrWeightedSumExact = kBmfrWeightedSumBase + bmfr::kFeatures * 6;  // 98
constexpr double kBmfrWeightedSumFast = kBmfrWeightedSumBase + bmfr::kFeatures * 3;   // 68
// The regression (regression.h, block_qr.h), a row of a block. A block sum, min or max costs a
// row its operation (1023 of them over 1024 rows: four a thread, then the 255 of the tree).
//   fill: the row's sample test 1, squared positions 3, the select into 13 columns 13 (17);
//   ranges: 12 reductions (min and max of the six scaled features), each a test, a select and
//     the min/max (36);
//   scale and noise, a sample's row only: test 1, six scaled() 30, under the noise strategy nine
//     features' noise (the hash to float 1, times 2^-24 1, 2u - 1 2, times amount 1, added 1) 54;
//     another row: the test;
//   QR: the largest column norm, ten sums of squares (20); per kept column the norm below the
//     pivot (square, select, sum: 3); per pair (kept column, later column; 75 with all 10 kept
//     and 3 colors) the dot product (the u or v select, the above-pivot select, mul, sum: 4) and
//     the reflection's update (select, then mul + sub exact, one FMA fast: 3 or 2).
constexpr int kBmfrPairs =
    bmfr::kFeatures * (bmfr::kColumns - 1) - bmfr::kFeatures * (bmfr::kFeatures - 1) / 2;  // 75
constexpr double kBmfrRowFill = 1 + 3 + bmfr::kColumns;
constexpr double kBmfrRowRanges = 2 * bmfr::kScaled * 3;
constexpr double kBmfrRowScale = 1 + bmfr::kScaled * kBmfrScaled;
constexpr double kBmfrRowNoise = (bmfr::kFeatures - 1) * 6;
constexpr double kBmfrRowQr = 2 * bmfr::kFeatures + 3 * bmfr::kFeatures;
constexpr double kBmfrRowPairExact = 4 + 3, kBmfrRowPairFast = 4 + 2;
// A block's own work, on one thread: per kept column its norm (x0^2 + below 2, two tests 2,
// sqrt 1, the sign 1, u0 1, |u|^2 2; fast also the reciprocal of |u|^2 1) 9; per pair d + d and
// the scale by 1 / |u|^2 2; max/min |R_ii| (10 abs, 18 min/max, a division) 29; the scaled
// ranges' empty-block test 6; back substitution, per color 45 mul + sub and 10 divisions.
constexpr double kBmfrBlockExact = 9 * bmfr::kFeatures + 2 * kBmfrPairs + 29 + bmfr::kScaled +
                                   3 * (bmfr::kFeatures * (bmfr::kFeatures - 1) + bmfr::kFeatures);
constexpr double kBmfrBlockFast = kBmfrBlockExact + bmfr::kFeatures;
// Planes a row reads: its pixel's sample test (history length), normal 3, position 3 and
// pre-accumulated color 3, loaded for every row (zero rows select 0 after the load).
constexpr int kBmfrRowPlanes = 1 + 3 + 3 + 3;

StageCost bmfr_regression(Mode mode, const BmfrParams& p, double surface_fraction, int width,
                          int height) {
  const bool fast = mode == Mode::Fast;
  const bool noise = p.rank_strategy == BmfrRankStrategy::Noise;
  const double blocks = bmfr_blocks_per_px(width, height);
  const double rows = blocks * block::kRows;
  const double shared = kBmfrRowFill + kBmfrRowRanges + kBmfrRowQr +
                        kBmfrPairs * (fast ? kBmfrRowPairFast : kBmfrRowPairExact);
  const double sample_row = shared + kBmfrRowScale + (noise ? kBmfrRowNoise : 0);
  const double other_row = shared + 1;
  const double s = unit_share(surface_fraction);
  StageCost c;
  c.read = rows * kBmfrRowPlanes * kFloat;
  c.written = blocks * BmfrBlockData::kFloats * kFloat;
  c.ops = rows * (s * sample_row + (1 - s) * other_row) +
          blocks * (fast ? kBmfrBlockFast : kBmfrBlockExact);
  c.planes =
      "per block row R history length, normal 3, position 3, noisy 3; per block W weights 30, "
      "ranges 12, rank, condition";
  return c;
}

StageCost bmfr_pixel_cost(Mode mode, const std::string& name, bool emission, bool surface,
                          int width, int height) {
  const double e = emission ? 3 : 0;
  StageCost c;
  if (name == bmfr_stage::kAccumulate) {
    // Always: position 3, normal 3, albedo 3, color 3, emission, depth, motion 2; a sample also
    // reads the previous frame's length, position 3, normal 3 and noisy 3 at its taps.
    c.read = (3 + 3 + 3 + 3 + e + 1 + 2 + (surface ? 10 : 0)) * kFloat;
    // noisy 3, length, position 3, normal 3, the reprojection 3
    c.written = (3 + 1 + 3 + 3 + 3) * kFloat;
    c.ops = surface ? kBmfrAccumulate : kBmfrAccumulateNoSample;
    c.planes =
        "R position 3, normal 3, albedo 3, color 3, emission 3 (if any), depth, motion 2, previous "
        "length, position 3, normal 3, noisy 3 (background: not the previous); W noisy 3, length, "
        "position 3, normal 3, reprojection (x, y, taps) 3";
  } else if (name == bmfr_stage::kWeightedSum) {
    // A surface pixel reads its block's weights, ranges and rank once (counted a block).
    const double block_floats = BmfrBlockData::kWeights + BmfrBlockData::kRanges + 1;
    c.read = surface ? (1 + 3 + 3 + bmfr_blocks_per_px(width, height) * block_floats) * kFloat
                     : (1 + 3) * kFloat;
    c.written = 3 * kFloat;
    c.ops = surface ? (mode == Mode::Fast ? kBmfrWeightedSumFast : kBmfrWeightedSumExact) : 1;
    c.planes =
        "R depth, normal 3, position 3, per block weights 30, ranges 12, rank (background: depth, "
        "noisy 3); W filtered 3";
  } else if (name == bmfr_stage::kPost) {
    // Always the taps mask, filtered 3, albedo 3, emission; with history also the previous
    // position (x, y), the length and the previous accumulated output 3 at the taps.
    c.read = (1 + 3 + 3 + e + (surface ? 2 + 1 + 3 : 0)) * kFloat;
    c.written = (3 + 3) * kFloat;  // accumulated 3, output 3
    c.ops = surface ? kBmfrPost : kBmfrPostNoHistory;
    c.planes =
        "R taps mask, filtered 3, albedo 3, emission 3 (if any), previous x, y, length, previous "
        "accumulated 3 (background: the first four); W accumulated 3, output 3";
  }
  return c;
}

}  // namespace

double strata_per_px(int width, int height) {
  if (width <= 0 || height <= 0) return 1.0 / 9.0;
  const auto strata = [](int n) { return (n + kGradientStratum - 1) / kGradientStratum; };
  return static_cast<double>(strata(width)) * strata(height) /
         (static_cast<double>(width) * height);
}

StageCost taa_cost() {
  StageCost c;
  c.read = (2 + 3 + 3) * kFloat;
  c.written = (3 + 3) * kFloat;
  c.ops = kTaa;
  c.planes = "R motion 2, input 3 (3x3), history 3 (bilinear); W history 3, output 3";
  return c;
}

StageCost stage_cost(Mode mode, Stage stage, const SvgfParams& p, const FrameTraits& f) {
  if (stage == Stage::Upload) return upload_cost(f.emission, false, gradient_runs(p, f));
  if (stage == Stage::Download) return download_cost();
  return blend(pixel_cost(mode, stage, p, f, true), pixel_cost(mode, stage, p, f, false),
               f.surface_fraction);
}

StageCost stage_cost(Mode mode, Stage stage, const SvgfParams& p, bool emission,
                     double surface_fraction) {
  FrameTraits f;
  f.emission = emission;
  f.surface_fraction = surface_fraction;
  return stage_cost(mode, stage, p, f);
}

StageCost frame_cost(Mode mode, const SvgfParams& p, const FrameTraits& f) {
  StageCost total;
  for (int s = 0; s < static_cast<int>(Stage::Upload); ++s) {
    const StageCost c = stage_cost(mode, static_cast<Stage>(s), p, f);
    total.read += c.read;
    total.written += c.written;
    total.ops += c.ops;
  }
  return total;
}

StageCost frame_cost(Mode mode, const SvgfParams& p, bool emission, double surface_fraction) {
  FrameTraits f;
  f.emission = emission;
  f.surface_fraction = surface_fraction;
  return frame_cost(mode, p, f);
}

StageCost jbf_filter_cost(Mode mode, const JbfParams& p, double surface_fraction) {
  const bool fast = mode == Mode::Fast;
  const bool atrous = p.atrous();
  const int taps = atrous ? kGridTaps : (2 * p.radius + 1) * (2 * p.radius + 1) - 1;
  const double tap = (fast ? kJbfFastTap : kJbfExactTap) + (atrous ? kJbfB3Tap : 0);
  const double ops =
      taps * tap + (fast ? kJbfFastCentre : kJbfExactCentre) + (atrous ? kJbfB3Centre : 0);
  const int passes = atrous ? p.levels : 1;
  StageCost c = times(blend(filter_pass(kJbfGuides, taps, ops, true),
                            filter_pass(kJbfGuides, taps, ops, false), surface_fraction),
                      passes);
  c.planes = std::string(atrous ? "per level " : "") +
             "R color 3, depth 1, normal 3, position 3 (background: depth, color); W color 3";
  return c;
}

StageCost wavelet_atrous_cost(Mode mode, const WaveletParams& p, double surface_fraction) {
  const bool fast = mode == Mode::Fast;
  const int squarings = NormalPower<>::of(p.sigma_normal).squarings;
  const double power = squarings >= 0 ? squarings : 1;
  const double divisions = p.kernel_size >= 7 ? 1 : 0;  // binomial_weight's / 64, / 256
  const int taps = p.kernel_size * p.kernel_size - 1;
  const double tap = (fast ? kWaveletFastTap : kWaveletExactTap) + power + 2 * divisions;
  const double ops =
      taps * tap + (fast ? kWaveletFastCentre : kWaveletExactCentre) + divisions;
  StageCost c = times(blend(filter_pass(kWaveletGuides, taps, ops, true),
                            filter_pass(kWaveletGuides, taps, ops, false), surface_fraction),
                      p.iterations);
  c.planes =
      "per pass R color 3, depth 1, normal 3, luma 1, deviation 1 (background: depth, color); "
      "W color 3";
  return c;
}

double bmfr_blocks_per_px(int width, int height) {
  if (width <= 0 || height <= 0) return 0;
  double blocks = 0;
  for (int k = 0; k < bmfr::kOffsetCount; ++k) blocks += BmfrGrid::of(width, height, k).blocks();
  return blocks / bmfr::kOffsetCount / (static_cast<double>(width) * height);
}

std::optional<StageCost> bmfr_stage_cost(Mode mode, const BmfrParams& p, const std::string& name,
                                         bool emission, double surface_fraction, int width,
                                         int height) {
  if (name == kSanitizeStage) return sanitize_cost(emission, true);
  if (name == kUploadStage) return upload_cost(emission, true);
  if (name == kDownloadStage) return download_cost();
  if (name == bmfr_stage::kRegression)
    return bmfr_regression(mode, p, surface_fraction, width, height);
  if (name == bmfr_stage::kTaa) return p.taa ? std::optional<StageCost>(taa_cost()) : std::nullopt;
  if (name != bmfr_stage::kAccumulate && name != bmfr_stage::kWeightedSum &&
      name != bmfr_stage::kPost)
    return std::nullopt;
  return blend(bmfr_pixel_cost(mode, name, emission, true, width, height),
               bmfr_pixel_cost(mode, name, emission, false, width, height), surface_fraction);
}

std::optional<StageCost> method_stage_cost(const DenoiserConfig& d, const std::string& name,
                                           const FrameTraits& f) {
  const bool emission = f.emission;
  const double surface_fraction = f.surface_fraction;
  const int width = f.width, height = f.height;
  switch (d.method) {
    case Method::Svgf: {
      const std::optional<Stage> s = svgf_cost_stage(name);
      if (!s) return std::nullopt;
      // A split frame runs the per-signal stages twice on other planes: counted are the stages
      // it runs once.
      const bool once = *s == Stage::Gradient || *s == Stage::GradientAtrous ||
                        *s == Stage::GradientLambda || *s == Stage::SplitSum ||
                        *s == Stage::Taa || *s == Stage::Download;
      if (f.split && !once) return std::nullopt;
      return stage_cost(d.mode, *s, d.svgf, f);
    }
    case Method::Jbf:
    case Method::JbfAtrous: {
      const bool atrous = d.method == Method::JbfAtrous;
      if (name != (atrous ? jbf_stage::kAtrous : jbf_stage::kFilter) || (atrous && d.jbf.levels <= 0))
        return std::nullopt;
      JbfParams p = d.jbf;
      if (!atrous) p.levels = 0;
      return jbf_filter_cost(d.mode, p, surface_fraction);
    }
    case Method::Wavelet:
      if (name != wavelet_stage::kAtrous) return std::nullopt;
      return wavelet_atrous_cost(d.mode, d.wavelet, surface_fraction);
    case Method::Bmfr:
      return bmfr_stage_cost(d.mode, d.bmfr, name, emission, surface_fraction, width, height);
    case Method::Gaussian:
      return std::nullopt;
  }
  return std::nullopt;
}

bool frame_is_costed(Method m) { return m == Method::Svgf || m == Method::Bmfr; }

}  // namespace svgf::bench

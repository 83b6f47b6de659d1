// Bytes and operations per pixel of every SVGF stage, read off the functors in methods/svgf/:
// exact mode (both backends) and the SvgfFast flavor (fast mode, methods/svgf/flavors.h), counted
// by hand. tests/bench_stage_cost_test.cpp checks exact mode's plane counts (bytes) against the
// kernels; the operation counts, and everything of fast mode, are not checked (see
// stage_cost.h). Conventions (docs/benchmarks.md):
//  - bytes: every plane the kernel reads, once, plus every plane it writes, once; 4 bytes a
//    value. Neighbour taps are assumed served by the caches (that is the floor, not a model);
//  - the steady state: a surface pixel whose history is at least spatial_variance_history frames
//    old and whose four bilinear reprojection taps pass (the young-history 7x7 variance estimate
//    and the 3x3 reprojection fallback are rare after the first frames);
//  - ops: floating-point operations (add, mul, compare/select, min/max, abs, floor, conversion;
//    a division, square root or special function counts one) from the source. Fast mode is
//    counted with FMA contraction (a multiply-add is one op), as it is compiled.
#include "bench/stage_cost.h"

namespace svgf::bench {
namespace {

constexpr double kFloat = 4.0;

// --- exact mode (core/*.h) ----------------------------------------------------------------
// edge_stopping_weight (edge_stopping.h) with phi_normal = 128: dot 5, max 1, seven squarings 7;
// depth and luminance terms |a-b|/phi 3 + 3; two clamps and the sum 4; det_exp_nonpositive
// (det_math.h: clamp 1, k = floor(x log2e + 1/2) 6, Cody-Waite r 4, r^2 1, polynomial 10,
// y 3, two scale products 2) 27; times the normal weight and the > 0 select 2.
constexpr double kExactEdgeWeight = 13 + 6 + 4 + 27 + 2;  // 52
constexpr double kLuminance = 5;                          // 3 mul, 2 add
// One a-trous tap: the tap's luminance, the weight, tap_distance (3 + sqrt) and phi_z * d 5,
// the B3 product and times it 2, accumulation (weight 1, color 6, variance w*w*v + add 3) 10.
constexpr double kExactAtrousTap = kLuminance + kExactEdgeWeight + 5 + 2 + 10;  // 74
// Per pixel and iteration, outside the 24 taps: 3x3 variance prefilter 9 x 4 + division 37;
// phi_l 4; phi_z 5; centre luminance 5; centre terms 5; final normalization 5.
constexpr double kExactAtrousCentre = 37 + 4 + 5 + 5 + 5 + 5;  // 61
constexpr double kExactAtrousIteration = 24 * kExactAtrousTap + kExactAtrousCentre;

// reproject.h, four bilinear taps kept: position, range check, floors, fractions and the four
// bilinear weights 22; per tap the consistency test (fwidth 3, tolerance 3, depth test 3,
// normal dot and test 6) 15 and the accumulation 13; normalization 7; blend (luminance 5,
// length 2, both alphas 4, color 9, moments 7, variance 3) 30.
constexpr double kReproject = 22 + 4 * (15 + 13) + 7 + 30;  // 171
// Without history (background, disocclusion): the blend with alpha = 1, luminance 5, color 9,
// moments 7, variance 3, length and alpha selects 2.
constexpr double kReprojectNoHistory = 26;
// demodulate.h: three sanitize tests 12, albedo clamp 3, three divisions 3.
constexpr double kDemodulate = 18;
// variance.h on the steady-state path: the history and surface tests, then a copy.
constexpr double kVarianceSteady = 2;
// remodulate.h: albedo clamp 3, product 3 (plus 3 adds with emission).
constexpr double kRemodulate = 6;
// With emission planes, demodulate's subtraction and clamp: 3 + 3.
constexpr double kEmission = 6;

// --- fast mode (SvgfFast) -----------------------------------------------------------------
// One tap: luminance 3 and normal dot 3 (mul + 2 FMA each), max 1, seven squarings 7, depth and
// luminance terms 3 + 3, their sum 1, __expf 2 (scale + ex2), times normal weight 1, select 1,
// times B3 weight 1, inv_phi_z * inv_dist 1, accumulation (weight 1, color 3 FMA, w*w and FMA 2) 6.
constexpr double kFastAtrousTap = 3 + 3 + 1 + 7 + 3 + 3 + 1 + 2 + 1 + 1 + 1 + 1 + 6;  // 33
// Outside the taps: 3x3 prefilter (9 FMA, 9 weight adds, divide 2) 20, phi_l and its reciprocal
// 6, phi_z and its reciprocal 6, centre luminance 3, centre terms 5, final normalization 6.
constexpr double kFastAtrousCentre = 20 + 6 + 6 + 3 + 5 + 6;  // 46
constexpr double kFastAtrousIteration = 24 * kFastAtrousTap + kFastAtrousCentre;

bool tap_in_range(const SvgfParams& p) {
  return p.feedback_tap >= 0 && p.feedback_tap < p.iterations;
}

StageCost exact_cost(Stage stage, const SvgfParams& p, bool emission, bool surface) {
  const double e = emission ? 3 : 0;  // emission planes, when the frames have them
  StageCost c;
  switch (stage) {
    case Stage::Demodulate:
      c.read = (3 + 3 + e) * kFloat;  // color, albedo, emission
      c.written = 3 * kFloat;         // illumination
      c.ops = kDemodulate + (emission ? kEmission : 0);
      c.planes = "R color 3, albedo 3, emission 3 (if any); W illumination 3";
      break;
    case Stage::Reproject:
      // Surface: this frame's guides: mesh id, depth, depth dx/dy, normal 3, motion 2 (9); the
      // illumination 3; the previous guides at the taps: mesh id, depth, normal 3 (5); the
      // history: color 3, moments 2, length 1 (6). Background: depth and illumination only.
      c.read = (surface ? 9 + 3 + 5 + 6 : 1 + 3) * kFloat;
      c.written = (4 + 2 + 1) * kFloat;  // accumulated color + variance, moments 2, length
      c.ops = surface ? kReproject : kReprojectNoHistory;
      c.planes =
          "R guides 9, illumination 3, previous guides 5, history 6 (background: depth, "
          "illumination); W accumulated 4, moments 2, length 1";
      break;
    case Stage::Variance:
      // The history length alone sends an old surface pixel down the pass-through (the guides
      // are read on the young-history path only); a background pixel's length is 1, so it
      // reads its depth too.
      c.read = (1 + 4 + (surface ? 0 : 1)) * kFloat;  // length, accumulated, (depth)
      c.written = 4 * kFloat;                         // filtered[0] color + variance
      c.ops = kVarianceSteady;
      c.planes = "R length 1, accumulated 4 (background: + depth 1); W color + variance 4";
      break;
    case Stage::Atrous:
      // Per iteration: color + variance 4, depth, depth dx/dy, normal 3 (10 read; background
      // pixels pass through: color + variance and depth, 5); 4 written.
      c.read = p.iterations * (surface ? 10 : 5) * kFloat;
      c.written = p.iterations * 4 * kFloat;
      c.ops = surface ? p.iterations * kExactAtrousIteration : 0;
      c.planes =
          "per iteration R color + variance 4, depth 1, depth dx/dy 2, normal 3 (background: "
          "color + variance, depth); W color + variance 4";
      break;
    case Stage::Feedback:  // a plane copy: the tap's output, or the accumulation when none
      c.read = 3 * kFloat;
      c.written = 3 * kFloat;
      c.planes = "R color 3; W color history 3";
      break;
    case Stage::Remodulate:
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

StageCost fast_cost(Stage stage, const SvgfParams& p, bool emission, bool surface) {
  const double e = emission ? 3 : 0;
  StageCost c;
  switch (stage) {
    case Stage::Demodulate:  // demodulate + reproject + guide packing, one kernel
      // The illumination comes back from the thread's own write. Background pixels read depth
      // and normal only (to pack them), besides color and albedo.
      c.read = (3 + 3 + e + (surface ? 9 + 5 + 6 : 4)) * kFloat;
      c.written = (3 + 4 + 2 + 1 + 4) * kFloat;  // + packed guides (depth, normal)
      c.ops =
          kDemodulate + (emission ? kEmission : 0) + (surface ? kReproject : kReprojectNoHistory);
      c.planes =
          "R color 3, albedo 3, emission 3 (if any), guides 9, previous guides 5, history 6 "
          "(background: depth, normal); W illumination 3, accumulated 4, moments 2, length 1, "
          "packed guides 4";
      break;
    case Stage::Variance:  // the same functor as exact mode's: guides on background only
      c.read = (1 + 4 + (surface ? 0 : 4)) * kFloat;  // length, accumulated, (packed guides)
      c.written = 4 * kFloat;                         // packed color + variance
      c.ops = kVarianceSteady;
      c.planes = "R length 1, accumulated 4 (background: + packed guides 4); W packed 4";
      break;
    case Stage::Atrous:
      if (p.iterations <= 0) break;
      // Per iteration: packed color + variance 4, packed guides 4, depth dx/dy 2 read; packed
      // 4 written except by the last, which remodulates (albedo 3 in, output 3 out); the
      // feedback tap's iteration also writes the color history 3.
      // Background pixels pass through: packed and packed guides only.
      c.read = (p.iterations * (surface ? 10 : 8) + 3 + e) * kFloat;
      c.written = ((p.iterations - 1) * 4 + 3 + (tap_in_range(p) ? 3 : 0)) * kFloat;
      c.ops =
          (surface ? p.iterations * kFastAtrousIteration : 0) + kRemodulate + (emission ? 3 : 0);
      c.planes =
          "per iteration R packed 4, packed guides 4, depth dx/dy 2 (background: packed, "
          "packed guides); W packed 4 (not the last); last R albedo 3 (+ emission 3), W output "
          "3; tap W history 3";
      break;
    case Stage::Feedback:
      if (tap_in_range(p)) break;  // rides on the tap's iteration
      c.read = 3 * kFloat;
      c.written = 3 * kFloat;
      c.planes = "R accumulated color 3; W color history 3";
      break;
    case Stage::Remodulate:
      if (p.iterations > 0) break;  // rides on the last iteration
      c.read = (4 + 3 + e) * kFloat;
      c.written = 3 * kFloat;
      c.ops = kRemodulate + (emission ? 3 : 0);
      c.planes = "R packed 4, albedo 3, emission 3 (if any); W output 3";
      break;
    default:
      break;
  }
  return c;
}

StageCost pixel_cost(Mode mode, Stage stage, const SvgfParams& p, bool emission, bool surface) {
  return mode == Mode::Fast ? fast_cost(stage, p, emission, surface)
                            : exact_cost(stage, p, emission, surface);
}

}  // namespace

StageCost stage_cost(Mode mode, Stage stage, const SvgfParams& p, bool emission,
                     double surface_fraction) {
  if (stage == Stage::Upload) {  // kernels_cuda/cuda_backend.h: the input planes in one copy
    StageCost c;
    c.read = (15 + (emission ? 3 : 0)) * kFloat;
    c.planes =
        "host to device: color 3, albedo 3, normal 3, depth, depth dx/dy 2, motion 2, "
        "mesh id, emission 3 (if any)";
    return c;
  }
  if (stage == Stage::Download) {
    StageCost c;
    c.written = 3 * kFloat;
    c.planes = "device to host: output 3";
    return c;
  }
  const StageCost a = pixel_cost(mode, stage, p, emission, true);
  const StageCost b = pixel_cost(mode, stage, p, emission, false);
  const double s = surface_fraction < 0 ? 0 : (surface_fraction > 1 ? 1 : surface_fraction);
  StageCost c = a;
  c.read = s * a.read + (1 - s) * b.read;
  c.written = s * a.written + (1 - s) * b.written;
  c.ops = s * a.ops + (1 - s) * b.ops;
  return c;
}

StageCost frame_cost(Mode mode, const SvgfParams& p, bool emission, double surface_fraction) {
  StageCost total;
  for (int s = 0; s < static_cast<int>(Stage::Upload); ++s) {
    const StageCost c = stage_cost(mode, static_cast<Stage>(s), p, emission, surface_fraction);
    total.read += c.read;
    total.written += c.written;
    total.ops += c.ops;
  }
  return total;
}

}  // namespace svgf::bench

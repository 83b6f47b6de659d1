#pragma once
// A-SVGF's three stages (methods/svgf/gradient.h) as one block kernel over a tile of strata, for
// the default filter: at most one a-trous step and a lambda radius of at most 1. Each block
// computes the samples of its tile and a 2-stratum halo, with the guides at their pixels, into
// its scratch (shared memory on the GPU: a tap reads a neighbour's guides there, not nine
// times from the frame), filters the tile and a 1-stratum halo there, and writes the largest
// lambda of each of its strata: one launch whose intermediate strata never leave the block,
// instead of three launches over the whole stratum image (each a short chain of dependent loads
// with the GPU a third full: docs/benchmarks.md).
// The per-stratum work is the stages' own functions (GradientSamplesKernel::sample,
// GradientAtrousKernel::filtered, stratum_lambda, largest_lambda), so the lambda plane has the
// three stages' bits (tests/svgf_gradient_test.cpp; the stratum planes are not written). The
// packed flavors run it (methods/svgf/flavors.h: kFusedGradient); the CPU's SvgfExact keeps its
// vectorized rows of the three stages.
#include "core/det_math.h"
#include "core/hd.h"
#include "methods/svgf/gradient.h"

namespace svgf {

struct GradientTileKernel {
  // Strata a tile has along each side; the halo the samples need around it (one a-trous step of
  // one stratum, then the lambda's radius of one); the block's cells (<= its 1024 rows).
  static constexpr int kTile = 16;
  static constexpr int kHalo = 2;
  static constexpr int kSpan = kTile + 2 * kHalo;  // the samples' cells along a side
  static constexpr int kMid = kTile + 2;           // the filtered cells along a side
  static constexpr int kSampleCells = kSpan * kSpan;
  static constexpr int kMidCells = kMid * kMid;
  // The planes of the samples' cells: each stratum's sample and the guides at its guide pixel
  // (the a-trous taps read each neighbour's guides up to nine times: here once from the frame).
  enum Plane { kDelta, kNormalizer, kWeight, kDepth, kNormalX, kNormalY, kNormalZ, kMesh,
               kDepthFwidth, kPlanes };
  // The planes, then each filtered cell's own lambda.
  static constexpr int kOwnLambdas = kPlanes * kSampleCells;
  static constexpr int kScratchFloats = kOwnLambdas + kMidCells;

  GradientSamplesKernel samples;  // its planes unused: the values stay in the scratch
  GradientAtrousKernel atrous;    // step 1; its planes unused
  float* lambda = nullptr;        // out, one value a stratum
  int iterations = 1;             // a-trous steps: 0 or 1
  int radius = 1;                 // lambda radius: 0 or 1
  int strata_width = 0, strata_height = 0;

  // Whether the kernel computes what the three stages would for these settings.
  static bool handles(int iterations, int radius) {
    return iterations >= 0 && iterations <= 1 && radius >= 0 && radius <= 1;
  }
  SVGF_HD int tiles_x() const { return (strata_width + kTile - 1) / kTile; }
  int blocks() const { return tiles_x() * ((strata_height + kTile - 1) / kTile); }

  // The samples' cells, as the a-trous's input (GradientAtrousKernel::filtered): stratum (qx, qy)
  // at its cell of the span whose first stratum is (x0, y0).
  struct TileInput {
    const float* cells = nullptr;
    int x0 = 0, y0 = 0;
    SVGF_HD int cell(int qx, int qy) const { return (qy - y0) * kSpan + (qx - x0); }
    SVGF_HD float at(Plane plane, int qx, int qy) const {
      return cells[plane * kSampleCells + cell(qx, qy)];
    }
    SVGF_HD float delta(int qx, int qy) const { return at(kDelta, qx, qy); }
    SVGF_HD float normalizer(int qx, int qy) const { return at(kNormalizer, qx, qy); }
    SVGF_HD float weight(int qx, int qy) const { return at(kWeight, qx, qy); }
    SVGF_HD uint32_t mesh(int qx, int qy) const { return float_bits(at(kMesh, qx, qy)); }
    SVGF_HD EdgeSample edge(int qx, int qy) const {
      const Vec3 n = make_vec3(at(kNormalX, qx, qy), at(kNormalY, qx, qy), at(kNormalZ, qx, qy));
      return EdgeSample{at(kDepth, qx, qy), n, 0.f};
    }
    SVGF_HD float depth_fwidth(int qx, int qy) const { return at(kDepthFwidth, qx, qy); }
  };

  SVGF_HD_TEMPLATE
  template <class Block>
  SVGF_HD void operator()(const Block& b, int block) const {
    const int tx = (block % tiles_x()) * kTile, ty = (block / tiles_x()) * kTile;
    float* const cells = b.scratch();
    float* const own = cells + kOwnLambdas;
    const TileInput input{cells, tx - kHalo, ty - kHalo};
    const auto inside = [&](int sx, int sy) {
      return sx >= 0 && sy >= 0 && sx < strata_width && sy < strata_height;
    };
    // 1. The samples of the tile and its halo (strata outside the image are never read) and,
    //    where an a-trous step reads them, their guides, as the sanitize stage leaves them (it
    //    may run after this launch: pipeline.h).
    b.rows([&](int r) {
      if (r >= kSampleCells) return;
      const int sx = input.x0 + r % kSpan, sy = input.y0 + r / kSpan;
      if (!inside(sx, sy)) return;
      const GradientSamplesKernel::Sample m = samples.sample(sx, sy);
      float* const c = cells + r;
      c[kDelta * kSampleCells] = m.value.delta;
      c[kNormalizer * kSampleCells] = m.value.normalizer;
      c[kWeight * kSampleCells] = m.value.weight;
      if (iterations == 0) return;
      const int p = StratumGuides::pixel_at(samples.width, sx, sy, m.guide);
      const SanitizedGuide g = sanitized_stratum_guide(atrous.guides, p);
      c[kDepth * kSampleCells] = g.guide.edge.depth;
      c[kNormalX * kSampleCells] = g.guide.edge.normal.x;
      c[kNormalY * kSampleCells] = g.guide.edge.normal.y;
      c[kNormalZ * kSampleCells] = g.guide.edge.normal.z;
      c[kMesh * kSampleCells] = bits_float(g.guide.mesh);
      c[kDepthFwidth * kSampleCells] = g.depth_fwidth;
    });
    // 2. The own lambda of each stratum of the tile and a 1-stratum halo: of its filtered
    //    value, or (no a-trous step) of its sample.
    b.rows([&](int r) {
      if (r >= kMidCells) return;
      const int sx = tx - 1 + r % kMid, sy = ty - 1 + r / kMid;
      if (!inside(sx, sy)) return;
      StratumValue v;
      if (iterations > 0) {
        with_normal_power_of<ExactArith>(atrous.phi_normal, [&](const auto& power) {
          v = atrous.filtered(sx, sy, power, input);
        });
      } else {
        v = StratumValue{input.delta(sx, sy), input.normalizer(sx, sy), input.weight(sx, sy)};
      }
      own[r] = stratum_lambda(v.weight, v.delta, v.normalizer);
    });
    // 3. The largest own lambda around each stratum of the tile.
    const auto own_at = [&](int qx, int qy) { return own[(qy - ty + 1) * kMid + (qx - tx + 1)]; };
    b.rows([&](int r) {
      if (r >= kTile * kTile) return;
      const int sx = tx + r % kTile, sy = ty + r / kTile;
      if (!inside(sx, sy)) return;
      lambda[sy * strata_width + sx] =
          radius == 1 ? largest_lambda<1>(sx, sy, radius, strata_width, strata_height, own_at)
                      : largest_lambda<0>(sx, sy, radius, strata_width, strata_height, own_at);
    });
  }
};

}  // namespace svgf

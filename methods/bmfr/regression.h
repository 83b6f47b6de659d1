#pragma once
// BMFR stage 2: the regression, one block at a time (paper Sec. 4.2, Eq. 3-4). Each block of
// 32x32 pixels (methods/bmfr/blocks.h) solves the least-squares problem
//   min_w || F w - c ||   per color channel c,  F: 1024 rows x 10 features (features.h)
// by the Householder QR of block_qr.h. Rows of pixels that are not samples (no surface, or an
// albedo under the epsilon: history length 0, accumulate.h) are zero rows, which do not change
// the fit. Written once over a Block (core/block_reduce.h): every sum runs the fixed
// tree, so the CPU and CUDA agree bit for bit.
#include <cstdint>

#include "core/arith.h"
#include "core/block_reduce.h"
#include "core/views.h"
#include "methods/bmfr/block_qr.h"
#include "methods/bmfr/blocks.h"
#include "methods/bmfr/features.h"
#include "methods/bmfr/params.h"

namespace svgf {

// Per block: weights (kFeatures x 3), the scaled features' ranges (kScaled x {min, max}), the
// number of columns kept (the rank the QR found) and max |R_ii| / min |R_ii| (block_qr.h).
struct BmfrBlockData {
  static constexpr int kWeights = bmfr::kFeatures * 3;
  static constexpr int kRanges = bmfr::kScaled * 2;
  static constexpr int kFloats = kWeights + kRanges + 2;
  float* data = nullptr;  // kFloats per block
  SVGF_HD float* weights(int b) const { return data + b * kFloats; }
  SVGF_HD float* ranges(int b) const { return data + b * kFloats + kWeights; }
  SVGF_HD float* rank(int b) const { return data + b * kFloats + kWeights + kRanges; }
  SVGF_HD float* condition(int b) const { return data + b * kFloats + kWeights + kRanges + 1; }
};

template <class ArithT>
struct BmfrFit {
  using Arith = ArithT;
  static constexpr int kScratchFloats = bmfr::kColumns * block::kRows;
  // A column whose remaining norm is under this fraction of the largest column's is numerically
  // zero with either strategy (the noise keeps real features far above it).
  static constexpr float kZeroColumn = 1e-6f;

  BmfrGrid grid;
  GuideView guides;  // surface (depth > 0) and normals
  ConstRgbView position;
  ConstRgbView noisy;            // the pre-accumulated illumination
  const float* length = nullptr;  // its history length: 0 for pixels that are not samples
  BmfrBlockData out;
  int frame = 0;
  BmfrRankStrategy strategy = BmfrRankStrategy::Noise;
  float noise_amount = 0.01f;
  float skip_threshold = 1e-3f;

  SVGF_HD_TEMPLATE
  template <class Block>
  SVGF_HD void operator()(const Block& blk, int b) const {
    using namespace bmfr;
    float* const a = blk.scratch();  // column k at a + k * kRows
    // 1. The block's rows: features and color of the pixels fitted, zeros elsewhere.
    blk.rows([&](int r) {
      const int i = grid.pixel_of(b, r);
      const bool surface = length[i] > 0.f;
      const Vec3 n = guides.normal.load(i), p = position.load(i), c = noisy.load(i);
      for (int k = 0; k < kFeatures; ++k) a[k * block::kRows + r] = surface ? feature(k, n, p) : 0.f;
      a[kFeatures * block::kRows + r] = surface ? c.x : 0.f;
      a[(kFeatures + 1) * block::kRows + r] = surface ? c.y : 0.f;
      a[(kFeatures + 2) * block::kRows + r] = surface ? c.z : 0.f;
    });
    // 2. Positions and their squares to [0, 1] over the block's fitted rows (column 0 is 1
    //    exactly there), then the rank-deficiency noise on every feature but the constant.
    float lo[kScaled], hi[kScaled];
    const auto scaled_column = [&](int s) { return a + (kScaledFirst + s) * block::kRows; };
    blk.template reduce<kScaled>(block::MinOp{}, kScaled, [&](int r, int s) {
      return a[r] > 0.f ? scaled_column(s)[r] : 3.4e38f;
    }, lo);
    blk.template reduce<kScaled>(block::MaxOp{}, kScaled, [&](int r, int s) {
      return a[r] > 0.f ? scaled_column(s)[r] : -3.4e38f;
    }, hi);
    for (int s = 0; s < kScaled; ++s)
      if (lo[s] > hi[s]) lo[s] = hi[s] = 0.f;  // no surface in the block
    const bool noise = strategy == BmfrRankStrategy::Noise;
    blk.rows([&](int r) {
      if (!(a[r] > 0.f)) return;
      for (int s = 0; s < kScaled; ++s) {
        float& v = a[(kScaledFirst + s) * block::kRows + r];
        v = scaled(v, lo[s], hi[s]);
      }
      if (noise)
        for (int k = 1; k < kFeatures; ++k) {
          float& v = a[k * block::kRows + r];
          v = v + feature_noise(r, k, frame, noise_amount);
        }
    });
    const float keep = noise ? kZeroColumn : max_f(skip_threshold, kZeroColumn);

    // 3. The least-squares fit (block_qr.h), then the block's ranges and rank.
    const BlockFit fit = BlockLeastSquares<kFeatures, 3>::solve<Arith>(blk, a, keep * keep,
                                                                       out.weights(b));
    blk.once([&] {
      float* const range = out.ranges(b);
      for (int s = 0; s < kScaled; ++s) {
        range[2 * s] = lo[s];
        range[2 * s + 1] = hi[s];
      }
      *out.rank(b) = static_cast<float>(fit.rank);
      *out.condition(b) = fit.condition;
    });
  }
};

}  // namespace svgf

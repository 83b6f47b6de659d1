#pragma once
// BMFR stage 3: the weighted sum (paper Eq. 5; the authors' weighted_sum). Each surface pixel's
// output is its block's weights times its own features, scaled by the block's ranges, without
// the noise; negative results are clamped to 0. Pixels without a surface, and those of a block
// with nothing to fit (no sample in it: rank 0), keep the pre-accumulated illumination.
#include "core/views.h"
#include "methods/bmfr/blocks.h"
#include "methods/bmfr/features.h"
#include "methods/bmfr/regression.h"

namespace svgf {

template <class ArithT>
struct BmfrWeightedSum {
  using Arith = ArithT;
  BmfrGrid grid;
  GuideView guides;
  ConstRgbView position;
  ConstRgbView noisy;
  BmfrBlockData blocks;
  RgbView filtered;

  SVGF_HD void operator()(int x, int y) const {
    using namespace bmfr;
    const int i = guides.index(x, y);
    const int b = guides.is_surface(i) ? grid.block_of(x, y) : -1;
    if (b < 0 || !(*blocks.rank(b) > 0.f)) {
      filtered.store(i, noisy.load(i));
      return;
    }
    const float* w = blocks.weights(b);
    const float* range = blocks.ranges(b);
    const Vec3 n = guides.normal.load(i), p = position.load(i);
    Vec3 sum = make_vec3(0.f, 0.f, 0.f);
    for (int k = 0; k < kFeatures; ++k) {
      float f = feature(k, n, p);
      if (k >= kScaledFirst) f = scaled(f, range[2 * (k - kScaledFirst)], range[2 * (k - kScaledFirst) + 1]);
      sum = Arith::mad(make_vec3(w[3 * k], w[3 * k + 1], w[3 * k + 2]), f, sum);
    }
    filtered.store(i, max_v(sum, 0.f));
  }
};

}  // namespace svgf

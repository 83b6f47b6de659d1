#pragma once
// BMFR stage 3: the weighted sum (paper Eq. 5; the authors' weighted_sum). Each surface pixel's
// output is its block's weights times its own features, scaled by the block's ranges, without
// the noise; negative results are clamped to 0. Pixels without a surface keep the
// pre-accumulated illumination; so do the surface pixels that fall back, counted in the report
// (kTallyFilterFallback): those of a block with nothing to fit (no sample in it: rank 0), and
// any whose sum is not finite (weights can overflow on a block near the rank threshold with
// huge demodulated colors), so nothing non-finite reaches the output or the history.
#include <cstdint>

#include "core/tallies.h"
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

  // Returns kTallyFilterFallback for a surface pixel that fell back, else 0.
  SVGF_HD uint32_t operator()(int x, int y) const {
    using namespace bmfr;
    const int i = guides.index(x, y);
    if (!guides.is_surface(i)) {
      filtered.store(i, noisy.load(i));
      return 0u;
    }
    const int b = grid.block_of(x, y);
    if (!(*blocks.rank(b) > 0.f)) {
      filtered.store(i, noisy.load(i));
      return kTallyFilterFallback;
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
    const bool finite = is_finite(sum);
    filtered.store(i, finite ? max_v(sum, 0.f) : noisy.load(i));
    return finite ? 0u : kTallyFilterFallback;
  }
};

}  // namespace svgf

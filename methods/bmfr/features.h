#pragma once
// BMFR's features (paper Sec. 4.2, Eq. 2): the regression explains a block's accumulated noisy
// illumination as a linear combination of ten G-buffer features of its pixels,
//   1, n.x, n.y, n.z, p.x, p.y, p.z, p.x^2, p.y^2, p.z^2        (n normal, p world position)
// The last six are scaled per block to [0, 1] by the block's minimum and maximum (the authors'
// scale(): divided by the range only when the range exceeds 1), so the fit does not depend on
// where the scene sits in world space.
#include <cstdint>

#include "core/hd.h"
#include "core/vec.h"

namespace svgf::bmfr {

constexpr int kFeatures = 10;
constexpr int kScaledFirst = 4;  // features 4..9 are scaled per block
constexpr int kScaled = kFeatures - kScaledFirst;
constexpr int kColumns = kFeatures + 3;  // the features, then the color channels

// Feature k of a pixel, unscaled.
SVGF_HD float feature(int k, Vec3 normal, Vec3 position) {
  switch (k) {
    case 0: return 1.f;
    case 1: return normal.x;
    case 2: return normal.y;
    case 3: return normal.z;
    case 4: return position.x;
    case 5: return position.y;
    case 6: return position.z;
    case 7: return position.x * position.x;
    case 8: return position.y * position.y;
    default: return position.z * position.z;
  }
}

// The authors' scale(): to [0, 1] over the block's range when that range exceeds 1, else only
// shifted (dividing by a tiny range would blow the noise of a flat coordinate up).
SVGF_HD float scaled(float value, float lo, float hi) {
  const float range = hi - lo;
  return abs_f(range) > 1.f ? (value - lo) / range : value - lo;
}

// The rank-deficiency noise of feature k at row r of a block in frame `frame`: uniform in
// [-amount, amount), from an integer hash (PCG's output permutation) of the three, so both
// backends draw the same numbers. 24 random bits make an exactly representable fraction.
SVGF_HD float feature_noise(int r, int k, int frame, float amount) {
  uint32_t s = static_cast<uint32_t>(r) + 1024u * (static_cast<uint32_t>(k) +
                                                   16u * static_cast<uint32_t>(frame));
  s = s * 747796405u + 2891336453u;
  s = ((s >> ((s >> 28u) + 4u)) ^ s) * 277803737u;
  s = (s >> 22u) ^ s;
  const float u = static_cast<float>(s >> 8) * (1.f / 16777216.f);  // [0, 1)
  return amount * (2.f * u - 1.f);
}

}  // namespace svgf::bmfr

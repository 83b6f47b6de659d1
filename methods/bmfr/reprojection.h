#pragma once
// BMFR's reprojection (paper Sec. 4.1; the authors' accumulate_noisy_data): a pixel's previous
// position, from its motion vector, is read with the 2x2 bilinear taps around it; a tap counts
// when it lies in the image, held a surface, and its world position and normal are close to
// this pixel's. The pre-accumulation decides which taps count (a 4-bit mask) and the
// post-accumulation reuses the decision with the same weights.
#include "core/hd.h"
#include "core/vec.h"

namespace svgf {

struct BilinearTaps {
  int x0 = 0, y0 = 0;  // the top-left tap
  float fx = 0.f, fy = 0.f;

  // Around the point (px, py) in pixel coordinates (pixel centres at integers). |px|, |py| stay
  // below 2^25 for sanitized motion (core/sanitize.h), where floor_small is exact.
  SVGF_HD static BilinearTaps at(float px, float py) {
    BilinearTaps t;
    const float xf = floor_small(px), yf = floor_small(py);
    t.x0 = static_cast<int>(xf);
    t.y0 = static_cast<int>(yf);
    t.fx = px - xf;
    t.fy = py - yf;
    return t;
  }
  // Tap k = 0..3: (x0, y0), (x0 + 1, y0), (x0, y0 + 1), (x0 + 1, y0 + 1).
  SVGF_HD int x(int k) const { return x0 + (k & 1); }
  SVGF_HD int y(int k) const { return y0 + (k >> 1); }
  SVGF_HD float weight(int k) const {
    const float wx = (k & 1) ? fx : 1.f - fx;
    const float wy = (k >> 1) ? fy : 1.f - fy;
    return wx * wy;
  }
};

}  // namespace svgf

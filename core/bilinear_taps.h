#pragma once
// The 2x2 bilinear taps around a reprojected position, shared by the methods that read their
// history through them (SVGF's reproject, BMFR's pre- and post-accumulation): each decides
// which taps count and renormalizes the weights of those.
#include "core/hd.h"
#include "core/vec.h"

namespace svgf {

struct BilinearTaps {
  int x0 = 0, y0 = 0;  // the top-left tap
  float fx = 0.f, fy = 0.f;

  // Around the point (px, py) in pixel coordinates (pixel centres at integers); |px|, |py| must
  // stay below 2^31, where floor_small is exact (sanitized motion keeps them below 2^25).
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
  // (1 - fx)(1 - fy), fx (1 - fy), (1 - fx) fy, fx fy.
  SVGF_HD float weight(int k) const {
    const float wx = (k & 1) ? fx : 1.f - fx;
    const float wy = (k >> 1) ? fy : 1.f - fy;
    return wx * wy;
  }
};

}  // namespace svgf

#pragma once
// Binomial filter weights: row `size - 1` of Pascal's triangle over 2^(size - 1), for the
// a-trous grids of the suite (5 taps: the B3 spline of Dammertz et al., 1/16 1/4 3/8 1/4 1/16).
// Every weight is an exact float.
#include "core/hd.h"

namespace svgf {

// Weight of offset d (|d| <= size / 2) in a kernel of `size` = 3, 5, 7 or 9 taps per axis.
SVGF_HD float binomial_weight(int size, int d) {
  const int a = d < 0 ? -d : d;
  switch (size) {
    case 3: return a == 0 ? 0.5f : 0.25f;
    case 5: return a == 0 ? 0.375f : (a == 1 ? 0.25f : 0.0625f);
    case 7: return (a == 0 ? 20.f : a == 1 ? 15.f : a == 2 ? 6.f : 1.f) / 64.f;
    default: return (a == 0 ? 70.f : a == 1 ? 56.f : a == 2 ? 28.f : a == 3 ? 8.f : 1.f) / 256.f;
  }
}

}  // namespace svgf

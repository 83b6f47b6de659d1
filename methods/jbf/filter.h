#pragma once
// The joint bilateral filter's pass (methods/jbf/weight.h), in both of its forms:
//   full window: every pixel within `radius` (step 1), weighted by J alone (the homework's
//     Filter());
//   a-trous: the 5x5 grid at `step` = 2^level, J times the B3 spline weights (the homework's
//     bonus), the colors compared being the previous level's result.
// Sums in one fixed order; taps outside the image or without a surface are skipped; pixels
// without a surface (depth <= 0) pass through. The centre has J = 1.
#include "core/arith.h"
#include "core/binomial.h"
#include "core/views.h"
#include "methods/jbf/weight.h"

namespace svgf {

template <class Arith>
struct JbfPass {
  GuideView guides;  // depth (surface test), normal
  ConstRgbView position;
  ConstRgbView in;
  RgbView out;
  int radius = 16;  // taps either side: the window's radius, or 2 for the a-trous grid
  int step = 1;
  bool b3 = false;  // the a-trous form: J times the B3 spline weights
  JbfScales scales;

  SVGF_HD void operator()(int x, int y) const {
    const int i = guides.index(x, y);
    const Vec3 c = in.load(i);
    if (!(guides.depth[i] > 0.f)) {
      out.store(i, c);
      return;
    }
    const JbfSample center{c, guides.normal.load(i), position.load(i)};
    const float k0 = b3 ? binomial_weight(5, 0) * binomial_weight(5, 0) : 1.f;
    float weight = k0;
    Vec3 sum = c * k0;
    for (int dy = -radius; dy <= radius; ++dy) {
      for (int dx = -radius; dx <= radius; ++dx) {
        if (dx == 0 && dy == 0) continue;
        const int xq = x + dx * step, yq = y + dy * step;
        if (!guides.inside(xq, yq)) continue;
        const int j = guides.index(xq, yq);
        if (!(guides.depth[j] > 0.f)) continue;
        const Vec3 cq = in.load(j);
        const JbfSample tap{cq, guides.normal.load(j), position.load(j)};
        const float d2 = static_cast<float>((dx * dx + dy * dy) * step * step);
        float w = jbf_weight<Arith>(center, tap, d2, scales);
        if (b3) w = w * (binomial_weight(5, dx) * binomial_weight(5, dy));
        weight = weight + w;
        sum = Arith::mad(cq, w, sum);
      }
    }
    out.store(i, Arith::divide_by(weight)(sum));
  }
};

}  // namespace svgf

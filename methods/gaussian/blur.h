#pragma once
// One pass of the separable Gaussian blur, along x or y: out(p) = sum_k w_k in(p + k d) / sum_k w_k
// over the taps inside the image (the project's border rule: skip and renormalize), with
// w_k = exp(-k^2 / (2 sigma^2)). Written once; Arith picks exact (det_exp, IEEE division) or
// fast evaluation.
#include "core/arith.h"
#include "core/views.h"

namespace svgf {

template <class Arith = ExactArith>
struct GaussianPass {
  int width = 0;
  int height = 0;
  ConstRgbView in;
  RgbView out;
  int dx = 1, dy = 0;  // direction: (1, 0) rows, (0, 1) columns
  int radius = 6;
  float neg_inv_two_sigma2 = -0.125f;  // -1 / (2 sigma^2)

  SVGF_HD void operator()(int x, int y) const {
    float weight_sum = 0.f;
    Vec3 sum;
    for (int k = -radius; k <= radius; ++k) {
      const int xq = x + k * dx, yq = y + k * dy;
      if (xq < 0 || yq < 0 || xq >= width || yq >= height) continue;
      const float w = Arith::exp_nonpositive(static_cast<float>(k * k) * neg_inv_two_sigma2);
      weight_sum = weight_sum + w;
      sum = Arith::mad(in.load(yq * width + xq), w, sum);
    }
    out.store(y * width + x, Arith::divide_by(weight_sum)(sum));
  }
};

}  // namespace svgf

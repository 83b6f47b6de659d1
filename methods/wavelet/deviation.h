#pragma once
// Wavelet stages 2 and 3: the luminance weight's scale, Dev = clamp(g3x3(sqrt(|SqrLuma - L^2|)),
// epsilon, 1) (Nagi's README). Nagi takes SqrLuma and L from the path tracer's running means
// over many samples per pixel; a 1-spp frame has no per-pixel second moment, so here both are
// the 3x3 means around the pixel (the spatial estimate SVGF also falls back to): spread =
// sqrt(|mean(Y^2) - mean(Y)^2|), taps outside the image skipped. Exact arithmetic in every
// mode (two cheap passes; fast mode differs in the a-trous iterations only).
#include "core/binomial.h"
#include "core/det_math.h"
#include "core/views.h"

namespace svgf {

// spread_p = sqrt(|mean(Y^2) - mean(Y)^2|) over the 3x3 block around p inside the image.
struct WaveletSpreadKernel {
  int width = 0, height = 0;
  const float* luma = nullptr;
  float* spread = nullptr;
  SVGF_HD void operator()(int x, int y) const {
    float m1 = 0.f, m2 = 0.f, n = 0.f;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int xq = x + dx, yq = y + dy;
        if (xq < 0 || yq < 0 || xq >= width || yq >= height) continue;
        const float l = luma[yq * width + xq];
        m1 = m1 + l;
        m2 = m2 + l * l;
        n = n + 1.f;
      }
    m1 = m1 / n;
    m2 = m2 / n;
    const float d = m2 - m1 * m1;
    spread[y * width + x] = sqrtf(d < 0.f ? -d : d);
  }
};

// The 3x3 Gaussian ([1 2 1] x [1 2 1] / 16, renormalized at the border) of spread, clamped to
// [epsilon, 1].
struct WaveletDeviationKernel {
  int width = 0, height = 0;
  const float* spread = nullptr;
  float* deviation = nullptr;
  float epsilon = 0.01f;
  SVGF_HD void operator()(int x, int y) const {
    float sum = 0.f, weight = 0.f;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int xq = x + dx, yq = y + dy;
        if (xq < 0 || yq < 0 || xq >= width || yq >= height) continue;
        const float k = binomial_weight(3, dx) * binomial_weight(3, dy);
        sum = sum + k * spread[yq * width + xq];
        weight = weight + k;
      }
    const float g = sum / weight;
    deviation[y * width + x] = min_f(max_f(g, epsilon), 1.f);
  }
};

}  // namespace svgf

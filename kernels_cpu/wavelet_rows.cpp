#include "kernels_cpu/wavelet_rows.h"

#include <algorithm>

#include "kernels_cpu/row_tools.h"

namespace svgf::cpu {
namespace {

// One tap (offset j - i) for the pixels x0..x1 of a row; the body is the per-pixel kernel's.
template <class Power>
SVGF_TAP_LOOP void wavelet_tap(const float* __restrict depth, const float* __restrict nx,
                               const float* __restrict ny, const float* __restrict nz,
                               const float* __restrict luma, const float* __restrict cr,
                               const float* __restrict cg, const float* __restrict cb,
                               const float* __restrict inv_sigma_luma, float* __restrict sw,
                               float* __restrict sr, float* __restrict sg, float* __restrict sb,
                               int row, int offset, int x0, int x1, float inv_sigma_depth,
                               float kw, const Power& power) {
  for (int x = x0; x < x1; ++x) {
    const int i = row + x, j = row + offset + x;
    const WaveletCentre p{depth[i], make_vec3(nx[i], ny[i], nz[i]), luma[i], inv_sigma_luma[x]};
    const float w = wavelet_weight<RowExactArith>(p, depth[j], make_vec3(nx[j], ny[j], nz[j]),
                                               luma[j], inv_sigma_depth, power) *
                    kw;
    sw[x] = sw[x] + w;
    sr[x] = sr[x] + cr[j] * w;
    sg[x] = sg[x] + cg[j] * w;
    sb[x] = sb[x] + cb[j] * w;
  }
}

template <class Power>
void wavelet_row(const WaveletExactIteration& k, int y, RowScratch& s, const Power& power) {
  const GuideView& g = k.guides;
  const int w = g.width, h = g.height, row = y * w;
  float* __restrict inv_sigma_luma = s[0];
  const ColorSums sums(s, 1);
  const float k0 = binomial_weight(k.kernel_size, 0);
  sums.start(k.in, row, w, k0 * k0);  // the centre: W = 1
  for (int x = 0; x < w; ++x) inv_sigma_luma[x] = k.inv_sigma_luma(row + x);
  // The taps in the per-pixel kernel's order; a tap outside the image is skipped, as there.
  const int r = k.kernel_size / 2;
  for (int dy = -r; dy <= r; ++dy) {
    const int yq = y + dy * k.step;
    if (yq < 0 || yq >= h) continue;
    for (int dx = -r; dx <= r; ++dx) {
      if (dx == 0 && dy == 0) continue;
      const int off = dx * k.step;
      const int x0 = std::max(0, -off), x1 = std::min(w, w - off);
      if (x0 < x1)
        wavelet_tap(g.depth, g.normal.r, g.normal.g, g.normal.b, k.luma, k.in.r, k.in.g, k.in.b,
                    inv_sigma_luma, sums.weight, sums.r, sums.g, sums.b, row,
                    (yq - y) * w + off, x0, x1,
                    k.inv_sigma_depth,
                    binomial_weight(k.kernel_size, dx) * binomial_weight(k.kernel_size, dy),
                    power);
    }
  }
  sums.finish(g.depth, k.in, k.out, row, w);
}

}  // namespace

void run_wavelet_rows(const WaveletExactIteration& kernel, int width, int height) {
  with_normal_power(kernel.normal_power.phi, [&](const auto& power) {
    parallel_rows(height, [&](int y0, int y1) {
      RowScratch s(5, width);
      for (int y = y0; y < y1; ++y) wavelet_row(kernel, y, s, power);
    });
  });
}

}  // namespace svgf::cpu

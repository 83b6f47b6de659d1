#pragma once
// Wavelet stage 4: one pass of the edge-avoiding a-trous wavelet filter (Dammertz et al. 2010,
// Eq. 6-8, in the CIS 565 form of docs/wavelet.md): taps on a kernel_size^2 grid spaced `step`
// = 2^pass pixels apart, binomial weights h, each times
//   W = W_Z W_N W_L = exp(-|Z_p - Z_q| / (sigma_Z + eps) - |L_p - L_q| / (sigma_L Dev_p + eps))
//       * saturate(N_p . N_q)^sigma_N,
// L the luma of the demodulated noisy color and Dev its deviation (deviation.h), both fixed
// over the passes. Taps outside the image are skipped and the weights renormalized (the
// project's border rule); pixels without a surface (depth <= 0) pass through.
#include "core/arith.h"
#include "core/binomial.h"
#include "core/normal_weight.h"
#include "core/views.h"

namespace svgf {

// What the centre pixel p brings to the weights of its taps.
struct WaveletCentre {
  float depth;
  Vec3 normal;
  float luma;
  float inv_sigma_luma;  // 1 / (sigma_L Dev_p + eps)
};

// W = W_Z W_N W_L of the tap q (the binomial factor is the caller's). NaN guide data drops the
// term it is in (max) or zeroes the weight (the normal term). One function for the per-pixel
// kernel below and the CPU's vectorized rows (kernels_cpu/wavelet_rows.cpp).
template <class Arith, class Power>
SVGF_HD float wavelet_weight(const WaveletCentre& p, float depth_q, Vec3 normal_q, float luma_q,
                             float inv_sigma_depth, const Power& normal_power) {
  const float e_z = Arith::abs(p.depth - depth_q) * inv_sigma_depth;
  const float e_l = Arith::abs(p.luma - luma_q) * p.inv_sigma_luma;
  const float w_n = normal_power(normal_cosine<Arith>(p.normal, normal_q));
  return Arith::positive_part(Arith::exp_neg_sum(Arith::max(e_l, 0.f), Arith::max(e_z, 0.f)) *
                              w_n);
}

template <class Arith, class Power>
struct WaveletIteration {
  GuideView guides;
  ConstRgbView in;
  RgbView out;
  const float* luma = nullptr;
  const float* deviation = nullptr;
  int step = 1;
  int kernel_size = 5;
  float inv_sigma_depth = 1.f;  // 1 / (sigma_depth + epsilon)
  float sigma_luma = 4.f;
  float epsilon = 0.01f;
  Power normal_power;

  // 1 / (sigma_L Dev_p + eps), the only per-pixel term besides the guides.
  SVGF_HD float inv_sigma_luma(int i) const {
    return Arith::recip(sigma_luma * deviation[i] + epsilon);
  }

  SVGF_HD void operator()(int x, int y) const {
    const int i = guides.index(x, y);
    const Vec3 center = in.load(i);
    const float depth = guides.depth[i];
    if (!(depth > 0.f)) {  // no surface: nothing to filter against
      out.store(i, center);
      return;
    }
    const WaveletCentre p{depth, guides.normal.load(i), luma[i], inv_sigma_luma(i)};
    const int r = kernel_size / 2;
    const float k0 = binomial_weight(kernel_size, 0);
    float weight = k0 * k0;  // the centre: W = 1
    Vec3 sum = center * weight;
    for (int dy = -r; dy <= r; ++dy) {
      for (int dx = -r; dx <= r; ++dx) {
        if (dx == 0 && dy == 0) continue;
        const int xq = x + dx * step, yq = y + dy * step;
        if (!guides.inside(xq, yq)) continue;
        const int j = guides.index(xq, yq);
        const float w = wavelet_weight<Arith>(p, guides.depth[j], guides.normal.load(j), luma[j],
                                              inv_sigma_depth, normal_power) *
                        (binomial_weight(kernel_size, dx) * binomial_weight(kernel_size, dy));
        weight = weight + w;
        sum = Arith::mad(in.load(j), w, sum);
      }
    }
    out.store(i, Arith::divide_by(weight)(sum));
  }
};

}  // namespace svgf

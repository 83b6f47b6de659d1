#pragma once
// BMFR stage 1: pre-accumulation (paper Sec. 4.1). The frame's demodulated illumination is
// blended with its reprojected history: by max(1 / (n + 1), pre_alpha), n the history length
// read through the taps, so the first samples are averaged and the blend then settles at
// pre_alpha. The result is what the regression fits, and the next frame's history. Writes the
// reprojection (previous position and the accepted taps) for the post-accumulation, and keeps
// this frame's positions and normals for the next frame's tests. A tap (core/bilinear_taps.h)
// counts when it lies in the image, held a sample, and its world position and normal are close
// to this pixel's (the authors' accumulate_noisy_data): a 4-bit mask the post-accumulation reuses.
//
// A pixel is a sample (history length > 0: it reads and leaves history and enters the fit) when
// it has a surface and its albedo reaches the demodulation's epsilon in every channel. Below it
// the illumination is the color divided by the epsilon (up to 1000x): an outlier that the least
// squares would spread over the whole block and the history keep for many frames (a planted
// zero albedo left a 4 dB error 16 frames later, tests/bad_input_test.cpp); for consistent input
// (color = albedo x light) such a pixel carries no light to fit anyway.
#include "core/modulation.h"
#include "core/views.h"
#include "core/bilinear_taps.h"

namespace svgf {

// The reprojection as the post-accumulation reads it back.
struct BmfrReprojectionView {
  float* prev_x = nullptr;  // previous position, pixel coordinates
  float* prev_y = nullptr;
  float* accept = nullptr;  // the accepted taps, bit k for tap k (0 to 15, exact in a float)
};

struct BmfrAccumulate {
  GuideView guides;  // this frame: surface (depth > 0), normal, motion
  ConstRgbView position;
  ConstRgbView color, albedo, emission;  // emission optional
  // The previous frame's history.
  ConstRgbView prev_position, prev_normal, prev_noisy;
  const float* prev_length = nullptr;  // 0 where it had no sample
  // This frame's.
  RgbView position_out, normal_out, noisy;
  float* length = nullptr;
  BmfrReprojectionView reprojection;
  bool has_history = false;
  float alpha = 0.2f;
  float position_limit_sq = 0.01f;
  float normal_limit_sq = 1.f;
  float albedo_epsilon = 1e-3f;

  SVGF_HD void operator()(int x, int y) const {
    const int i = guides.index(x, y);
    const Vec3 p = position.load(i), n = guides.normal.load(i), al = albedo.load(i);
    const Vec3 c = demodulated(color.load(i), emission.load_or_zero(i), al, albedo_epsilon);
    const bool sample = guides.is_surface(i) && min_f(min_f(al.x, al.y), al.z) >= albedo_epsilon;
    const float px = static_cast<float>(x) + guides.motion_x[i];
    const float py = static_cast<float>(y) + guides.motion_y[i];
    const BilinearTaps taps = BilinearTaps::at(px, py);
    int accepted = 0;
    float total = 0.f, n_prev = 0.f;
    Vec3 c_prev = make_vec3(0.f, 0.f, 0.f);
    if (has_history && sample) {
      for (int k = 0; k < 4; ++k) {
        const int xs = taps.x(k), ys = taps.y(k);
        if (!guides.inside(xs, ys)) continue;
        const int j = guides.index(xs, ys);
        if (!(prev_length[j] > 0.f)) continue;  // no sample there
        const Vec3 dp = prev_position.load(j) - p, dn = prev_normal.load(j) - n;
        if (!(dot(dp, dp) < position_limit_sq) || !(dot(dn, dn) < normal_limit_sq)) continue;
        const float w = taps.weight(k);
        accepted |= 1 << k;
        total = total + w;
        n_prev = n_prev + w * prev_length[j];
        c_prev = c_prev + prev_noisy.load(j) * w;
      }
    }
    Vec3 result = c;
    float history = 0.f;
    if (total > 0.f) {
      n_prev = n_prev / total;
      c_prev = c_prev / total;
      const float a = max_f(1.f / (n_prev + 1.f), alpha);
      result = c * a + c_prev * (1.f - a);
      history = n_prev;
    }
    noisy.store(i, result);
    length[i] = sample ? min_f(history + 1.f, 255.f) : 0.f;  // the authors' 8-bit count
    position_out.store(i, p);
    normal_out.store(i, n);
    reprojection.prev_x[i] = px;
    reprojection.prev_y[i] = py;
    reprojection.accept[i] = static_cast<float>(accepted);
  }
};

}  // namespace svgf

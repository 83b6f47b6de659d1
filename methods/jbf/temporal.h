#pragma once
// The JBF's temporal accumulation (GAMES202 homework 5, assignment Sec. 2.2-2.3): each pixel
// follows its motion vector to the nearest pixel of the previous frame; the history is valid
// there when that pixel is inside the image and shows the same object (mesh id, a surface).
// The history is clamped, per channel, to mean +- k sigma of this frame's filtered color over
// the 7x7 block around the pixel, then blended: C = lerp(clamp(history), filtered, alpha).
// Invalid pixels (and the first frame) take the filtered color. The homework reprojects world
// positions through the objects' and the camera's matrices; the frame format here carries the
// renderer's motion vectors, which encode the same mapping (docs/jbf.md).
#include "core/vec.h"
#include "core/views.h"

namespace svgf {

struct JbfTemporal {
  GuideView guides;       // this frame: depth, motion, mesh ids
  GuideView prev_guides;  // the previous frame's: depth, mesh ids
  ConstRgbView filtered;
  ConstRgbView prev_accumulated;
  RgbView accumulated;  // the next frame's history
  RgbView output;
  bool has_history = false;
  float alpha = 0.2f;
  float clamp_k = 1.f;
  int clamp_radius = 3;  // 7x7 (the framework's kernelRadius 3)

  SVGF_HD void operator()(int x, int y) const {
    const int i = guides.index(x, y);
    const Vec3 c = filtered.load(i);
    Vec3 result = c;
    const int j = previous_pixel(x, y, i);
    if (j >= 0) {
      // Mean and standard deviation of the filtered color over the block, per channel.
      Vec3 m1 = make_vec3(0.f, 0.f, 0.f), m2 = m1;
      float n = 0.f;
      for (int dy = -clamp_radius; dy <= clamp_radius; ++dy)
        for (int dx = -clamp_radius; dx <= clamp_radius; ++dx) {
          if (!guides.inside(x + dx, y + dy)) continue;
          const Vec3 v = filtered.load(guides.index(x + dx, y + dy));
          m1 = m1 + v;
          m2 = m2 + v * v;
          n = n + 1.f;
        }
      const Vec3 mean = m1 / n;
      const Vec3 var = max_v(m2 / n - mean * mean, 0.f);
      const Vec3 spread = make_vec3(sqrtf(var.x), sqrtf(var.y), sqrtf(var.z)) * clamp_k;
      const Vec3 lo = mean - spread, hi = mean + spread;
      const Vec3 h = prev_accumulated.load(j);
      const Vec3 clamped = make_vec3(min_f(max_f(h.x, lo.x), hi.x), min_f(max_f(h.y, lo.y), hi.y),
                                     min_f(max_f(h.z, lo.z), hi.z));
      result = clamped + (c - clamped) * alpha;
    }
    accumulated.store(i, result);
    output.store(i, result);
  }

 private:
  // The previous frame's pixel this one came from, or -1 when there is no valid history.
  SVGF_HD int previous_pixel(int x, int y, int i) const {
    if (!has_history || !guides.is_surface(i)) return -1;
    const float px = static_cast<float>(x) + guides.motion_x[i];
    const float py = static_cast<float>(y) + guides.motion_y[i];
    if (!(abs_f(px) < 1e7f && abs_f(py) < 1e7f)) return -1;  // far outside, or NaN motion
    const int xp = static_cast<int>(floor_small(px + 0.5f));
    const int yp = static_cast<int>(floor_small(py + 0.5f));
    if (!prev_guides.inside(xp, yp)) return -1;
    const int j = prev_guides.index(xp, yp);
    if (!prev_guides.is_surface(j) || prev_guides.mesh_id[j] != guides.mesh_id[i]) return -1;
    return j;
  }
};

}  // namespace svgf

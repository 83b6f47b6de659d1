#pragma once
// Temporal anti-aliasing after remodulation, one stage for every method that offers it (BMFR's
// optional last stage, paper Sec. 4.4 and the authors' `taa` kernel; SVGF's in issue 12). The
// frame's output is blended with the previous TAA output, reprojected through the motion
// vectors with bilinear taps (those inside the image, renormalized) and first clamped to this
// frame's neighbourhood in YCoCg, so history that no longer belongs to the pixel (a moved
// object, changed light) cannot ghost:
//   bounds = (3x3 box min/max + 5-tap cross min/max) / 2   (the authors' rounder box)
//   out    = max(alpha * current + (1 - alpha) * clamp(history), 0)
// Without history, or with no tap in the image, the pixel passes through. YCoCg here is the
// authors' unnormalized one (Y = r + 2g + b, Co = 2r - 2b, Cg = 2g - r - b; back with 1/4).
// The frame format has no sub-pixel jitter (docs/frame-format.md), so none is undone.
#include "core/bilinear_taps.h"
#include "core/hd.h"
#include "core/vec.h"
#include "core/views.h"

namespace svgf {

SVGF_HD Vec3 rgb_to_ycocg(Vec3 c) {
  return make_vec3((c.x + 2.f * c.y) + c.z, 2.f * c.x - 2.f * c.z, (2.f * c.y - c.x) - c.z);
}
SVGF_HD Vec3 ycocg_to_rgb(Vec3 v) {
  return make_vec3(0.25f * ((v.x + v.y) - v.z), 0.25f * (v.x + v.z), 0.25f * ((v.x - v.y) - v.z));
}

struct TemporalAntiAliasing {
  GuideView guides;       // size and motion (prev = (x, y) + motion)
  ConstRgbView current;   // this frame's output before TAA
  ConstRgbView history;   // the previous frame's TAA output
  RgbView history_out;    // this frame's TAA output: the next frame's history
  RgbView output;         // and the frame's output
  bool has_history = false;
  float alpha = 0.2f;

  SVGF_HD void operator()(int x, int y) const {
    const int i = guides.index(x, y);
    const Vec3 c = current.load(i);
    Vec3 result = c;
    if (has_history) {
      const BilinearTaps taps = BilinearTaps::at(static_cast<float>(x) + guides.motion_x[i],
                                                 static_cast<float>(y) + guides.motion_y[i]);
      float total = 0.f;
      Vec3 prev = make_vec3(0.f, 0.f, 0.f);
      for (int k = 0; k < 4; ++k) {
        if (!guides.inside(taps.x(k), taps.y(k))) continue;
        const float w = taps.weight(k);
        total = total + w;
        prev = prev + history.load(guides.index(taps.x(k), taps.y(k))) * w;
      }
      if (total > 0.f) {
        const Vec3 big = make_vec3(3.4e38f, 3.4e38f, 3.4e38f);
        Vec3 box_lo = big, box_hi = big * -1.f, cross_lo = big, cross_hi = big * -1.f;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            if (!guides.inside(x + dx, y + dy)) continue;
            const Vec3 v = rgb_to_ycocg(current.load(guides.index(x + dx, y + dy)));
            box_lo = min_v(box_lo, v);
            box_hi = max_v(box_hi, v);
            if (dx == 0 || dy == 0) {
              cross_lo = min_v(cross_lo, v);
              cross_hi = max_v(cross_hi, v);
            }
          }
        const Vec3 lo = (box_lo + cross_lo) * 0.5f, hi = (box_hi + cross_hi) * 0.5f;
        const Vec3 h = rgb_to_ycocg(prev / total);
        const Vec3 clamped =
            ycocg_to_rgb(make_vec3(min_f(max_f(h.x, lo.x), hi.x), min_f(max_f(h.y, lo.y), hi.y),
                                   min_f(max_f(h.z, lo.z), hi.z)));
        result = max_v(c * alpha + clamped * (1.f - alpha), 0.f);
      }
    }
    history_out.store(i, result);
    output.store(i, result);
  }
};

}  // namespace svgf

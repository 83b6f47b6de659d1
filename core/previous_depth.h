#pragma once
// The view depth that the surface point seen at pixel (x, y) had in the previous frame's
// camera: what a reprojection should compare with the previous frame's depth there. The
// current depth is not it once the camera moves: a turn of 3.5 degrees changes the depth of a
// wall point by up to 7%, which a relative depth test of 3% reads as a disocclusion (docs/
// svgf.md, "Reprojection under camera motion"). NRD's 2.5D motion vectors carry the same view-Z
// change for the same reason.
//
// For a perspective or orthographic projection the point at depth d behind pixel (x, y) is
// affine in d, and so is its depth in any other affine view, with coefficients affine in x and
// y: depth_then = d * (s0 + s1 x + s2 y) + (t0 + t1 x + t2 y). The host derives the six
// numbers once a frame from the two cameras; a pixel evaluates them in a fixed order of float
// operations (the same bits on the CPU and the GPU).
#include <array>
#include <cmath>

#include "core/camera.h"
#include "core/hd.h"
#include "core/matrix4.h"

namespace svgf {

struct PreviousViewDepth {
  float s0 = 1.f, s1 = 0.f, s2 = 0.f;  // the depth's factor
  float t0 = 0.f, t1 = 0.f, t2 = 0.f;  // the offset
  // The default: the depth as it is (no camera, a still camera, a camera this cannot model).

  SVGF_HD float at(int x, int y, float depth) const {
    const float fx = static_cast<float>(x), fy = static_cast<float>(y);
    return depth * ((s0 + s1 * fx) + s2 * fy) + ((t0 + t1 * fx) + t2 * fy);
  }

  bool is_identity() const {
    return s0 == 1.f && s1 == 0.f && s2 == 0.f && t0 == 0.f && t1 == 0.f && t2 == 0.f;
  }

  // From the previous frame's camera to the current one's, for an image of width x height
  // (docs/frame-format.md: pixel centres at x + 0.5, y + 0.5, y down; OpenGL clip space). The
  // identity where the cameras are the same, or where they are not what the model covers (a
  // projection whose w depends on x or y, a singular or non-affine view, non-finite results).
  static PreviousViewDepth between(const Camera& previous, const Camera& current, int width,
                                   int height) {
    const PreviousViewDepth identity;
    if (previous.world_to_view == current.world_to_view || width <= 0 || height <= 0)
      return identity;
    const auto& P = current.view_to_clip;
    // Matrices made by multiplying others (an importer's) carry rounding residue where the
    // model wants zeros: below 1e-6 of the row's scale it is taken as zero.
    const auto tiny = [](double v, double scale) { return std::fabs(v) <= 1e-6 * scale; };
    const double w_scale = std::fabs(P[14]) + std::fabs(P[15]);
    if (!tiny(P[12], w_scale) || !tiny(P[13], w_scale)) return identity;
    // Previous view * current view^-1 takes a current view point to the previous view; its row
    // 2 gives the previous depth, and its row 3 must be (0, 0, 0, 1) (affine views).
    Matrix4 view_to_world;
    if (!invert(to_double(current.world_to_view), view_to_world)) return identity;
    const Matrix4 M = multiply(to_double(previous.world_to_view), view_to_world);
    if (!tiny(M[12], 1.0) || !tiny(M[13], 1.0) || !tiny(M[14], 1.0) || !tiny(M[15] - 1.0, 1.0))
      return identity;
    const double m[4] = {M[8], M[9], M[10], M[11]};

    // A view point (vx, vy, -d) lands on ndc (nx, ny) where P's rows 0 and 1 over its w
    // (P[14] (-d) + P[15]) give them: a 2x2 system in vx, vy, affine in d.
    const auto p = [&](int r, int c) { return static_cast<double>(P[r * 4 + c]); };
    const double det2 = p(0, 0) * p(1, 1) - p(0, 1) * p(1, 0);
    if (!(std::fabs(det2) > 0.0)) return identity;
    const double a00 = p(1, 1) / det2, a01 = -p(0, 1) / det2;
    const double a10 = -p(1, 0) / det2, a11 = p(0, 0) / det2;
    // Depth factor S and offset T at pixel (x, y).
    const auto at_pixel = [&](double x, double y, double& S, double& T) {
      const double nx = (2.0 * x + 1.0) / width - 1.0;
      const double ny = 1.0 - (2.0 * y + 1.0) / height;
      const double cx = p(0, 2) - nx * p(3, 2), cy = p(1, 2) - ny * p(3, 2);  // per unit d
      const double ex = nx * p(3, 3) - p(0, 3), ey = ny * p(3, 3) - p(1, 3);  // constant
      const double ax = a00 * cx + a01 * cy, ay = a10 * cx + a11 * cy;
      const double bx = a00 * ex + a01 * ey, by = a10 * ex + a11 * ey;
      S = -(m[0] * ax + m[1] * ay - m[2]);
      T = -(m[0] * bx + m[1] * by + m[3]);
    };
    double S00, T00, S10, T10, S01, T01;
    at_pixel(0, 0, S00, T00);
    at_pixel(1, 0, S10, T10);
    at_pixel(0, 1, S01, T01);
    PreviousViewDepth r;
    r.s0 = static_cast<float>(S00);
    r.s1 = static_cast<float>(S10 - S00);
    r.s2 = static_cast<float>(S01 - S00);
    r.t0 = static_cast<float>(T00);
    r.t1 = static_cast<float>(T10 - T00);
    r.t2 = static_cast<float>(T01 - T00);
    for (float v : {r.s0, r.s1, r.s2, r.t0, r.t1, r.t2})
      if (!std::isfinite(v)) return identity;
    return r;
  }
};

}  // namespace svgf

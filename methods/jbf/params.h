#pragma once
// The joint bilateral filter of GAMES202 homework 5 (real-time ray tracing denoising): its
// spatial filter, in full-window and a-trous form, and its temporal accumulation. Defaults are the homework framework's
// (src/denoiser.h and Filter() in src/denoiser.cpp of the framework skeleton; docs/jbf.md).
#include <cmath>
#include <stdexcept>
#include <string>

namespace svgf {

struct JbfParams {
  // Full window: taps within `radius` pixels either side (the framework's kernelRadius 16, a
  // 33x33 window).
  int radius = 16;
  // The a-trous form (the homework's bonus): `levels` passes of 5x5 taps at steps 1, 2, 4, ...;
  // 0 means the full window. 4 levels reach 30 px, the window's 16 and beyond (docs/jbf.md).
  int levels = 0;
  float sigma_coord = 32.f;   // m_sigmaCoord: pixels
  float sigma_color = 0.6f;   // m_sigmaColor: RGB distance of the noisy color
  float sigma_normal = 0.1f;  // m_sigmaNormal: radians between the normals
  float sigma_plane = 0.1f;   // m_sigmaPlane: distance from the tangent plane, over distance
  // Temporal accumulation (methods/jbf/temporal.h): the blend toward this frame's filtered color
  // (m_alpha; 1 turns the history off) and the clamp's k (m_colorBoxK).
  float alpha = 0.2f;
  float clamp_k = 1.f;

  bool atrous() const { return levels > 0; }
  // std::invalid_argument naming the flag.
  void validate() const {
    auto fail = [](const std::string& what) { throw std::invalid_argument("jbf: " + what); };
    if (radius < 1 || radius > 64)
      fail("--jbf-radius must be in [1, 64], got " + std::to_string(radius));
    if (levels < 0 || levels > 10)
      fail("--jbf-levels must be in [0, 10], got " + std::to_string(levels));
    auto check = [&](float v, const char* flag) {
      if (!(std::isfinite(v) && v > 0.f))
        fail(std::string(flag) + " must be finite and > 0, got " + std::to_string(v));
    };
    check(sigma_coord, "--jbf-sigma-coord");
    check(sigma_color, "--jbf-sigma-color");
    check(sigma_normal, "--jbf-sigma-normal");
    check(sigma_plane, "--jbf-sigma-plane");
    if (!(alpha > 0.f && alpha <= 1.f))
      fail("--jbf-alpha must be in (0, 1], got " + std::to_string(alpha));
    if (!(std::isfinite(clamp_k) && clamp_k >= 0.f))
      fail("--jbf-clamp-k must be finite and >= 0, got " + std::to_string(clamp_k));
  }
};

}  // namespace svgf

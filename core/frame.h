#pragma once
// One rendered frame as the denoisers consume it (docs/frame-format.md describes the file form).
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/camera.h"
#include "core/image.h"
#include "core/views.h"

namespace svgf {

constexpr int kGradientStratum = 3;  // A-SVGF strata are 3x3 pixels

struct Frame {
  int index = 0;           // frame number within its sequence
  Image color;             // 3: noisy radiance, linear HDR (1 spp)
  Image albedo;            // 3: surface albedo at the primary hit (1 on emitters and background)
  Image normal;            // 3: world-space unit shading normal (0 on background)
  Image position;          // 3: world-space position of the primary hit (0 on background)
  Image depth;             // 1: linear view depth (> 0 on surfaces, 0 on background)
  Image depth_gradient;    // 2: d depth/dx, d depth/dy in depth units per pixel
  Image motion;            // 2: pixels to the previous frame: prev = (x, y) + motion
  std::vector<uint32_t> mesh_id;  // object id at the primary hit; 0 on background
  Image emission;          // 3, optional: radiance emitted at the primary hit (part of color)
  Image reference;         // 3, optional: converged radiance for quality measurement
  Image direct;            // 3, optional: direct illumination of `color`
  Image indirect;          // 3, optional: indirect illumination of `color`
  Image gradient;          // 3, optional: A-SVGF gradient samples (docs/frame-format.md):
                           // previous and current luminance of one re-shaded sample per
                           // kGradientStratum^2 stratum, and 1 at the pixel that holds it
  Camera camera;

  int width() const { return color.width(); }
  int height() const { return color.height(); }
  bool has_reference() const { return !reference.empty(); }

  // Allocates every required channel at this size (zero-filled); optional ones stay empty.
  void allocate(int width, int height) {
    color = Image(width, height, 3);
    albedo = Image(width, height, 3);
    normal = Image(width, height, 3);
    position = Image(width, height, 3);
    depth = Image(width, height, 1);
    depth_gradient = Image(width, height, 2);
    motion = Image(width, height, 2);
    mesh_id.assign(static_cast<size_t>(width) * height, 0u);
  }

  GuideView guides() const {
    GuideView g;
    g.width = width();
    g.height = height();
    g.depth = depth.plane(0);
    g.depth_dx = depth_gradient.plane(0);
    g.depth_dy = depth_gradient.plane(1);
    g.normal = normal.rgb();
    g.mesh_id = mesh_id.data();
    g.motion_x = motion.plane(0);
    g.motion_y = motion.plane(1);
    return g;
  }
};

// Throws std::invalid_argument naming the first channel whose size or channel count is wrong.
inline void check_frame_consistent(const Frame& f) {
  const int w = f.width(), h = f.height();
  auto check = [&](const Image& im, const char* name, int channels, bool optional) {
    if (optional && im.empty()) return;
    if (im.width() != w || im.height() != h || im.channels() != channels)
      throw std::invalid_argument(std::string("frame ") + std::to_string(f.index) + ": channel '" +
                                  name + "' is " + std::to_string(im.width()) + "x" +
                                  std::to_string(im.height()) + "x" +
                                  std::to_string(im.channels()) + ", expected " +
                                  std::to_string(w) + "x" + std::to_string(h) + "x" +
                                  std::to_string(channels));
  };
  if (w <= 0 || h <= 0 || f.color.channels() != 3)
    throw std::invalid_argument("frame " + std::to_string(f.index) + ": no color channel");
  check(f.albedo, "albedo", 3, false);
  check(f.normal, "normal", 3, false);
  check(f.position, "position", 3, true);
  check(f.depth, "depth", 1, false);
  check(f.depth_gradient, "depth_gradient", 2, false);
  check(f.motion, "motion", 2, false);
  check(f.emission, "emission", 3, true);
  check(f.reference, "reference", 3, true);
  check(f.direct, "direct", 3, true);
  check(f.indirect, "indirect", 3, true);
  check(f.gradient, "gradient", 3, true);
  if (f.mesh_id.size() != f.color.pixel_count())
    throw std::invalid_argument("frame " + std::to_string(f.index) +
                                ": channel 'mesh_id' has the wrong size");
}

}  // namespace svgf

#include "app/input_warnings.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace svgf::app {

std::vector<InputWarning> input_warnings(const Frame& f, const Camera* previous_camera) {
  std::vector<InputWarning> w;
  const size_t n = f.depth.pixel_count();
  size_t surface = 0, first = n;
  bool albedo_varies = false, motion_zero = true;
  for (size_t i = 0; i < n; ++i) {
    if (!(f.depth.plane(0)[i] > 0.f)) continue;
    if (surface++ == 0) first = i;
    for (int c = 0; c < 3; ++c)
      albedo_varies = albedo_varies || f.albedo.plane(c)[i] != f.albedo.plane(c)[first];
    motion_zero = motion_zero && f.motion.plane(0)[i] == 0.f && f.motion.plane(1)[i] == 0.f;
  }
  if (surface == 0) {
    w.push_back({"no-surface",
                 "no pixel has depth > 0: every pixel counts as background and passes through "
                 "unfiltered (depth 0 means no geometry; give the view depth where there is "
                 "some, docs/frame-format.md)"});
    return w;
  }
  if (!albedo_varies && surface > 1) {
    char v[96];
    std::snprintf(v, sizeof v, "(%g, %g, %g)", f.albedo.plane(0)[first], f.albedo.plane(1)[first],
                  f.albedo.plane(2)[first]);
    w.push_back({"constant-albedo",
                 std::string("albedo is ") + v + " at every surface pixel: texture is not "
                 "demodulated and gets filtered as noise (give the albedo buffer if the "
                 "renderer has one)"});
  }
  if (previous_camera && motion_zero) {
    float moved = 0.f;
    for (int k = 0; k < 16; ++k)
      moved = std::max(moved, std::fabs(f.camera.world_to_view[k] -
                                        previous_camera->world_to_view[k]));
    if (moved > 1e-5f)
      w.push_back({"zero-motion",
                   "the camera moved (world_to_view changed since the previous frame) but every "
                   "motion vector is 0: the history is read from where the pixel is now, not "
                   "where it was (docs/frame-format.md, motion)"});
  }
  return w;
}

}  // namespace svgf::app

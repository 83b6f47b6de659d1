#pragma once
// The bad-sample rule every method applies to its noisy input (docs/architecture.md).
#include "core/hd.h"
#include "core/views.h"

namespace svgf {

// A color component that is NaN, +-Inf or negative is replaced by 0 (no light), and the pixel
// is counted. Radiance is never negative, and 0 is the one value that cannot brighten or darken
// a history beyond what a dark sample would.
SVGF_HD float sanitize_radiance(float v, bool& replaced) {
  const bool ok = v >= 0.f && is_finite(v);
  replaced = replaced || !ok;
  return ok ? v : 0.f;
}

SVGF_HD Vec3 sanitize_radiance(Vec3 c, bool& replaced) {
  return make_vec3(sanitize_radiance(c.x, replaced), sanitize_radiance(c.y, replaced),
                   sanitize_radiance(c.z, replaced));
}

// The color with bad samples replaced; returns true where a sample was (engines count these).
struct SanitizeKernel {
  int width = 0;
  ConstRgbView color;
  RgbView out;
  SVGF_HD bool operator()(int x, int y) const {
    const int i = y * width + x;
    bool replaced = false;
    out.store(i, sanitize_radiance(color.load(i), replaced));
    return replaced;
  }
};

}  // namespace svgf

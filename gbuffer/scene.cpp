#include "gbuffer/scene.h"

#include <cmath>

namespace svgf::gbuffer {

Vec3 pattern_albedo(const Material& m, float u, float v) {
  const float fu = u / m.scale;
  const float fv = v / m.scale;
  const float iu = std::floor(fu);
  const float iv = std::floor(fv);
  switch (m.pattern) {
    case Pattern::Constant:
      return m.albedo;
    case Pattern::Checker: {
      const long parity = (static_cast<long>(iu) + static_cast<long>(iv)) & 1L;
      return parity ? m.albedo2 : m.albedo;
    }
    case Pattern::Stripes:
      return (static_cast<long>(iu) & 1L) ? m.albedo2 : m.albedo;
    case Pattern::Tiles: {
      // Tiles of `albedo` separated by grout lines of `albedo2`, 8% of a period wide.
      const bool grout = (fu - iu) < 0.08f || (fv - iv) < 0.08f;
      return grout ? m.albedo2 : m.albedo;
    }
  }
  return m.albedo;
}

}  // namespace svgf::gbuffer

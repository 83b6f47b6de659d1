#include "metrics/disocclusion.h"

#include <cmath>
#include <stdexcept>

namespace svgf::metrics {

PixelMask disoccluded_pixels(const std::vector<uint32_t>& mesh_previous,
                             const std::vector<uint32_t>& mesh_current, const Image& motion) {
  const int w = motion.width(), h = motion.height();
  const size_t n = motion.pixel_count();
  if (motion.channels() != 2 || mesh_previous.size() != n || mesh_current.size() != n)
    throw std::invalid_argument(
        "disoccluded_pixels: mesh ids and 2-channel motion of different sizes");
  PixelMask m;
  m.inside.assign(n, 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = static_cast<size_t>(y) * w + x;
      if (mesh_current[i] == 0) continue;
      const double px = std::floor(x + static_cast<double>(motion.plane(0)[i]) + 0.5);
      const double py = std::floor(y + static_cast<double>(motion.plane(1)[i]) + 0.5);
      const bool inside = px >= 0 && py >= 0 && px < w && py < h;  // NaN: false
      if (inside &&
          mesh_previous[static_cast<size_t>(py) * w + static_cast<size_t>(px)] == mesh_current[i])
        continue;
      m.inside[i] = 1;
      ++m.count;
    }
  return m;
}

}  // namespace svgf::metrics

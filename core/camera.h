#pragma once
// Camera of a frame, host or device (core/frame.h, core/device_frame.h). Row-major 4x4
// matrices acting on column vectors: p_view = world_to_view * p_world, p_clip = view_to_clip *
// p_view. View space looks down -z (OpenGL convention); linear depth is -p_view.z. The
// defaults (identity) stand for "no camera given".
#include <array>

namespace svgf {

struct Camera {
  std::array<float, 16> world_to_view{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  std::array<float, 16> view_to_clip{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
};

}  // namespace svgf

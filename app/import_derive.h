#pragma once
// What svgf import derives when a buffer is absent (docs/import.md states each convention).
// Screen coordinates are the frame format's: continuous pixels, (0, 0) the top-left corner,
// +x right, +y down, pixel (x, y) centred at (x + 0.5, y + 0.5). Math in double, stored in float.
#include <array>
#include <cstdint>
#include <vector>

#include "core/frame.h"
#include "core/matrix4.h"
#include "io/games202_matrices.h"

namespace svgf::app {

using io::Matrix4;
using io::SceneMatrices;

using svgf::invert;    // core/matrix4.h
using svgf::multiply;
// m * (x, y, z, 1): the homogeneous result (x, y, z, w).
std::array<double, 4> transform(const Matrix4& m, const double p[3]);

// (d depth/dx, d depth/dy) per pixel by differences of neighbouring depths, 0 on background.
// A neighbour counts when it is inside the image, a surface (depth > 0) with the same mesh id.
// With both neighbours along an axis and one-sided differences b (to the left / above) and
// f (to the right / below) that agree (|f - b| <= max(|f|, |b|) / 2): the central difference
// (f + b) / 2, which matches the renderer's analytic gradient on planes to second order.
// Otherwise (an edge, a crease) the smaller of the usable one-sided differences; none: 0.
Image depth_gradient_from_depth(const Image& depth, const std::vector<uint32_t>& mesh_id);

// Linear view depth |z_camera| of each surface pixel's world position, 0 on background.
Image depth_from_position(const Image& position, const std::vector<uint32_t>& mesh_id,
                          const Matrix4& world_to_camera);

// World positions of the surface pixels from linear view depth: the point that world_to_screen
// projects to the pixel centre, in front of the camera (screen w > 0), whose |z_camera| is the
// depth (camera space may look down -z or +z). Throws std::invalid_argument when a pixel's ray
// lies in the camera's z = const plane (a degenerate matrix).
Image position_from_depth(const Image& depth, const std::vector<uint32_t>& mesh_id,
                          const SceneMatrices& m);

// Motion in the frame format's convention, motion = screen_prev - screen_cur in pixels, for the
// surface point P at each pixel: with per_object, P is carried by its object (mesh id - 1):
// P_prev = prev.object_to_world[k] * inverse(cur.object_to_world[k]) * P (the identity where the
// two are equal); without, the world is static. screen_prev = prev.world_to_screen * P_prev,
// screen_cur = cur.world_to_screen * P (both projected, so a static point under a static camera
// gets exactly 0). Behind the previous camera, or an object the previous frame lacks: the
// previous position (-W, -H) (no history), as the renderer does. Background: 0.
Image motion_from_matrices(const Image& position, const std::vector<uint32_t>& mesh_id,
                           bool per_object, const SceneMatrices& cur, const SceneMatrices& prev);

// The frame header's camera: world_to_view = world_to_camera as given; view_to_clip such that
// view_to_clip * world_to_view maps world points to the clip space whose NDC x, y map to the
// screen as the frame format says (sx = (x + 1) / 2 * W, sy = (1 - y) / 2 * H).
Camera camera_from_matrices(const SceneMatrices& m, int width, int height);

}  // namespace svgf::app

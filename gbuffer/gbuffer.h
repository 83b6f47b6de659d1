#pragma once
// The G-buffer of one pixel, from its primary hit (the camera ray through the pixel centre).
// Conventions (docs/gbuffer.md): normal faces the camera; depth = -z_view of the hit;
// depth_gradient = analytic screen derivative of the depth of the hit's tangent plane;
// motion = previous screen position of the hit's object-space point minus its current one
// (which is (x+0.5, y+0.5) up to float rounding of the hit, ~1e-5 px).
#include <cstdint>

#include "core/vec.h"
#include "gbuffer/frame_scene.h"

namespace svgf::gbuffer {

struct GBufferSample {
  Vec3 position;                          // 0 on background
  Vec3 normal;                            // 0 on background
  Vec3 albedo = make_vec3(1.f, 1.f, 1.f); // 1 on background and emitters
  Vec3 emission;                          // radiance the surface emits towards the camera
  float depth = 0.f;                      // 0 on background
  Vec2 depth_gradient;                    // 0 on background
  Vec2 motion;
  uint32_t mesh_id = 0;                   // object index + 1; 0 on background
};

// Camera ray through the centre of pixel (x, y): origin and (normalized) direction in float.
void primary_ray(const CameraModel& camera, int x, int y, Vec3& origin, Vec3& dir);

// `hit` is the first hit of primary_ray(x, y) (possibly a miss).
GBufferSample gbuffer_sample(const FrameScene& scene, int x, int y, const Hit& hit, Vec3 dir);

// Where the previous frame saw the point of this frame's hit: screen position, or false when
// the point was behind the previous camera. Misses reproject their direction at infinity.
bool previous_screen_position(const FrameScene& scene, const Hit& hit, Vec3 dir,
                              glm::dvec2& prev);

}  // namespace svgf::gbuffer

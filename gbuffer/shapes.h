#pragma once
// Quad-mesh builders for the scenes. Orientation only matters for emitters (they emit on the
// front side, cross(e1, e2)); other surfaces are two-sided.
#include <vector>

#include <glm/glm.hpp>

#include "gbuffer/scene.h"

namespace svgf::gbuffer {

// Axis-aligned box of size `size`, its origin at the centre of its bottom face, faces outward.
std::vector<LocalQuad> box(const glm::dvec3& size);

// The six inner faces of a room [lo, hi], facing inward, in the order
// floor, ceiling, back (z = lo.z), front (z = hi.z), left (x = lo.x), right (x = hi.x).
enum RoomFace { kFloor, kCeiling, kBack, kFront, kLeft, kRight };
LocalQuad room_face(const glm::dvec3& lo, const glm::dvec3& hi, RoomFace face);

// A horizontal emitter facing down: corner (x0, y, z0), extent (dx, dz).
LocalQuad ceiling_light(double x0, double y, double z0, double dx, double dz);

Material diffuse(float r, float g, float b);
Material patterned(Pattern pattern, Vec3 a, Vec3 b, float scale);
Material emitter(float r, float g, float b);

Object make_object(const std::string& name, const Material& m, std::vector<LocalQuad> quads,
                   std::function<Pose(double)> pose = {});
// An object that stays at `translation`, turned by `yaw_turns`.
Object placed(const std::string& name, const Material& m, std::vector<LocalQuad> quads,
              const glm::dvec3& translation, double yaw_turns = 0.0);

}  // namespace svgf::gbuffer

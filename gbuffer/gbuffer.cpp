#include "gbuffer/gbuffer.h"

#include <cmath>

#include "gbuffer/vec_ops.h"

namespace svgf::gbuffer {

namespace {
glm::dvec3 to_double(Vec3 v) { return {v.x, v.y, v.z}; }
}  // namespace

void primary_ray(const CameraModel& camera, int x, int y, Vec3& origin, Vec3& dir) {
  const glm::dvec3 d = camera.world_direction(x + 0.5, y + 0.5);
  const glm::dvec3 dn = d / std::sqrt(glm::dot(d, d));
  const glm::dvec3& e = camera.eye();
  origin = make_vec3(static_cast<float>(e.x), static_cast<float>(e.y), static_cast<float>(e.z));
  dir = make_vec3(static_cast<float>(dn.x), static_cast<float>(dn.y), static_cast<float>(dn.z));
}

bool previous_screen_position(const FrameScene& scene, const Hit& hit, Vec3 dir,
                              glm::dvec2& prev) {
  if (!hit.valid()) return scene.prev_camera().project_direction(to_double(dir), prev);
  // Same object-space point, placed where its object was one frame earlier.
  const glm::dvec3 p = to_double(hit.p);
  if (!scene.moved(hit.object)) return scene.prev_camera().project(p, prev);
  const glm::dvec3 local = scene.transform(hit.object).to_local(p);
  return scene.prev_camera().project(scene.prev_transform(hit.object).to_world(local), prev);
}

GBufferSample gbuffer_sample(const FrameScene& scene, int x, int y, const Hit& hit, Vec3 dir) {
  GBufferSample g;
  const CameraModel& cam = scene.camera();
  const double cx = x + 0.5, cy = y + 0.5;
  // Both positions come from projecting the same point, so rounding cancels and a static point
  // seen by a static camera gets exactly 0 (the hit point is within ~1e-5 px of the centre).
  glm::dvec2 prev, cur;
  const bool seen_before = previous_screen_position(scene, hit, dir, prev);
  const bool seen_now = hit.valid() ? cam.project(to_double(hit.p), cur)
                                    : cam.project_direction(to_double(dir), cur);
  if (!seen_now) cur = {cx, cy};
  // Behind the previous camera: no previous position; point off the image, at (-W, -H).
  if (!seen_before) prev = {-static_cast<double>(cam.width()), -static_cast<double>(cam.height())};
  g.motion = make_vec2(static_cast<float>(prev.x - cur.x), static_cast<float>(prev.y - cur.y));
  if (!hit.valid()) return g;

  const Material& m = scene.material(hit.object);
  g.position = hit.p;
  g.normal = dot(hit.n, dir) < 0.f ? hit.n : neg(hit.n);
  g.albedo = m.is_emitter() ? vec3(1.f) : scene.albedo(hit);
  // One-sided emitters, as trace_path sees them: this is exactly the emitted part of the color.
  if (m.is_emitter() && dot(hit.n, dir) < 0.f) g.emission = scene.emission(hit.object);
  g.mesh_id = static_cast<uint32_t>(hit.object) + 1u;
  const double depth = cam.depth(to_double(hit.p));
  g.depth = static_cast<float>(depth);
  const glm::dvec2 grad = cam.depth_gradient(cx, cy, depth, to_double(hit.n));
  g.depth_gradient = make_vec2(static_cast<float>(grad.x), static_cast<float>(grad.y));
  return g;
}

}  // namespace svgf::gbuffer

#include "gbuffer/shapes.h"

#include <utility>

namespace svgf::gbuffer {

std::vector<LocalQuad> box(const glm::dvec3& s) {
  const double hx = 0.5 * s.x, hz = 0.5 * s.z, h = s.y;
  using V = glm::dvec3;
  return {
      {V(hx, 0, -hz), V(0, h, 0), V(0, 0, s.z)},     // +x
      {V(-hx, 0, -hz), V(0, 0, s.z), V(0, h, 0)},    // -x
      {V(-hx, h, -hz), V(0, 0, s.z), V(s.x, 0, 0)},  // +y
      {V(-hx, 0, -hz), V(s.x, 0, 0), V(0, 0, s.z)},  // -y
      {V(-hx, 0, hz), V(s.x, 0, 0), V(0, h, 0)},     // +z
      {V(-hx, 0, -hz), V(0, h, 0), V(s.x, 0, 0)},    // -z
  };
}

LocalQuad room_face(const glm::dvec3& lo, const glm::dvec3& hi, RoomFace face) {
  using V = glm::dvec3;
  const V d = hi - lo;
  switch (face) {
    case kFloor: return {V(lo.x, lo.y, lo.z), V(0, 0, d.z), V(d.x, 0, 0)};
    case kCeiling: return {V(lo.x, hi.y, lo.z), V(d.x, 0, 0), V(0, 0, d.z)};
    case kBack: return {V(lo.x, lo.y, lo.z), V(d.x, 0, 0), V(0, d.y, 0)};
    case kFront: return {V(lo.x, lo.y, hi.z), V(0, d.y, 0), V(d.x, 0, 0)};
    case kLeft: return {V(lo.x, lo.y, lo.z), V(0, d.y, 0), V(0, 0, d.z)};
    case kRight: return {V(hi.x, lo.y, lo.z), V(0, 0, d.z), V(0, d.y, 0)};
  }
  return {};
}

LocalQuad ceiling_light(double x0, double y, double z0, double dx, double dz) {
  return {glm::dvec3(x0, y, z0), glm::dvec3(dx, 0, 0), glm::dvec3(0, 0, dz)};
}

Material diffuse(float r, float g, float b) {
  Material m;
  m.albedo = make_vec3(r, g, b);
  return m;
}

Material patterned(Pattern pattern, Vec3 a, Vec3 b, float scale) {
  Material m;
  m.pattern = pattern;
  m.albedo = a;
  m.albedo2 = b;
  m.scale = scale;
  return m;
}

Material emitter(float r, float g, float b) {
  Material m;
  m.albedo = make_vec3(0.f, 0.f, 0.f);
  m.emission = make_vec3(r, g, b);
  return m;
}

Object make_object(const std::string& name, const Material& m, std::vector<LocalQuad> quads,
                   std::function<Pose(double)> pose) {
  Object o;
  o.name = name;
  o.material = m;
  o.quads = std::move(quads);
  o.pose = std::move(pose);
  return o;
}

Object placed(const std::string& name, const Material& m, std::vector<LocalQuad> quads,
              const glm::dvec3& translation, double yaw_turns) {
  const Pose pose{translation, yaw_turns};
  return make_object(name, m, std::move(quads), [pose](double) { return pose; });
}

}  // namespace svgf::gbuffer

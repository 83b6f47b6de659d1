#pragma once
// Rigid object motion: a rotation about the world y axis, then a translation. Animation math is
// in double; only what Embree and the shading see is rounded to float.
#include <glm/glm.hpp>

#include "gbuffer/det_trig.h"

namespace svgf::gbuffer {

// Where an object is at one instant.
struct Pose {
  glm::dvec3 translation{0.0};
  double yaw_turns = 0.0;  // rotation about +y, counter-clockwise seen from above, in turns
};

class RigidTransform {
 public:
  RigidTransform() = default;
  explicit RigidTransform(const Pose& pose) : t_(pose.translation) {
    sincos_turns(pose.yaw_turns, s_, c_);
  }
  glm::dvec3 rotate(const glm::dvec3& v) const {
    return {c_ * v.x + s_ * v.z, v.y, c_ * v.z - s_ * v.x};
  }
  glm::dvec3 unrotate(const glm::dvec3& v) const {
    return {c_ * v.x - s_ * v.z, v.y, c_ * v.z + s_ * v.x};
  }
  glm::dvec3 to_world(const glm::dvec3& local) const { return rotate(local) + t_; }
  glm::dvec3 to_local(const glm::dvec3& world) const { return unrotate(world - t_); }

 private:
  glm::dvec3 t_{0.0};
  double s_ = 0.0, c_ = 1.0;
};

}  // namespace svgf::gbuffer

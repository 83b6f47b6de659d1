#pragma once
// Pinhole camera of one frame, in double. Screen coordinates are continuous pixels: (0, 0) is the
// top-left corner of the image, +x right, +y down, pixel (x, y) has its centre at (x+0.5, y+0.5).
// View space is the frame format's: +x right, +y up, looking down -z; depth = -z_view.
#include <glm/glm.hpp>

#include "core/frame.h"

namespace svgf::gbuffer {

struct CameraPose {
  glm::dvec3 eye{0.0, 1.0, 3.0};
  glm::dvec3 target{0.0, 1.0, 0.0};
  double fovy_degrees = 40.0;  // full vertical field of view
};

inline constexpr double kNearPlane = 0.01;   // only for the stored view_to_clip matrix
inline constexpr double kFarPlane = 1000.0;

class CameraModel {
 public:
  CameraModel() = default;
  CameraModel(const CameraPose& pose, int width, int height);

  const glm::dvec3& eye() const { return eye_; }
  int width() const { return width_; }
  int height() const { return height_; }

  // View-space direction through a screen point, scaled so that its z is -1 (so a point at
  // depth d along it is d * dir).
  glm::dvec3 view_direction(double sx, double sy) const;
  // The same direction in world space, not normalized (its depth component is 1).
  glm::dvec3 world_direction(double sx, double sy) const;
  glm::dvec3 to_view(const glm::dvec3& world) const;
  glm::dvec3 direction_to_view(const glm::dvec3& world_dir) const;
  double depth(const glm::dvec3& world) const { return -to_view(world).z; }
  // Screen position of a world point; false when it is not in front of the camera.
  bool project(const glm::dvec3& world, glm::dvec2& screen) const;
  // Screen position of the point at infinity in direction `world_dir`.
  bool project_direction(const glm::dvec3& world_dir, glm::dvec2& screen) const;
  // Screen-space derivative of the depth of the plane through the point at `depth` with world
  // normal `world_normal`, at the screen point (sx, sy): (d depth/dx, d depth/dy) per pixel.
  glm::dvec2 depth_gradient(double sx, double sy, double depth,
                            const glm::dvec3& world_normal) const;
  // The frame format's matrices (row-major, column vectors, OpenGL clip space).
  Camera matrices() const;

 private:
  glm::dvec3 eye_{0.0}, right_{1, 0, 0}, up_{0, 1, 0}, back_{0, 0, 1};
  double tan_x_ = 1.0, tan_y_ = 1.0;  // half-extent of the image plane at depth 1
  int width_ = 1, height_ = 1;
};

}  // namespace svgf::gbuffer

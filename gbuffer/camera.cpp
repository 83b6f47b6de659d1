#include "gbuffer/camera.h"

#include <cmath>
#include <stdexcept>

#include "gbuffer/det_trig.h"

namespace svgf::gbuffer {

namespace {
glm::dvec3 unit(const glm::dvec3& v) { return v / std::sqrt(glm::dot(v, v)); }
}  // namespace

CameraModel::CameraModel(const CameraPose& pose, int width, int height)
    : eye_(pose.eye), width_(width), height_(height) {
  if (width <= 0 || height <= 0) throw std::invalid_argument("camera: empty image");
  back_ = unit(pose.eye - pose.target);
  right_ = unit(glm::cross(glm::dvec3(0, 1, 0), back_));
  up_ = glm::cross(back_, right_);
  tan_y_ = tan_turns(pose.fovy_degrees / 720.0);
  tan_x_ = tan_y_ * static_cast<double>(width) / static_cast<double>(height);
}

glm::dvec3 CameraModel::view_direction(double sx, double sy) const {
  const double ndc_x = 2.0 * sx / width_ - 1.0;
  const double ndc_y = 1.0 - 2.0 * sy / height_;
  return {ndc_x * tan_x_, ndc_y * tan_y_, -1.0};
}

glm::dvec3 CameraModel::world_direction(double sx, double sy) const {
  const glm::dvec3 v = view_direction(sx, sy);
  return right_ * v.x + up_ * v.y + back_ * v.z;
}

glm::dvec3 CameraModel::direction_to_view(const glm::dvec3& d) const {
  return {glm::dot(right_, d), glm::dot(up_, d), glm::dot(back_, d)};
}

glm::dvec3 CameraModel::to_view(const glm::dvec3& world) const {
  return direction_to_view(world - eye_);
}

bool CameraModel::project_direction(const glm::dvec3& world_dir, glm::dvec2& screen) const {
  const glm::dvec3 v = direction_to_view(world_dir);
  if (!(v.z < 0.0)) return false;
  const double ndc_x = v.x / (-v.z * tan_x_);
  const double ndc_y = v.y / (-v.z * tan_y_);
  screen = {(ndc_x + 1.0) * 0.5 * width_, (1.0 - ndc_y) * 0.5 * height_};
  return true;
}

bool CameraModel::project(const glm::dvec3& world, glm::dvec2& screen) const {
  return project_direction(world - eye_, screen);
}

glm::dvec2 CameraModel::depth_gradient(double sx, double sy, double depth,
                                       const glm::dvec3& world_normal) const {
  // On the plane n.X = c (view space), the ray X = D * v(s) has depth D = c / (n.v(s)), so
  // dD/ds = -D (n . dv/ds) / (n . v). v is affine in s: dv/ds is the step between neighbouring
  // pixels' rays, (2 tan_x / W, 0, 0) along x and (0, -2 tan_y / H, 0) along y.
  const glm::dvec3 n = direction_to_view(world_normal);
  const glm::dvec3 v = view_direction(sx, sy);
  double n_dot_v = glm::dot(n, v);
  const double min_cos = 1e-6 * std::sqrt(glm::dot(v, v));  // grazing: steep but finite
  if (std::fabs(n_dot_v) < min_cos) n_dot_v = n_dot_v < 0.0 ? -min_cos : min_cos;
  const double dvx = 2.0 * tan_x_ / width_;
  const double dvy = -2.0 * tan_y_ / height_;
  return {-depth * (n.x * dvx) / n_dot_v, -depth * (n.y * dvy) / n_dot_v};
}

Camera CameraModel::matrices() const {
  Camera cam;
  const glm::dvec3 rows[3] = {right_, up_, back_};
  for (int r = 0; r < 3; ++r) {
    cam.world_to_view[r * 4 + 0] = static_cast<float>(rows[r].x);
    cam.world_to_view[r * 4 + 1] = static_cast<float>(rows[r].y);
    cam.world_to_view[r * 4 + 2] = static_cast<float>(rows[r].z);
    cam.world_to_view[r * 4 + 3] = static_cast<float>(-glm::dot(rows[r], eye_));
  }
  cam.world_to_view[12] = 0.f;
  cam.world_to_view[13] = 0.f;
  cam.world_to_view[14] = 0.f;
  cam.world_to_view[15] = 1.f;
  const double n = kNearPlane, f = kFarPlane;
  cam.view_to_clip = {static_cast<float>(1.0 / tan_x_), 0.f, 0.f, 0.f,
                      0.f, static_cast<float>(1.0 / tan_y_), 0.f, 0.f,
                      0.f, 0.f, static_cast<float>(-(f + n) / (f - n)),
                      static_cast<float>(-2.0 * f * n / (f - n)),
                      0.f, 0.f, -1.f, 0.f};
  return cam;
}

}  // namespace svgf::gbuffer

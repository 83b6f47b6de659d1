#include "app/import_derive.h"

#include <cmath>
#include <stdexcept>

namespace svgf::app {

std::array<double, 4> transform(const Matrix4& m, const double p[3]) {
  std::array<double, 4> r{};
  for (int i = 0; i < 4; ++i)
    r[i] = m[i * 4] * p[0] + m[i * 4 + 1] * p[1] + m[i * 4 + 2] * p[2] + m[i * 4 + 3];
  return r;
}

namespace {

// The gradient along one axis from the depths before (b_ok, db) and after (f_ok, df) a pixel.
double one_axis(double d, bool b_ok, double db, bool f_ok, double df) {
  const double b = d - db, f = df - d;
  if (b_ok && f_ok) {
    if (std::fabs(f - b) <= 0.5 * std::max(std::fabs(f), std::fabs(b))) return 0.5 * (f + b);
    return std::fabs(b) <= std::fabs(f) ? b : f;
  }
  if (b_ok) return b;
  if (f_ok) return f;
  return 0.0;
}

bool is_surface(const std::vector<uint32_t>& mesh_id, size_t i) { return mesh_id[i] != 0; }

void world_position(const Image& position, size_t i, double p[3]) {
  for (int c = 0; c < 3; ++c) p[c] = position.plane(c)[i];
}

}  // namespace

Image depth_gradient_from_depth(const Image& depth, const std::vector<uint32_t>& mesh_id) {
  const int w = depth.width(), h = depth.height();
  Image g(w, h, 2);
  const float* d = depth.plane(0);
  auto usable = [&](int x, int y, uint32_t id) {
    if (x < 0 || y < 0 || x >= w || y >= h) return false;
    const size_t j = static_cast<size_t>(y) * w + x;
    return d[j] > 0.f && mesh_id[j] == id;
  };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = static_cast<size_t>(y) * w + x;
      if (!(d[i] > 0.f) || !is_surface(mesh_id, i)) continue;
      const uint32_t id = mesh_id[i];
      const auto at = [&](int xx, int yy) { return double(d[static_cast<size_t>(yy) * w + xx]); };
      const bool l = usable(x - 1, y, id), r = usable(x + 1, y, id);
      const bool u = usable(x, y - 1, id), dn = usable(x, y + 1, id);
      g.plane(0)[i] = static_cast<float>(
          one_axis(d[i], l, l ? at(x - 1, y) : 0.0, r, r ? at(x + 1, y) : 0.0));
      g.plane(1)[i] = static_cast<float>(
          one_axis(d[i], u, u ? at(x, y - 1) : 0.0, dn, dn ? at(x, y + 1) : 0.0));
    }
  return g;
}

Image depth_from_position(const Image& position, const std::vector<uint32_t>& mesh_id,
                          const Matrix4& world_to_camera) {
  Image depth(position.width(), position.height(), 1);
  for (size_t i = 0; i < depth.pixel_count(); ++i) {
    if (!is_surface(mesh_id, i)) continue;
    double p[3];
    world_position(position, i, p);
    depth.plane(0)[i] = static_cast<float>(std::fabs(transform(world_to_camera, p)[2]));
  }
  return depth;
}

Image position_from_depth(const Image& depth, const std::vector<uint32_t>& mesh_id,
                          const SceneMatrices& m) {
  const Matrix4& S = m.world_to_screen;
  const Matrix4& V = m.world_to_camera;
  const int w = depth.width(), h = depth.height();
  Image pos(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = static_cast<size_t>(y) * w + x;
      if (!is_surface(mesh_id, i)) continue;
      // P = (X, Y, Z, 1) projects to the pixel centre (sx, sy): (S0 - sx S3) . P = 0 and
      // (S1 - sy S3) . P = 0; and its camera z is +-depth. Of the two signs, the point in
      // front of the camera (screen w > 0) is the one.
      const double sx = x + 0.5, sy = y + 0.5;
      double a[3][4];
      for (int c = 0; c < 4; ++c) {
        a[0][c] = S[c] - sx * S[12 + c];
        a[1][c] = S[4 + c] - sy * S[12 + c];
        a[2][c] = V[8 + c];
      }
      const auto det3 = [](double m00, double m01, double m02, double m10, double m11, double m12,
                           double m20, double m21, double m22) {
        return m00 * (m11 * m22 - m12 * m21) - m01 * (m10 * m22 - m12 * m20) +
               m02 * (m10 * m21 - m11 * m20);
      };
      const double det = det3(a[0][0], a[0][1], a[0][2], a[1][0], a[1][1], a[1][2], a[2][0],
                              a[2][1], a[2][2]);
      if (!(std::fabs(det) > 1e-300))
        throw std::invalid_argument("the pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                                    ")'s ray runs along the camera plane: positions cannot be "
                                    "reconstructed from depth (give a position buffer)");
      for (double sign : {-1.0, 1.0}) {
        const double b[3] = {-a[0][3], -a[1][3], sign * depth.plane(0)[i] - a[2][3]};
        double p[3];  // Cramer's rule
        for (int k = 0; k < 3; ++k) {
          double m[3][3];
          for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) m[r][c] = c == k ? b[r] : a[r][c];
          p[k] = det3(m[0][0], m[0][1], m[0][2], m[1][0], m[1][1], m[1][2], m[2][0], m[2][1],
                      m[2][2]) / det;
        }
        if (transform(S, p)[3] > 0 || sign > 0)
          for (int c = 0; c < 3; ++c) pos.plane(c)[i] = static_cast<float>(p[c]);
        if (transform(S, p)[3] > 0) break;
      }
    }
  return pos;
}

Image motion_from_matrices(const Image& position, const std::vector<uint32_t>& mesh_id,
                           bool per_object, const SceneMatrices& cur, const SceneMatrices& prev) {
  const int w = position.width(), h = position.height();
  // Per object: current world -> previous world, or none when the previous frame lacks it.
  std::vector<Matrix4> carry(cur.object_to_world.size());
  std::vector<int> kind(cur.object_to_world.size(), 0);  // 0 static, 1 moved, -1 no history
  for (size_t k = 0; per_object && k < cur.object_to_world.size(); ++k) {
    if (k >= prev.object_to_world.size()) {
      kind[k] = -1;
      continue;
    }
    if (prev.object_to_world[k] == cur.object_to_world[k]) continue;
    Matrix4 inv;
    if (!invert(cur.object_to_world[k], inv))
      throw std::invalid_argument("object " + std::to_string(k) + "'s object->world matrix is singular");
    carry[k] = multiply(prev.object_to_world[k], inv);
    kind[k] = 1;
  }
  Image motion(w, h, 2);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = static_cast<size_t>(y) * w + x;
      if (!is_surface(mesh_id, i)) continue;
      double p[3];
      world_position(position, i, p);
      const size_t k = mesh_id[i] - 1u;
      const int how = per_object && k < kind.size() ? kind[k] : 0;
      double prev_x = -w, prev_y = -h;
      if (how >= 0) {
        double q[3] = {p[0], p[1], p[2]};
        if (how == 1) {
          const auto r = transform(carry[k], p);
          for (int c = 0; c < 3; ++c) q[c] = r[c] / r[3];
        }
        const auto s = transform(prev.world_to_screen, q);
        if (s[3] > 0) {
          prev_x = s[0] / s[3];
          prev_y = s[1] / s[3];
        }
      }
      const auto s = transform(cur.world_to_screen, p);
      const double cur_x = s[3] > 0 ? s[0] / s[3] : x + 0.5, cur_y = s[3] > 0 ? s[1] / s[3] : y + 0.5;
      motion.plane(0)[i] = static_cast<float>(prev_x - cur_x);
      motion.plane(1)[i] = static_cast<float>(prev_y - cur_y);
    }
  return motion;
}

Camera camera_from_matrices(const SceneMatrices& m, int width, int height) {
  Camera cam;
  Matrix4 camera_to_world;
  if (!invert(m.world_to_camera, camera_to_world))
    throw std::invalid_argument("world->camera matrix is singular");
  const Matrix4 screen_to_ndc = {2.0 / width, 0, 0, -1, 0, -2.0 / height, 0, 1,
                                 0, 0, 1, 0, 0, 0, 0, 1};
  const Matrix4 view_to_clip = multiply(multiply(screen_to_ndc, m.world_to_screen), camera_to_world);
  for (int k = 0; k < 16; ++k) {
    cam.world_to_view[k] = static_cast<float>(m.world_to_camera[k]);
    cam.view_to_clip[k] = static_cast<float>(view_to_clip[k]);
  }
  return cam;
}

}  // namespace svgf::app

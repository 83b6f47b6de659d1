// Tests of the Embree fixture renderer (gbuffer/) and of the committed fixtures (fixtures/).
#include <tbb/task_arena.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "gbuffer/det_trig.h"
#include "gbuffer/fixture_format.h"
#include "gbuffer/frame_scene.h"
#include "gbuffer/gbuffer.h"
#include "gbuffer/renderer.h"
#include "gbuffer/rng.h"
#include "gbuffer/scene_timeline.h"
#include "gbuffer/scenes.h"
#include "gbuffer/shapes.h"
#include "gbuffer/vec_ops.h"
#include "io/sequence.h"
#include "io/sha256.h"
#include "gbuffer_test_support.h"

namespace fs = std::filesystem;
using namespace svgf;
using namespace svgf::gbuffer;

namespace {

using svgf::test::renderer;

RenderSettings small(int w, int h) {
  RenderSettings s;
  s.width = w;
  s.height = h;
  return s;
}

bool same_bits(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

bool same_frame_bits(const Frame& a, const Frame& b) {
  return same_bits(a.color.data(), b.color.data()) && same_bits(a.albedo.data(), b.albedo.data()) &&
         same_bits(a.normal.data(), b.normal.data()) &&
         same_bits(a.position.data(), b.position.data()) &&
         same_bits(a.depth.data(), b.depth.data()) &&
         same_bits(a.depth_gradient.data(), b.depth_gradient.data()) &&
         same_bits(a.motion.data(), b.motion.data()) && a.mesh_id == b.mesh_id &&
         same_bits(a.reference.data(), b.reference.data()) &&
         same_bits(a.direct.data(), b.direct.data()) &&
         same_bits(a.indirect.data(), b.indirect.data()) &&
         same_bits(a.gradient.data(), b.gradient.data());
}

Vec3 load3(const Image& im, int x, int y) {
  return make_vec3(im.at(x, y, 0), im.at(x, y, 1), im.at(x, y, 2));
}

// Same object and the very same normal over the 3x3 block: away from edges.
bool interior(const Frame& f, int x, int y) {
  const int w = f.width();
  const uint32_t id = f.mesh_id[y * w + x];
  if (id == 0 || x < 1 || y < 1 || x + 1 >= w || y + 1 >= f.height()) return false;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      if (f.mesh_id[(y + dy) * w + x + dx] != id) return false;
      for (int c = 0; c < 3; ++c)
        if (f.normal.at(x + dx, y + dy, c) != f.normal.at(x, y, c)) return false;
    }
  return true;
}

std::string fixture_dir(const std::string& scene) {
  return std::string(SVGF_SOURCE_DIR) + "/fixtures/" + scene;
}

struct MotionCheck {
  int interior = 0, tested = 0;
  int tested_moving = 0;  // on objects that moved since the previous frame
  double max_error = 0.0;
};

// Follows each interior pixel's motion vector into the previous frame, traces the previous
// camera's ray there, and carries the surface point it hits back into this frame: it must land
// on the pixel centre. Points hidden in the previous frame (another quad is hit) are skipped.
MotionCheck check_motion(const SceneDesc& scene, int frame, int w, int h) {
  const Frame f = renderer().render(scene, frame, small(w, h));
  const FrameScene cur(renderer().device(), scene, frame, w, h);
  const FrameScene prev(renderer().device(), scene, frame - 1, w, h);
  const float inf = std::numeric_limits<float>::infinity();
  MotionCheck m;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (!interior(f, x, y)) continue;
      Vec3 o, d;
      primary_ray(cur.camera(), x, y, o, d);
      const Hit here = cur.intersect(o, d, inf);
      REQUIRE(here.object + 1 == static_cast<int>(f.mesh_id[y * w + x]));
      ++m.interior;
      const double px = x + 0.5 + f.motion.at(x, y, 0), py = y + 0.5 + f.motion.at(x, y, 1);
      if (px < 0.0 || py < 0.0 || px > w || py > h) continue;
      const glm::dvec3 pd = prev.camera().world_direction(px, py);
      const glm::dvec3 pn = pd / std::sqrt(glm::dot(pd, pd));
      const glm::dvec3& e = prev.camera().eye();
      const Hit before = prev.intersect(
          make_vec3(float(e.x), float(e.y), float(e.z)),
          make_vec3(float(pn.x), float(pn.y), float(pn.z)), inf);
      if (before.object != here.object || before.quad != here.quad) continue;
      ++m.tested;
      if (cur.moved(here.object)) ++m.tested_moving;
      const glm::dvec3 local =
          prev.transform(before.object).to_local(glm::dvec3(before.p.x, before.p.y, before.p.z));
      glm::dvec2 s;
      REQUIRE(cur.camera().project(cur.transform(here.object).to_world(local), s));
      m.max_error = std::fmax(m.max_error, std::hypot(s.x - (x + 0.5), s.y - (y + 0.5)));
    }
  return m;
}

}  // namespace

TEST_CASE("Philox-4x32-10 matches the Random123 known answers", "[gbuffer][rng]") {
  const Philox4 a = philox4x32_10(Philox4{{0, 0, 0, 0}}, 0, 0);
  CHECK(a.v[0] == 0x6627e8d5u);
  CHECK(a.v[1] == 0xe169c58du);
  CHECK(a.v[2] == 0xbc57ac4cu);
  CHECK(a.v[3] == 0x9b00dbd8u);
  const Philox4 b = philox4x32_10(Philox4{{0xffffffffu, 0xffffffffu, 0xffffffffu, 0xffffffffu}},
                                  0xffffffffu, 0xffffffffu);
  CHECK(b.v[0] == 0x408f276du);
  CHECK(b.v[3] == 0x6d5451fdu);
  const Philox4 c = philox4x32_10(Philox4{{0x243f6a88u, 0x85a308d3u, 0x13198a2eu, 0x03707344u}},
                                  0xa4093822u, 0x299f31d0u);
  CHECK(c.v[0] == 0xd16cfe09u);
  CHECK(c.v[3] == 0x24126ea1u);
  CHECK(to_unit_float(0xffffffffu) < 1.f);
  CHECK(to_unit_float(0u) == 0.f);
}

TEST_CASE("libm-free sin and cos are accurate", "[gbuffer][math]") {
  for (double t = -2.0; t <= 2.0; t += 0.01) {
    double s, c, s2, c2;
    sincos_turns(t, s, c);
    sincos_turns_coarse(t, s2, c2);
    CHECK(std::fabs(s - std::sin(6.283185307179586 * t)) < 1e-14);
    CHECK(std::fabs(c - std::cos(6.283185307179586 * t)) < 1e-14);
    CHECK(std::fabs(s2 - s) < 1e-12);
    CHECK(std::fabs(c2 - c) < 1e-12);
  }
}

TEST_CASE("camera conventions: pixel centres, y down, depth = -z_view", "[gbuffer][camera]") {
  // 90 degree vertical field of view, 4x2 pixels: the image plane at depth 1 spans x in [-2, 2].
  const CameraModel cam(CameraPose{glm::dvec3(0, 0, 5), glm::dvec3(0, 0, 0), 90.0}, 4, 2);
  glm::dvec2 s;
  REQUIRE(cam.project(glm::dvec3(0, 0, 0), s));
  CHECK(s.x == Approx(2.0));
  CHECK(s.y == Approx(1.0));
  REQUIRE(cam.project(glm::dvec3(0, 1, 4), s));  // top edge, one unit in front
  CHECK(s.y == Approx(0.0).margin(1e-12));
  REQUIRE(cam.project(glm::dvec3(2, -0.5, 4), s));  // right edge, lower half
  CHECK(s.x == Approx(4.0));
  CHECK(s.y == Approx(1.5));
  CHECK_FALSE(cam.project(glm::dvec3(0, 0, 6), s));  // behind the camera
  CHECK(cam.depth(glm::dvec3(0.3, -0.2, 1.0)) == Approx(4.0));
  // The ray through pixel (0, 0)'s centre points left (-x) and up (+y).
  const glm::dvec3 d = cam.world_direction(0.5, 0.5);
  CHECK(d.x == Approx(-1.5));
  CHECK(d.y == Approx(0.5));
  CHECK(d.z == Approx(-1.0));
  // The stored matrices agree: view z of the origin is -5 and it lands in clip-space centre.
  const Camera m = cam.matrices();
  CHECK(m.world_to_view[11] == Approx(-5.f));
  CHECK(m.view_to_clip[14] == -1.f);
}

TEST_CASE("depth gradient is the derivative of the tangent plane's depth", "[gbuffer][camera]") {
  const CameraModel cam(CameraPose{glm::dvec3(0.3, 1.0, 4.0), glm::dvec3(0, 0.5, 0), 40.0}, 64, 48);
  const glm::dvec3 n = glm::dvec3(0.2, 0.9, 0.4) / std::sqrt(0.04 + 0.81 + 0.16);
  const glm::dvec3 p0(0.1, 0.2, -0.3);
  // Depth of the plane along the ray through screen point (sx, sy): its direction has depth 1.
  auto plane_depth = [&](double sx, double sy) {
    const glm::dvec3 d = cam.world_direction(sx, sy);
    return glm::dot(n, p0 - cam.eye()) / glm::dot(n, d);
  };
  for (double sx : {10.5, 32.5, 50.5})
    for (double sy : {5.5, 30.5, 44.5}) {
      const double depth = plane_depth(sx, sy);
      const glm::dvec2 g = cam.depth_gradient(sx, sy, depth, n);
      const double h = 1e-3;
      CHECK(g.x == Approx((plane_depth(sx + h, sy) - plane_depth(sx - h, sy)) / (2 * h)).epsilon(1e-6));
      CHECK(g.y == Approx((plane_depth(sx, sy + h) - plane_depth(sx, sy - h)) / (2 * h)).epsilon(1e-6));
      CHECK(glm::length(cam.depth_gradient(sx, sy, depth, -n) - g) < 1e-12);  // side-independent
    }
}

TEST_CASE("scene library and bad input", "[gbuffer][scenes]") {
  for (const char* name : {"cornell-static", "cornell-moving", "camera-pan", "textured", "thin",
                           "cut", "moving-shadow", "light-switch"})
    CHECK(find_scene(name).name == name);
  CHECK(scene_library().size() == 8u);
  CHECK_THROWS_WITH(find_scene("nope"), Catch::Contains("unknown scene 'nope'") &&
                                            Catch::Contains("cornell-static"));
  CHECK(find_scene("cut").camera_cuts == std::vector<int>{6});
  RenderSettings s = small(0, 16);
  CHECK_THROWS_AS(validate(s), std::invalid_argument);
  s = small(16, kMaxImageSide + 1);
  CHECK_THROWS_AS(validate(s), std::invalid_argument);
  s = small(16, 16);
  s.spp = 0;
  CHECK_THROWS_AS(validate(s), std::invalid_argument);
  s.spp = 1;
  s.reference_spp = -1;
  CHECK_THROWS_AS(validate(s), std::invalid_argument);
}

TEST_CASE("G-buffer: unit normals, depth agrees with position and camera", "[gbuffer]") {
  for (const char* name : {"cornell-static", "camera-pan", "thin", "cut"}) {
    const SceneDesc& scene = find_scene(name);
    const int w = 48, h = 40, frame = 7;
    const Frame f = renderer().render(scene, frame, small(w, h));
    check_frame_consistent(f);
    const Camera& cam = f.camera;
    int surfaces = 0, background = 0, emitters = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        INFO(name << " pixel " << x << "," << y);
        const uint32_t id = f.mesh_id[y * w + x];
        REQUIRE(id <= scene.objects.size());
        if (id == 0) {
          ++background;
          CHECK(load3(f.emission, x, y).y == 0.f);
          CHECK(f.depth.at(x, y, 0) == 0.f);
          CHECK(length(load3(f.normal, x, y)) == 0.f);
          CHECK(load3(f.albedo, x, y).x == 1.f);
          continue;
        }
        ++surfaces;
        CHECK(std::fabs(length(load3(f.normal, x, y)) - 1.f) < 1e-6f);
        if (scene.objects[id - 1].material.is_emitter()) {
          ++emitters;
          CHECK(load3(f.albedo, x, y).y == 1.f);
          // A camera ray that hits the (front of the) light sees its emission and nothing else.
          CHECK(load3(f.emission, x, y).x > 0.f);
          CHECK(load3(f.color, x, y).x == load3(f.emission, x, y).x);
        } else {
          CHECK(load3(f.emission, x, y).x == 0.f);
        }
        const Vec3 p = load3(f.position, x, y);
        const Vec3 n = load3(f.normal, x, y);
        double v[4];
        for (int r = 0; r < 4; ++r)
          v[r] = double(cam.world_to_view[r * 4]) * p.x + double(cam.world_to_view[r * 4 + 1]) * p.y +
                 double(cam.world_to_view[r * 4 + 2]) * p.z + double(cam.world_to_view[r * 4 + 3]);
        const double depth = f.depth.at(x, y, 0);
        CHECK(depth > 0.0);
        CHECK(std::fabs(depth - -v[2]) <= 1e-5 * depth);
        // Projecting the position with the stored matrices lands on the pixel centre.
        double c[4];
        for (int r = 0; r < 4; ++r)
          c[r] = double(cam.view_to_clip[r * 4]) * v[0] + double(cam.view_to_clip[r * 4 + 1]) * v[1] +
                 double(cam.view_to_clip[r * 4 + 2]) * v[2] + double(cam.view_to_clip[r * 4 + 3]) * v[3];
        const double sx = (c[0] / c[3] + 1.0) * 0.5 * w, sy = (1.0 - c[1] / c[3]) * 0.5 * h;
        CHECK(std::fabs(sx - (x + 0.5)) < 1e-3);
        CHECK(std::fabs(sy - (y + 0.5)) < 1e-3);
        // The normal faces the camera: in view space the eye is at the origin.
        double facing = 0.0;
        for (int r = 0; r < 3; ++r)
          facing -= (double(cam.world_to_view[r * 4]) * n.x + double(cam.world_to_view[r * 4 + 1]) * n.y +
                     double(cam.world_to_view[r * 4 + 2]) * n.z) * v[r];
        CHECK(facing > 0.0);
      }
    CHECK(surfaces > w * h / 2);
    if (std::string(name) == "cornell-static") {  // wider than the box: both cases occur
      CHECK(background > 0);
      CHECK(emitters > 0);
    }
  }
}

TEST_CASE("G-buffer: depth gradient matches neighbouring depths on planes", "[gbuffer]") {
  const SceneDesc& scene = find_scene("camera-pan");
  const int w = 64, h = 64;
  const Frame f = renderer().render(scene, 4, small(w, h));
  int tested = 0, floor_pixels = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (!interior(f, x, y)) continue;
      ++tested;
      const double depth = f.depth.at(x, y, 0);
      const double cdx = (f.depth.at(x + 1, y, 0) - f.depth.at(x - 1, y, 0)) / 2.0;
      const double cdy = (f.depth.at(x, y + 1, 0) - f.depth.at(x, y - 1, 0)) / 2.0;
      const double gx = f.depth_gradient.at(x, y, 0), gy = f.depth_gradient.at(x, y, 1);
      INFO("pixel " << x << "," << y << " gradient " << gx << "," << gy << " central " << cdx << ","
                    << cdy);
      CHECK(std::fabs(gx - cdx) <= 1e-4 * depth + 0.02 * std::fabs(gx));
      CHECK(std::fabs(gy - cdy) <= 1e-4 * depth + 0.02 * std::fabs(gy));
      if (f.normal.at(x, y, 1) > 0.99f) {  // floor: farther towards the top of the image
        ++floor_pixels;
        CHECK(gy < 0.0);
      }
    }
  CHECK(tested > w * h / 2);
  CHECK(floor_pixels > 100);
}

TEST_CASE("motion vectors lead to the same surface point in the previous frame", "[gbuffer][motion]") {
  struct Case {
    const char* scene;
    int frame;
  };
  for (const Case& c : {Case{"cornell-moving", 5}, Case{"camera-pan", 3}, Case{"textured", 9},
                        Case{"thin", 2}, Case{"cut", 8}, Case{"cornell-moving", 0}}) {
    const MotionCheck m = check_motion(find_scene(c.scene), c.frame, 64, 64);
    INFO(c.scene << " frame " << c.frame << ": " << m.tested << " of " << m.interior
                 << " interior pixels tested, max error " << m.max_error << " px");
    CHECK(m.tested > m.interior * 3 / 4);
    CHECK(m.max_error < 1e-3);
    if (std::string(c.scene) == "cornell-moving") CHECK(m.tested_moving > 30);
  }
}

TEST_CASE("motion vector sign and static scenes", "[gbuffer][motion]") {
  const int w = 64, h = 64;
  // Static camera and scene: exactly zero motion.
  const Frame s = renderer().render(find_scene("cornell-static"), 3, small(w, h));
  for (float v : s.motion.data()) REQUIRE(v == 0.f);
  // The cube moves +x (right on screen): its previous position is to the left.
  const SceneDesc& moving = find_scene("cornell-moving");
  const Frame f = renderer().render(moving, 4, small(w, h));
  uint32_t cube = 0;
  for (size_t i = 0; i < moving.objects.size(); ++i)
    if (moving.objects[i].name == "cube") cube = static_cast<uint32_t>(i + 1);
  int n = 0;
  for (int i = 0; i < w * h; ++i) {
    if (f.mesh_id[i] == cube) {
      ++n;
      CHECK(f.motion.plane(0)[i] < -0.5f);
    } else {
      CHECK(f.motion.plane(0)[i] == 0.f);  // everything else stands still
    }
  }
  CHECK(n > 20);
}

TEST_CASE("next-event estimation matches the irradiance of a square light", "[gbuffer][light]") {
  // A floor point 1.998 below the centre of a 0.5 x 0.5 emitter, nothing else in the way.
  SceneDesc scene;
  scene.name = "light-test";
  scene.camera = [](double) { return CameraPose{}; };
  scene.objects.push_back(placed("floor", diffuse(0.5f, 0.5f, 0.5f),
                                 {room_face(glm::dvec3(-1, 0, -1), glm::dvec3(1, 2, 1), kFloor)},
                                 glm::dvec3(0)));
  scene.objects.push_back(placed("light", emitter(10.f, 20.f, 30.f),
                                 {ceiling_light(-0.25, 1.998, -0.25, 0.5, 0.5)}, glm::dvec3(0)));
  const FrameScene fs(renderer().device(), scene, 0, 8, 8);
  Hit hit;
  hit.object = 0;
  hit.quad = 0;
  hit.p = make_vec3(0.f, 0.f, 0.f);
  hit.n = make_vec3(0.f, 1.f, 0.f);
  PathSettings direct_only;
  direct_only.max_bounces = 0;
  uint64_t rays = 0;
  double sum = 0.0;
  const int n = 40000;
  for (int k = 0; k < n; ++k) {
    SampleKey key;
    key.sample = static_cast<uint32_t>(k);
    sum += trace_path(fs, hit, make_vec3(0.f, -1.f, 0.f), key, direct_only, rays).direct.y;
  }
  // E = L * integral of h^2 / r^4 over the light (midpoint rule); L_out = albedo / pi * E.
  double e = 0.0;
  const int m = 200;
  const double h = 1.998, cell = 0.5 / m;
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) {
      const double x = -0.25 + (i + 0.5) * cell, z = -0.25 + (j + 0.5) * cell;
      const double r2 = x * x + z * z + h * h;
      e += h * h / (r2 * r2) * cell * cell;
    }
  CHECK(sum / n == Approx(0.5 / 3.141592653589793 * 20.0 * e).epsilon(0.005));
  CHECK(rays == static_cast<uint64_t>(n));  // one shadow ray per sample
}

TEST_CASE("reference error falls as its sample count grows", "[gbuffer][reference]") {
  const SceneDesc& scene = find_scene("cornell-static");
  RenderSettings s = small(16, 16);
  s.split = false;
  s.seed = 77;  // independent of the estimates below
  s.reference_spp = 4096;
  const Frame truth = renderer().render(scene, 0, s);
  s.seed = 1;
  std::vector<double> rmse;
  for (int spp : {16, 64, 256}) {
    s.reference_spp = spp;
    const Frame f = renderer().render(scene, 0, s);
    double sum = 0.0;
    for (size_t i = 0; i < truth.reference.data().size(); ++i) {
      const double d = f.reference.data()[i] - truth.reference.data()[i];
      sum += d * d;
    }
    rmse.push_back(std::sqrt(sum / truth.reference.data().size()));
  }
  INFO("rmse at 16, 64, 256 spp: " << rmse[0] << ", " << rmse[1] << ", " << rmse[2]);
  CHECK(rmse[1] < rmse[0] / 1.5);  // 1/sqrt(n): halves with every 4x
  CHECK(rmse[2] < rmse[1] / 1.5);
}

TEST_CASE("the same seed gives the same bits, on any thread count", "[gbuffer][determinism]") {
  const SceneDesc& scene = find_scene("cornell-moving");
  RenderSettings s = small(40, 32);
  s.reference_spp = 4;
  s.gradients = true;
  Frame one, two;
  tbb::task_arena(1).execute([&] { one = renderer().render(scene, 3, s); });
  tbb::task_arena(2).execute([&] { two = renderer().render(scene, 3, s); });
  CHECK(same_frame_bits(one, two));
  // A frame renders the same alone or after others.
  renderer().render(scene, 2, s);
  CHECK(same_frame_bits(one, renderer().render(scene, 3, s)));
  // Another seed changes the noise, not the G-buffer.
  s.seed = 2;
  const Frame other = renderer().render(scene, 3, s);
  CHECK_FALSE(same_bits(one.color.data(), other.color.data()));
  CHECK(same_bits(one.depth.data(), other.depth.data()));
  CHECK(same_bits(one.motion.data(), other.motion.data()));
}

TEST_CASE("committed manifests match the committed files", "[gbuffer][fixtures]") {
  uint64_t total = 0;
  for (const SceneDesc& scene : scene_library()) {
    const std::string dir = fixture_dir(scene.name);
    INFO(dir);
    const io::Manifest m = io::read_manifest(dir);
    CHECK(m.scene == scene.name);
    CHECK(m.generator == generator_tag());
    // The scene's defaults are the committed fixture's settings (`generate --all` remakes them).
    CHECK(m.width == scene.width);
    CHECK(m.height == scene.height);
    CHECK(m.frames.size() == static_cast<size_t>(scene.frames));
    CHECK(m.spp == scene.spp);
    CHECK(m.reference_spp == scene.reference_spp);
    std::vector<int> cuts;
    for (int c : scene.camera_cuts)
      if (c < static_cast<int>(m.frames.size())) cuts.push_back(c);
    CHECK(m.camera_cuts == cuts);
    for (const io::ManifestFile& file : m.frames) {
      INFO(file.name);
      CHECK(io::sha256_file(dir + "/" + file.name) == file.sha256);
    }
    // Gradient samples where the scene has them by default: none at frame 0, some at frame 1.
    const io::Sequence seq(dir);
    const Frame first = seq.read(0), second = seq.read(1);
    CHECK(first.gradient.empty() == !scene.gradients);
    CHECK(second.gradient.empty() == !scene.gradients);
    if (scene.gradients) {
      const std::vector<float>& m0 = first.gradient.data();
      CHECK(std::count(m0.begin(), m0.end(), 0.f) == static_cast<long>(m0.size()));
      const float* mask = second.gradient.plane(2);
      CHECK(std::count(mask, mask + second.gradient.pixel_count(), 1.f) > 100);
    }
    for (const auto& e : fs::directory_iterator(dir)) total += e.file_size();
  }
  CHECK(total <= 30u * 1000u * 1000u);
}

TEST_CASE("re-rendering a committed fixture's frame reproduces it", "[gbuffer][fixtures]") {
  struct Case {
    const char* scene;
    int frame;
  };
  // The light switches off at frame 6 of light-switch: its gradient samples darken there.
  for (const Case& c : {Case{"cornell-moving", 0}, Case{"camera-pan", 0}, Case{"light-switch", 6},
                        Case{"moving-shadow", 4}}) {
    const std::string name = c.scene;
    const io::Sequence seq(fixture_dir(name));
    RenderSettings s = settings_from_manifest(seq.manifest());
    s.reference_spp = 0;  // the 1024-spp reference is left to `svgf-fixtures verify`
    const Frame stored = seq.read(c.frame);
    s.gradients = !stored.gradient.empty();
    // Spread over the sequence's length as `eval` spreads its scenes: at the committed length
    // that is the scene itself, bit for bit.
    const Frame fresh = renderer().render(scene_over(find_scene(name), seq.size()), c.frame, s);
    CompareOptions options;
    options.reference = false;
    const std::vector<ChannelDiff> diffs = compare_frames(stored, fresh, fixture_storage(), options);
    for (const ChannelDiff& d : diffs) UNSCOPED_INFO(name << ": " << describe(d));
    CHECK(diffs.empty());
  }
}

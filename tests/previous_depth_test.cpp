// core/previous_depth.h: the view depth a pixel's point had in the previous camera, from the
// two cameras alone, against the same depth computed from the point's world position.
#include <cmath>
#include <string>

#include <catch2/catch.hpp>

#include "core/previous_depth.h"
#include "io/sequence.h"
#include "test_support.h"

using namespace svgf;

namespace {

// -(world_to_view * p).z in double.
double view_depth(const Camera& c, double x, double y, double z) {
  const auto& m = c.world_to_view;
  return -(m[8] * x + m[9] * y + m[10] * z + m[11]);
}

// A perspective camera at `eye` looking down -z (world axes), vertical field of view 60 degrees.
Camera looking_down_z(double ex, double ey, double ez, int width, int height) {
  Camera c;
  c.world_to_view = {1, 0, 0, float(-ex), 0, 1, 0, float(-ey), 0, 0, 1, float(-ez), 0, 0, 0, 1};
  const double ty = std::tan(30.0 * 3.14159265358979 / 180.0), tx = ty * width / height;
  const double n = 0.01, f = 1000.0;
  c.view_to_clip = {float(1 / tx), 0, 0, 0, 0, float(1 / ty), 0, 0, 0, 0, float(-(f + n) / (f - n)),
                    float(-2 * f * n / (f - n)), 0, 0, -1, 0};
  return c;
}

}  // namespace

TEST_CASE("previous depth: the same camera, or none, leaves the depth as it is",
          "[previous_depth]") {
  const Camera none;
  const Camera cam = looking_down_z(0.3, 1.0, 4.0, 64, 32);
  for (const Camera& c : {none, cam}) {
    const PreviousViewDepth d = PreviousViewDepth::between(c, c, 64, 32);
    REQUIRE(d.is_identity());
    for (float z : {0.f, 1e-3f, 2.5f, 1e6f})
      for (int x : {0, 17, 63}) REQUIRE(d.at(x, 31, z) == z);
  }
  // A projection whose w depends on x is not modelled: the depth is compared as it is.
  Camera odd = cam, moved = cam;
  odd.view_to_clip[12] = 0.1f;
  moved.world_to_view[11] -= 0.5f;  // half a unit further back
  REQUIRE(PreviousViewDepth::between(moved, odd, 64, 32).is_identity());
  REQUIRE_FALSE(PreviousViewDepth::between(moved, cam, 64, 32).is_identity());
  // Rounding residue where the model wants zeros (an importer's matrix products) is not a
  // different projection: the same depths as without it.
  Camera residue = cam, moved_residue = moved;
  residue.view_to_clip[12] = 3e-9f;
  residue.world_to_view[14] = -2e-9f;
  moved_residue.world_to_view[15] = 1.f + 1e-7f;
  const PreviousViewDepth clean = PreviousViewDepth::between(moved, cam, 64, 32);
  const PreviousViewDepth noisy = PreviousViewDepth::between(moved_residue, residue, 64, 32);
  REQUIRE_FALSE(noisy.is_identity());
  CHECK(noisy.at(40, 10, 2.f) == Approx(clean.at(40, 10, 2.f)).epsilon(1e-6));
}

TEST_CASE("previous depth: a dolly adds its distance, a side step nothing", "[previous_depth]") {
  const int w = 96, h = 54;
  const Camera now = looking_down_z(0.0, 1.0, 3.0, w, h);
  // The previous camera stood 0.25 further back: every point was 0.25 deeper then.
  const PreviousViewDepth back =
      PreviousViewDepth::between(looking_down_z(0.0, 1.0, 3.25, w, h), now, w, h);
  // One step to the side: view depth is unchanged for every point.
  const PreviousViewDepth side =
      PreviousViewDepth::between(looking_down_z(0.4, 1.0, 3.0, w, h), now, w, h);
  for (int y : {0, 20, h - 1})
    for (int x : {0, 50, w - 1})
      for (float z : {0.5f, 2.f, 7.f}) {
        CHECK(back.at(x, y, z) == Approx(z + 0.25f).epsilon(1e-6));
        CHECK(side.at(x, y, z) == Approx(z).epsilon(1e-6));
      }
}

// A camera at `eye` pitched up by `pitch` radians (a turn about the x axis), 60 degrees
// vertical field of view.
Camera pitched(double pitch, double ex, double ey, double ez, int width, int height) {
  Camera c = looking_down_z(0, 0, 0, width, height);
  const double cs = std::cos(pitch), sn = std::sin(pitch);
  // Rows of R_x(-pitch), the world-to-view rotation, then -R eye.
  const double r[3][3] = {{1, 0, 0}, {0, cs, sn}, {0, -sn, cs}};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) c.world_to_view[i * 4 + j] = float(r[i][j]);
    c.world_to_view[i * 4 + 3] = float(-(r[i][0] * ex + r[i][1] * ey + r[i][2] * ez));
  }
  return c;
}

TEST_CASE("previous depth: a turn and a step, against points placed behind the pixels",
          "[previous_depth]") {
  // Points at known depths behind pixel centres of the current camera (world position from
  // its own pose, in double), then their depth in the previous camera: every coefficient,
  // the x and y directions included, is exercised.
  const int w = 80, h = 45;
  const double pitch = 0.2, ex = 0.3, ey = 1.1, ez = 2.5;
  const Camera now = pitched(pitch, ex, ey, ez, w, h);
  const Camera before = pitched(0.26, 0.1, 1.3, 2.9, w, h);
  const PreviousViewDepth d = PreviousViewDepth::between(before, now, w, h);
  const double ty = std::tan(30.0 * 3.14159265358979 / 180.0), tx = ty * w / h;
  const double cs = std::cos(pitch), sn = std::sin(pitch);
  for (int y : {0, 7, 30, h - 1})
    for (int x : {0, 11, 50, w - 1})
      for (double z : {0.7, 2.0, 5.5}) {
        const double nx = (2.0 * x + 1.0) / w - 1.0, ny = 1.0 - (2.0 * y + 1.0) / h;
        const double vx = nx * tx * z, vy = ny * ty * z, vz = -z;
        // world = R^T v + eye (R's rows above, transposed)
        const double px = vx + ex, py = cs * vy - sn * vz + ey, pz = sn * vy + cs * vz + ez;
        const double expected = view_depth(before, px, py, pz);
        INFO("pixel " << x << "," << y << " depth " << z);
        CHECK(d.at(x, y, float(z)) == Approx(expected).epsilon(2e-6));
        CHECK(std::fabs(expected - z) > 0.02);  // the turn and step change it
      }
}

TEST_CASE("previous depth: the camera-pan fixture's points, as their world positions say",
          "[previous_depth]") {
  // The fixture's camera turns and moves sideways every frame; its frames carry the cameras and
  // the world position of every pixel's point (stored as half floats: about 1e-3 relative).
  const io::Sequence fixture(std::string(SVGF_SOURCE_DIR) + "/fixtures/camera-pan");
  const Frame prev = fixture.read(4), f = fixture.read(5);
  REQUIRE_FALSE(f.position.empty());
  const PreviousViewDepth d =
      PreviousViewDepth::between(prev.camera, f.camera, f.width(), f.height());
  double worst = 0, largest_change = 0;
  int surfaces = 0;
  for (int y = 0; y < f.height(); ++y)
    for (int x = 0; x < f.width(); ++x) {
      const float z = f.depth.at(x, y, 0);
      if (!(z > 0.f)) continue;
      ++surfaces;
      const double then = view_depth(prev.camera, f.position.at(x, y, 0), f.position.at(x, y, 1),
                                     f.position.at(x, y, 2));
      worst = std::max(worst, std::fabs(d.at(x, y, z) - then) / then);
      largest_change = std::max(largest_change, std::fabs(then - z) / z);
    }
  INFO("worst relative difference " << worst << ", largest depth change " << largest_change);
  REQUIRE(surfaces > f.width() * f.height() / 2);
  CHECK(largest_change > 0.02);  // what the current depth would have been off by
  CHECK(worst < 1e-3);
}

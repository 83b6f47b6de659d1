// The input rule (core/sanitize.h), the stage every method's frame passes first: on the CPU and
// CUDA (the same bits: tests/test_device.h compares every mapped plane), case by case.
#include <cmath>
#include <cstring>
#include <limits>
#include <utility>

#include <catch2/catch.hpp>

#include "core/sanitize.h"
#include "test_device.h"
#include "test_support.h"

using namespace svgf;
using svgf::test::StageRunner;
using svgf::test::TestDevice;

namespace {

using svgf::test::kNaN;
using svgf::test::kInf;

// One frame's inputs as separate images, every pixel a clean surface to start with.
struct Inputs {
  int w, h;
  Image color, albedo, emission, normal, position, depth, gradient, motion;
  Inputs(int w_, int h_)
      : w(w_), h(h_), color(w, h, 3, 0.5f), albedo(w, h, 3, 0.5f), emission(w, h, 3, 0.f),
        normal(w, h, 3, 0.f), position(w, h, 3, 1.f), depth(w, h, 1, 3.f), gradient(w, h, 2, 0.01f),
        motion(w, h, 2, 0.5f) {
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) normal.at(x, y, 2) = 1.f;
  }
  Image all() const {  // every plane of every input, for bitwise comparison
    Image a(w, h, 20);
    int p = 0;
    for (const Image* im : {&color, &albedo, &emission, &normal, &position, &depth, &gradient,
                            &motion})
      for (int c = 0; c < im->channels(); ++c, ++p)
        std::memcpy(a.plane(p), im->plane(c), im->pixel_count() * sizeof(float));
    return a;
  }
  // The kernel over these images in place (on the runner's device), `with_optional`: emission
  // and position are present.
  SanitizeInputs kernel(StageRunner& r, bool with_optional = true) {
    InputPlanesOut o;
    o.color = r.rgb(color);
    o.albedo = r.rgb(albedo);
    if (with_optional) o.emission = r.rgb(emission);
    o.normal = r.rgb(normal);
    if (with_optional) o.position = r.rgb(position);
    o.depth = r.plane(depth);
    o.depth_dx = r.plane(gradient, 0);
    o.depth_dy = r.plane(gradient, 1);
    o.motion_x = r.plane(motion, 0);
    o.motion_y = r.plane(motion, 1);
    return SanitizeInputs{w, read_only(o), o};
  }
  static InputPlanes read_only(const InputPlanesOut& o) {
    InputPlanes i;
    i.color = o.color;
    i.albedo = o.albedo;
    i.emission = o.emission;
    i.normal = o.normal;
    i.position = o.position;
    i.depth = o.depth;
    i.depth_dx = o.depth_dx;
    i.depth_dy = o.depth_dy;
    i.motion_x = o.motion_x;
    i.motion_y = o.motion_y;
    return i;
  }
  // The repair bits of every pixel, from a dry run on the host (nothing written).
  std::vector<uint32_t> masks() {
    StageRunner host(test::kCpu);
    SanitizeInputs k = kernel(host);
    k.out = InputPlanesOut{};
    std::vector<uint32_t> m;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) m.push_back(k(x, y));
    return m;
  }
};

bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void clean_input_untouched(const TestDevice& d) {
  Inputs in(8, 3);
  test::fill_uniform(in.color, 0.f, 50.f, 3);
  test::fill_uniform(in.position, -100.f, 100.f, 4);
  test::fill_uniform(in.motion, -40.f, 40.f, 5);
  test::fill_uniform(in.gradient, -2.f, 2.f, 6);
  // The edges of every range are still clean.
  in.color.at(0, 0, 0) = -0.f;
  in.color.at(1, 0, 0) = 1e-40f;  // subnormal
  in.color.at(2, 0, 0) = kMaxRadiance;
  in.albedo.at(3, 0, 0) = 0.f;
  in.albedo.at(4, 0, 1) = 1.f;
  in.normal.at(5, 0, 2) = 1.0001f;  // a half-float unit normal: |n|^2 = 1.0002
  in.normal.at(6, 0, 2) = 0.95f;    // |n|^2 = 0.9025, inside [0.81, 1.21]
  in.motion.at(7, 0, 0) = -kMaxMotion;
  in.depth.at(0, 1, 0) = 0.f;  // background, guides 0
  for (int c = 0; c < 3; ++c) in.normal.at(0, 1, c) = 0.f;
  in.depth.at(1, 1, 0) = -1.f;  // background by the negative-depth convention
  in.depth.at(2, 1, 0) = kMaxGuide;
  const Image before = in.all();
  for (uint32_t m : in.masks()) REQUIRE(m == 0u);
  StageRunner r(d);
  r.run(in.kernel(r), in.w, in.h);
  test::require_identical(in.all(), before, "clean input after the sanitize stage");
}

void each_bad_value_repaired(const TestDevice& d) {
  Inputs in(16, 2);
  auto px = [&](int x, int y) { return y * in.w + x; };
  in.color.at(0, 0, 0) = kNaN;
  in.color.at(1, 0, 1) = kInf;
  in.color.at(2, 0, 2) = -1.f;
  in.color.at(3, 0, 0) = 2e8f;  // above kMaxRadiance
  in.albedo.at(4, 0, 0) = kNaN;
  in.albedo.at(4, 0, 1) = 1.5f;
  in.albedo.at(4, 0, 2) = -0.2f;
  in.emission.at(5, 0, 0) = kInf;
  in.normal.at(6, 0, 2) = 2.f;
  in.normal.at(7, 0, 0) = 1e10f;
  in.normal.at(7, 0, 1) = 1e10f;
  in.normal.at(7, 0, 2) = 0.f;
  in.normal.at(8, 0, 2) = 0.f;  // zero length
  in.normal.at(9, 0, 0) = 3e38f;  // beyond kMaxGuide
  in.depth.at(10, 0, 0) = kNaN;
  in.depth.at(11, 0, 0) = kInf;
  in.depth.at(12, 0, 0) = 2e18f;  // above kMaxGuide
  in.gradient.at(13, 0, 0) = kInf;
  in.position.at(14, 0, 1) = kNaN;
  in.normal.at(1, 1, 0) = kNaN;
  in.motion.at(15, 0, 0) = kNaN;
  in.motion.at(15, 0, 1) = -1e30f;
  in.depth.at(0, 1, 0) = 0.f;  // background with a NaN normal
  in.normal.at(0, 1, 0) = kNaN;
  in.color.at(1, 1, 0) = kNaN;  // three kinds at one pixel
  in.depth.at(1, 1, 0) = kNaN;
  in.motion.at(1, 1, 1) = kInf;
  in.normal.at(2, 1, 2) = 1e-31f;  // too short to scale

  const std::vector<uint32_t> m = in.masks();
  StageRunner r(d);
  r.run(in.kernel(r), in.w, in.h);

  CHECK(m[px(0, 0)] == kRepairColor);
  CHECK(in.color.at(0, 0, 0) == 0.f);
  CHECK(in.color.at(0, 0, 1) == 0.5f);  // the other components are kept
  CHECK(m[px(1, 0)] == kRepairColor);
  CHECK(in.color.at(1, 0, 1) == 0.f);
  CHECK(m[px(2, 0)] == kRepairColor);
  CHECK(in.color.at(2, 0, 2) == 0.f);
  CHECK(m[px(3, 0)] == kRepairColor);
  CHECK(in.color.at(3, 0, 0) == 0.f);
  CHECK(m[px(4, 0)] == kRepairAlbedo);
  CHECK(in.albedo.at(4, 0, 0) == 1.f);
  CHECK(in.albedo.at(4, 0, 1) == 1.f);
  CHECK(in.albedo.at(4, 0, 2) == 0.f);
  CHECK(m[px(5, 0)] == kRepairEmission);
  CHECK(in.emission.at(5, 0, 0) == 0.f);
  CHECK(m[px(6, 0)] == kRepairNormal);
  CHECK(in.normal.at(6, 0, 2) == 1.f);
  CHECK(m[px(7, 0)] == kRepairNormal);
  CHECK(in.normal.at(7, 0, 0) == 1.f / std::sqrt(2.f));
  CHECK(in.normal.at(7, 0, 1) == 1.f / std::sqrt(2.f));
  for (int x : {8, 9, 10, 11, 12, 13, 14}) {
    INFO("pixel " << x << " becomes background");
    CHECK(m[px(x, 0)] == kRepairSurface);
    CHECK(same_bits(in.depth.at(x, 0, 0), 0.f));
    for (int c = 0; c < 2; ++c) CHECK(same_bits(in.gradient.at(x, 0, c), 0.f));
    for (int c = 0; c < 3; ++c) CHECK(same_bits(in.normal.at(x, 0, c), 0.f));
    for (int c = 0; c < 3; ++c) CHECK(same_bits(in.position.at(x, 0, c), 0.f));
    CHECK(in.color.at(x, 0, 0) == 0.5f);  // color and motion are another matter
    CHECK(in.motion.at(x, 0, 0) == 0.5f);
  }
  CHECK(m[px(15, 0)] == kRepairMotion);
  CHECK(in.motion.at(15, 0, 0) == kMaxMotion);
  CHECK(in.motion.at(15, 0, 1) == -kMaxMotion);
  CHECK(m[px(0, 1)] == kRepairSurface);
  CHECK(in.normal.at(0, 1, 0) == 0.f);
  CHECK(m[px(1, 1)] == (kRepairColor | kRepairSurface | kRepairMotion));
  CHECK(in.color.at(1, 1, 0) == 0.f);
  CHECK(in.depth.at(1, 1, 0) == 0.f);
  CHECK(in.motion.at(1, 1, 1) == kMaxMotion);
  CHECK(m[px(2, 1)] == kRepairSurface);
  for (int x = 3; x < in.w; ++x) CHECK(m[px(x, 1)] == 0u);
  const Image all = in.all();
  for (float v : all.data()) REQUIRE(std::isfinite(v));
}

// Without emission and position planes, neither is read or written.
void optional_planes_absent(const TestDevice& d) {
  Inputs in(4, 1);
  in.emission.at(1, 0, 0) = kNaN;
  in.position.at(2, 0, 0) = kNaN;
  StageRunner r(d);
  SanitizeInputs k = in.kernel(r, /*with_optional=*/false);
  r.run(k, in.w, in.h);
  REQUIRE(std::isnan(in.emission.at(1, 0, 0)));
  REQUIRE(std::isnan(in.position.at(2, 0, 0)));
  REQUIRE(in.depth.at(2, 0, 0) == 3.f);  // no position plane: not a reason to drop the surface
}

}  // namespace

SVGF_BACKEND_TEST("sanitize: clean input keeps every bit, range edges included", "[sanitize]",
                  clean_input_untouched)
SVGF_BACKEND_TEST("sanitize: each kind of bad value is repaired as documented and flagged",
                  "[sanitize]", each_bad_value_repaired)
SVGF_BACKEND_TEST("sanitize: absent emission and position planes are not touched", "[sanitize]",
                  optional_planes_absent)

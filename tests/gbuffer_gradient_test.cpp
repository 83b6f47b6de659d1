// A-SVGF gradient samples of the fixture renderer (gbuffer/gradient_samples.h) and the
// time-dependent emission of the light-switch scene (issue 12).
#include <tbb/task_arena.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "gbuffer/frame_scene.h"
#include "gbuffer/gradient_samples.h"
#include "gbuffer/renderer.h"
#include "gbuffer/scenes.h"
#include "gbuffer_test_support.h"

using namespace svgf;
using namespace svgf::gbuffer;

namespace {

using svgf::test::renderer;

Frame render(const std::string& scene, int frame, int w, int h) {
  RenderSettings s;
  s.width = w;
  s.height = h;
  s.split = false;
  s.gradients = true;
  return renderer().render(find_scene(scene), frame, s);
}

struct Sample {
  int x = 0, y = 0;
  float previous = 0.f, current = 0.f;
  uint32_t mesh_id = 0;
};

// The samples of a frame's gradient group, checking its layout on the way: the mask is 0 or 1,
// both luminances are 0 beside it, and each 3x3 stratum holds at most one sample.
std::vector<Sample> samples_of(const Frame& f) {
  REQUIRE(f.gradient.channels() == 3);
  REQUIRE(f.gradient.width() == f.width());
  const int w = f.width(), h = f.height(), nx = (w + kGradientStratum - 1) / kGradientStratum;
  const int ny = (h + kGradientStratum - 1) / kGradientStratum;
  std::vector<int> per_stratum(static_cast<size_t>(nx) * ny, 0);
  std::vector<Sample> out;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float m = f.gradient.at(x, y, 2);
      if (m == 0.f) {
        CHECK(f.gradient.at(x, y, 0) == 0.f);
        CHECK(f.gradient.at(x, y, 1) == 0.f);
        continue;
      }
      REQUIRE(m == 1.f);
      ++per_stratum[static_cast<size_t>(y / kGradientStratum) * nx + x / kGradientStratum];
      out.push_back({x, y, f.gradient.at(x, y, 0), f.gradient.at(x, y, 1),
                     f.mesh_id[static_cast<size_t>(y) * w + x]});
    }
  for (int n : per_stratum) CHECK(n <= 1);
  return out;
}

uint32_t mesh_id_of(const std::string& scene, const std::string& object) {
  const SceneDesc& s = find_scene(scene);
  for (size_t i = 0; i < s.objects.size(); ++i)
    if (s.objects[i].name == object) return static_cast<uint32_t>(i + 1);
  FAIL("no object " << object << " in " << scene);
  return 0;
}

bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

}  // namespace

TEST_CASE("gradient samples: none at frame 0 or a camera cut, at most one per stratum",
          "[gbuffer][gradient]") {
  // 20x16: the last column and row of strata are partial (2 and 1 pixels).
  for (int frame : {0, 6}) {
    const Frame f = render("cut", frame, 20, 16);
    INFO("frame " << frame);
    CHECK(samples_of(f).empty());
  }
  const std::vector<Sample> s = samples_of(render("cut", 7, 20, 16));
  CHECK(s.size() > 7u * 6u / 2u);
  for (const Sample& x : s) CHECK(x.mesh_id != 0u);
}

// On still surfaces the re-shaded path is the previous one: the same point, normal, random
// numbers, lights and geometry. Only the view direction differs, and a Lambertian path does not
// see it (it decides which side of a two-sided quad is lit, and a surface seen from both frames
// is seen from the same side), so current == previous to the bit, not just within a tolerance.
TEST_CASE("gradient samples on still surfaces re-shade to the same bits", "[gbuffer][gradient]") {
  SECTION("still camera: each sample stays at its pixel and is that pixel's color sample") {
    const int w = 32, h = 32, n = (w + 2) / 3;
    const Frame before = render("cornell-static", 2, w, h);
    const Frame now = render("cornell-static", 3, w, h);
    int expected = 0;
    for (int sy = 0; sy < n; ++sy)
      for (int sx = 0; sx < n; ++sx) {
        const StratumPick p = pick_in_stratum(1, 2, sx, sy, w, h);
        REQUIRE(p.x / 3 == sx);
        REQUIRE(p.y / 3 == sy);
        if (before.mesh_id[static_cast<size_t>(p.y) * w + p.x] == 0) continue;
        ++expected;
        INFO("stratum " << sx << "," << sy << " pixel " << p.x << "," << p.y);
        REQUIRE(now.gradient.at(p.x, p.y, 2) == 1.f);
        const Vec3 c = make_vec3(before.color.at(p.x, p.y, 0), before.color.at(p.x, p.y, 1),
                                 before.color.at(p.x, p.y, 2));
        CHECK(same_bits(now.gradient.at(p.x, p.y, 0), luminance(c)));
      }
    const std::vector<Sample> s = samples_of(now);
    CHECK(static_cast<int>(s.size()) == expected);
    CHECK(expected > n * n / 2);
    for (const Sample& x : s) CHECK(same_bits(x.current, x.previous));
  }
  SECTION("moving camera") {
    const std::vector<Sample> s = samples_of(render("camera-pan", 3, 32, 32));
    CHECK(s.size() > 11u * 11u * 2u / 3u);
    for (const Sample& x : s) CHECK(same_bits(x.current, x.previous));
  }
}

TEST_CASE("light-switch: light-a goes dark at frame 6, and the gradient samples see it",
          "[gbuffer][gradient][light]") {
  const SceneDesc& scene = find_scene("light-switch");
  CHECK(FrameScene(renderer().device(), scene, 5, 8, 8).lights().size() == 2u);
  CHECK(FrameScene(renderer().device(), scene, 6, 8, 8).lights().size() == 1u);
  const uint32_t light_a = mesh_id_of("light-switch", "light-a");
  const int w = 32, h = 32;
  const Frame on = render("light-switch", 5, w, h), off = render("light-switch", 6, w, h);
  int seen = 0;
  for (int i = 0; i < w * h; ++i) {
    if (on.mesh_id[i] != light_a) continue;
    ++seen;
    CHECK(on.emission.plane(0)[i] > 0.f);
    CHECK(on.color.plane(0)[i] == on.emission.plane(0)[i]);
    CHECK(off.emission.plane(0)[i] == 0.f);
    CHECK(off.color.plane(0)[i] == 0.f);
  }
  CHECK(seen > 0);
  // Before and after the switch nothing changes; at the switch most of the room darkens.
  for (const Sample& x : samples_of(on)) CHECK(same_bits(x.current, x.previous));
  for (const Sample& x : samples_of(render("light-switch", 8, w, h)))
    CHECK(same_bits(x.current, x.previous));
  const std::vector<Sample> s = samples_of(off);
  double before = 0.0, after = 0.0;
  size_t darkened = 0;
  for (const Sample& x : s) {
    before += x.previous;
    after += x.current;
    if (x.current < 0.5f * x.previous) ++darkened;
  }
  INFO(s.size() << " samples, " << darkened << " darkened by half, luminance " << before << " -> "
                << after);
  CHECK(s.size() > 11u * 11u / 2u);
  CHECK(after < 0.7 * before);
  CHECK(darkened > s.size() / 4);
}

TEST_CASE("moving-shadow: floor samples change where the shadow passes", "[gbuffer][gradient]") {
  const uint32_t floor = mesh_id_of("moving-shadow", "floor");
  const std::vector<Sample> s = samples_of(render("moving-shadow", 5, 48, 48));
  size_t on_floor = 0, changed = 0, kept = 0;
  for (const Sample& x : s) {
    if (x.mesh_id != floor) continue;
    ++on_floor;
    const float d = std::fabs(x.current - x.previous), m = std::fmax(x.current, x.previous);
    if (d > 0.5f * m) ++changed;  // the light sample's shadow ray is blocked in one frame only
    if (d <= 0.01f * m) ++kept;
  }
  INFO(s.size() << " samples, " << on_floor << " on the floor: " << changed << " changed, " << kept
                << " kept");
  CHECK(on_floor > 40u);
  CHECK(changed >= 4u);
  CHECK(kept > on_floor * 3 / 4);
}

TEST_CASE("gradient samples are the same bits on any thread count", "[gbuffer][gradient][determinism]") {
  Frame one, two;
  tbb::task_arena(1).execute([&] { one = render("cornell-moving", 4, 40, 32); });
  tbb::task_arena(2).execute([&] { two = render("cornell-moving", 4, 40, 32); });
  REQUIRE(one.gradient.data().size() == two.gradient.data().size());
  CHECK(std::memcmp(one.gradient.data().data(), two.gradient.data().data(),
                    one.gradient.data().size() * sizeof(float)) == 0);
  // The cube moved: some of its samples were carried to another pixel and shade differently.
  const uint32_t cube = mesh_id_of("cornell-moving", "cube");
  size_t on_cube = 0;
  for (const Sample& x : samples_of(one)) on_cube += x.mesh_id == cube;
  CHECK(on_cube > 3u);
}

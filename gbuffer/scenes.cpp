#include "gbuffer/scenes.h"

#include <stdexcept>

#include "gbuffer/shapes.h"

namespace svgf::gbuffer {

namespace {

using V = glm::dvec3;

// Classic Cornell box reflectances.
const Material kWhite = diffuse(0.725f, 0.71f, 0.68f);
const Material kRed = diffuse(0.63f, 0.065f, 0.05f);
const Material kGreen = diffuse(0.14f, 0.45f, 0.091f);
const Material kBlue = diffuse(0.10f, 0.18f, 0.55f);
const Material kLight = emitter(34.f, 28.f, 20.f);

// Room [-1,1] x [0,2] x [-1,1], open at the front, without a light.
void add_cornell_walls(SceneDesc& s) {
  const V lo(-1, 0, -1), hi(1, 2, 1);
  s.objects.push_back(placed("floor", kWhite, {room_face(lo, hi, kFloor)}, V(0)));
  s.objects.push_back(placed("ceiling", kWhite, {room_face(lo, hi, kCeiling)}, V(0)));
  s.objects.push_back(placed("back", kWhite, {room_face(lo, hi, kBack)}, V(0)));
  s.objects.push_back(placed("left", kRed, {room_face(lo, hi, kLeft)}, V(0)));
  s.objects.push_back(placed("right", kGreen, {room_face(lo, hi, kRight)}, V(0)));
}

// The room with a 0.5 x 0.5 ceiling light.
void add_cornell_room(SceneDesc& s) {
  add_cornell_walls(s);
  s.objects.push_back(
      placed("light", kLight, {ceiling_light(-0.25, 1.998, -0.25, 0.5, 0.5)}, V(0)));
}

// Looking straight down -z, slightly off-centre: from the exact centre the box's corner edges
// would project onto pixel centres, and rays through them would tie between two walls.
CameraPose cornell_view() { return {V(0.013, 1.011, 3.9), V(0.013, 1.011, 0), 38.0}; }

SceneDesc cornell_static() {
  SceneDesc s;
  s.name = "cornell-static";
  s.summary = "Cornell box, two boxes, static camera: accumulation should converge";
  add_cornell_room(s);
  s.objects.push_back(placed("tall-box", kWhite, box(V(0.6, 1.2, 0.6)), V(-0.35, 0, -0.3), 0.05));
  s.objects.push_back(placed("short-box", kWhite, box(V(0.6, 0.6, 0.6)), V(0.35, 0, 0.35), -0.05));
  s.camera = [](double) { return cornell_view(); };
  return s;
}

SceneDesc cornell_moving() {
  SceneDesc s;
  s.name = "cornell-moving";
  s.summary = "Cornell box, a blue cube sliding and spinning across it: disocclusion, ghosting";
  add_cornell_room(s);
  s.objects.push_back(placed("tall-box", kWhite, box(V(0.6, 1.2, 0.6)), V(-0.35, 0, -0.3), 0.05));
  s.objects.push_back(make_object("cube", kBlue, box(V(0.45, 0.45, 0.45)), [](double t) {
    return Pose{V(-0.6 + 0.1 * t, 0.0, 0.3), 0.012 * t};
  }));
  s.camera = [](double) { return cornell_view(); };
  return s;
}

SceneDesc camera_pan() {
  SceneDesc s;
  s.name = "camera-pan";
  s.summary = "closed room, camera translating sideways and turning: reprojection by camera motion";
  const V lo(-2, 0, -2), hi(2, 2.4, 2);
  s.objects.push_back(placed("floor", kWhite, {room_face(lo, hi, kFloor)}, V(0)));
  s.objects.push_back(placed("ceiling", kWhite, {room_face(lo, hi, kCeiling)}, V(0)));
  s.objects.push_back(placed("back", kWhite, {room_face(lo, hi, kBack)}, V(0)));
  s.objects.push_back(placed("front", kWhite, {room_face(lo, hi, kFront)}, V(0)));
  s.objects.push_back(placed("left", kRed, {room_face(lo, hi, kLeft)}, V(0)));
  s.objects.push_back(placed("right", kBlue, {room_face(lo, hi, kRight)}, V(0)));
  s.objects.push_back(placed("light-a", kLight, {ceiling_light(-1.4, 2.398, -1.2, 0.9, 0.9)}, V(0)));
  s.objects.push_back(placed("light-b", kLight, {ceiling_light(0.4, 2.398, -0.4, 0.9, 0.9)}, V(0)));
  s.objects.push_back(placed("pillar", kWhite, box(V(0.4, 2.4, 0.4)), V(-0.9, 0, -0.9), 0.1));
  s.objects.push_back(placed("crate", kGreen, box(V(0.7, 0.7, 0.7)), V(0.5, 0, -0.6), 0.08));
  s.objects.push_back(placed("block", kWhite, box(V(0.5, 1.0, 0.5)), V(1.2, 0, -1.4), -0.04));
  s.camera = [](double t) {
    return CameraPose{V(-0.8 + 0.12 * t, 1.2, 1.6), V(0.7 - 0.1 * t, 0.9, -2.0), 60.0};
  };
  return s;
}

SceneDesc textured() {
  SceneDesc s;
  s.name = "textured";
  s.summary = "checker floor, striped and tiled walls, slow dolly: demodulation must keep texture sharp";
  const V lo(-1, 0, -1), hi(1, 2, 1);
  const Vec3 light = make_vec3(0.8f, 0.78f, 0.74f), dark = make_vec3(0.08f, 0.08f, 0.09f);
  s.objects.push_back(placed("floor", patterned(Pattern::Checker, light, dark, 0.2f),
                             {room_face(lo, hi, kFloor)}, V(0)));
  s.objects.push_back(placed("ceiling", kWhite, {room_face(lo, hi, kCeiling)}, V(0)));
  s.objects.push_back(placed("back", patterned(Pattern::Tiles, make_vec3(0.7f, 0.55f, 0.4f),
                                               make_vec3(0.15f, 0.12f, 0.1f), 0.25f),
                             {room_face(lo, hi, kBack)}, V(0)));
  s.objects.push_back(placed("left", patterned(Pattern::Stripes, make_vec3(0.63f, 0.065f, 0.05f),
                                               make_vec3(0.7f, 0.7f, 0.65f), 0.1f),
                             {room_face(lo, hi, kLeft)}, V(0)));
  s.objects.push_back(placed("right", patterned(Pattern::Stripes, make_vec3(0.14f, 0.45f, 0.091f),
                                                make_vec3(0.7f, 0.7f, 0.65f), 0.15f),
                             {room_face(lo, hi, kRight)}, V(0)));
  s.objects.push_back(
      placed("light", kLight, {ceiling_light(-0.25, 1.998, -0.25, 0.5, 0.5)}, V(0)));
  s.objects.push_back(placed("box", patterned(Pattern::Checker, make_vec3(0.2f, 0.3f, 0.7f),
                                              make_vec3(0.8f, 0.8f, 0.8f), 0.1f),
                             box(V(0.6, 0.6, 0.6)), V(0.3, 0, -0.2), 0.07));
  s.camera = [](double t) {
    return CameraPose{V(0.25 - 0.03 * t, 1.0 + 0.01 * t, 3.7 - 0.04 * t), V(0, 0.8, 0), 38.0};
  };
  return s;
}

SceneDesc thin() {
  SceneDesc s;
  s.name = "thin";
  s.summary = "a fence of 1-2 pixel bars and sub-pixel rails before a lit wall, camera drifting";
  const V lo(-1.5, 0, -1), hi(1.5, 2, 1);
  s.objects.push_back(placed("floor", kWhite, {room_face(lo, hi, kFloor)}, V(0)));
  s.objects.push_back(placed("ceiling", kWhite, {room_face(lo, hi, kCeiling)}, V(0)));
  s.objects.push_back(placed("wall", diffuse(0.8f, 0.75f, 0.6f), {room_face(lo, hi, kBack)}, V(0)));
  s.objects.push_back(placed("left", kRed, {room_face(lo, hi, kLeft)}, V(0)));
  s.objects.push_back(placed("right", kBlue, {room_face(lo, hi, kRight)}, V(0)));
  s.objects.push_back(placed("light", kLight, {ceiling_light(-0.8, 1.998, -0.95, 1.6, 0.3)}, V(0)));
  std::vector<LocalQuad> fence;
  auto add_box = [&fence](const V& size, const V& at) {
    for (LocalQuad q : box(size)) {
      q.o += at;
      fence.push_back(q);
    }
  };
  for (int k = 0; k < 17; ++k) add_box(V(0.03, 1.5, 0.03), V(-1.2 + 0.15 * k, 0, 0));
  add_box(V(2.5, 0.012, 0.02), V(0, 0.55, 0.03));
  add_box(V(2.5, 0.012, 0.02), V(0, 1.25, 0.03));
  s.objects.push_back(make_object("fence", diffuse(0.3f, 0.3f, 0.32f), fence));
  s.camera = [](double t) {
    return CameraPose{V(-0.3 + 0.04 * t, 1.0, 3.4), V(-0.1 + 0.02 * t, 0.9, 0), 42.0};
  };
  return s;
}

SceneDesc cut() {
  SceneDesc s;
  s.name = "cut";
  s.summary = "Cornell box seen from the front, then (frame 6 on) from a high corner: history must reset";
  add_cornell_room(s);
  s.objects.push_back(placed("tall-box", kWhite, box(V(0.6, 1.2, 0.6)), V(-0.35, 0, -0.3), 0.05));
  s.objects.push_back(placed("short-box", kWhite, box(V(0.6, 0.6, 0.6)), V(0.35, 0, 0.35), -0.05));
  constexpr int kCut = 6;
  s.camera = [](double t) {
    if (t < kCut) return CameraPose{V(-0.213 + 0.04 * t, 1.011, 3.9), V(0, 1, 0), 38.0};
    return CameraPose{V(0.7 - 0.03 * (t - kCut), 1.7, 0.9), V(-0.3, 0.3, -0.4), 55.0};
  };
  s.camera_cuts = {kCut};
  return s;
}

// Scenes for anti-lag (A-SVGF's temporal gradients): lighting that changes where nothing moves.
// Small committed fixtures (64x64) with gradient samples, to stay within the fixture budget.
void anti_lag_defaults(SceneDesc& s) {
  s.width = 64;
  s.height = 64;
  s.gradients = true;
}

SceneDesc moving_shadow() {
  SceneDesc s;
  s.name = "moving-shadow";
  s.summary = "a slab floating across under a small light: its hard shadow sweeps over the floor";
  anti_lag_defaults(s);
  const V lo(-1.2, 0, -1.2), hi(1.2, 2, 1.2);
  s.objects.push_back(placed("floor", kWhite, {room_face(lo, hi, kFloor)}, V(0)));
  s.objects.push_back(placed("ceiling", kWhite, {room_face(lo, hi, kCeiling)}, V(0)));
  s.objects.push_back(placed("back", kWhite, {room_face(lo, hi, kBack)}, V(0)));
  s.objects.push_back(placed("left", kRed, {room_face(lo, hi, kLeft)}, V(0)));
  s.objects.push_back(placed("right", kGreen, {room_face(lo, hi, kRight)}, V(0)));
  // 0.16 m square, as bright in total as the Cornell light: a penumbra of ~6 cm on the floor.
  s.objects.push_back(placed("light", emitter(332.f, 273.f, 195.f),
                             {ceiling_light(-0.07, 1.998, -0.21, 0.16, 0.16)}, V(0)));
  // 96x96: a shadow must be wider than the a-trous footprint (~30 px) for its contrast to be
  // measurable, as shadows at 1080p are; at 64x64 with a 0.5 m slab (~15 px) no configuration
  // kept 75% of it (docs/svgf.md). The 1 m slab, 0.6 m above the floor, casts a ~1.4 m shadow
  // (~55 px) that moves 0.10 m (~4 px) a frame. Seen from above, in front of the slab, so the
  // slab hides none of its shadow.
  s.width = s.height = 96;
  s.objects.push_back(make_object("slab", kBlue, box(V(1.0, 0.06, 1.0)), [](double t) {
    return Pose{V(-0.99 + 0.10 * t, 0.6, -0.12), 0.01 * t};
  }));
  s.camera = [](double) {
    return CameraPose{V(0.031, 1.85, 1.6), V(0.017, 0.0, -0.3), 55.0};
  };
  return s;
}

SceneDesc light_switch() {
  SceneDesc s;
  s.name = "light-switch";
  s.summary = "Cornell box lit by two lights; the larger switches off at frame 6";
  anti_lag_defaults(s);
  constexpr int kSwitch = 6;
  add_cornell_walls(s);
  Object a = placed("light-a", kLight, {ceiling_light(-0.75, 1.998, -0.45, 0.45, 0.45)}, V(0));
  a.emission_scale = [](double t) { return t < kSwitch ? 1.f : 0.f; };
  s.objects.push_back(a);
  s.objects.push_back(placed("light-b", emitter(20.f, 24.f, 30.f),
                             {ceiling_light(0.4, 1.998, 0.05, 0.35, 0.35)}, V(0)));
  s.objects.push_back(placed("tall-box", kWhite, box(V(0.5, 1.1, 0.5)), V(-0.4, 0, -0.35), 0.06));
  s.objects.push_back(placed("short-box", kWhite, box(V(0.55, 0.55, 0.55)), V(0.4, 0, 0.3), -0.05));
  s.camera = [](double) { return cornell_view(); };
  return s;
}

}  // namespace

const std::vector<SceneDesc>& scene_library() {
  static const std::vector<SceneDesc> scenes = {
      cornell_static(), cornell_moving(), camera_pan(), textured(),
      thin(),           cut(),            moving_shadow(), light_switch()};
  return scenes;
}

const SceneDesc& find_scene(const std::string& name) {
  std::string known;
  for (const SceneDesc& s : scene_library()) {
    if (s.name == name) return s;
    known += (known.empty() ? "" : ", ") + s.name;
  }
  throw std::invalid_argument("unknown scene '" + name + "' (known: " + known + ")");
}

}  // namespace svgf::gbuffer

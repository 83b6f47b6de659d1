#pragma once
// Scene descriptions: a handful of rigidly animated objects made of planar quads, Lambertian
// materials with constant or procedural albedo, and one-sided quad area emitters. Defined in code
// (scenes.cpp); everything is a function of the frame number, so any frame can be built alone.
#include <functional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/vec.h"
#include "gbuffer/camera.h"
#include "gbuffer/transform.h"

namespace svgf::gbuffer {

// Procedural albedo patterns, evaluated in metres on each quad from its first corner along its
// two edges (so a pattern moves with its object).
enum class Pattern { Constant, Checker, Stripes, Tiles };

struct Material {
  Vec3 albedo = make_vec3(0.7f, 0.7f, 0.7f);
  Vec3 albedo2 = make_vec3(0.2f, 0.2f, 0.2f);  // second colour of a pattern
  Pattern pattern = Pattern::Constant;
  float scale = 0.25f;                         // pattern period in metres
  Vec3 emission = make_vec3(0.f, 0.f, 0.f);    // radiance leaving the front side
  bool is_emitter() const { return emission.x > 0.f || emission.y > 0.f || emission.z > 0.f; }
};

// A parallelogram: corners o, o+e1, o+e1+e2, o+e2. Its front side faces cross(e1, e2).
struct LocalQuad {
  glm::dvec3 o{0.0}, e1{0.0}, e2{0.0};
};

struct Object {
  std::string name;
  Material material;
  std::vector<LocalQuad> quads;             // object space
  std::function<Pose(double frame)> pose;   // empty: identity at every frame
  // Emitters: factor on material.emission at a frame (a light switching off or dimming); empty:
  // 1. Geometry stays: an emitter at 0 is a black quad that reflects nothing and is not sampled.
  std::function<float(double frame)> emission_scale;
};

struct SceneDesc {
  std::string name;
  std::string summary;
  std::vector<Object> objects;              // mesh id of objects[i] is i + 1
  std::function<CameraPose(double frame)> camera;
  std::vector<int> camera_cuts;             // frames whose camera does not follow the previous one
  // Defaults of `svgf-fixtures generate` (the committed fixtures use them).
  int width = 128;
  int height = 128;
  int frames = 12;
  int spp = 1;
  int reference_spp = 1024;
  bool gradients = false;  // A-SVGF gradient samples (RenderSettings::gradients)

  Pose object_pose(size_t object, double frame) const {
    const auto& f = objects[object].pose;
    return f ? f(frame) : Pose{};
  }
  // Radiance the object's front side emits at `frame` (0 for non-emitters).
  Vec3 object_emission(size_t object, double frame) const {
    const Object& o = objects[object];
    return o.emission_scale ? o.material.emission * o.emission_scale(frame) : o.material.emission;
  }
};

// Albedo of `m` at pattern coordinates (u, v) in metres.
Vec3 pattern_albedo(const Material& m, float u, float v);

}  // namespace svgf::gbuffer

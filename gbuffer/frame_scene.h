#pragma once
// One frame of a scene, ready to trace: objects posed at this frame, an Embree BVH over them, the
// emitters for next-event estimation, and this and the previous frame's cameras and object
// transforms (for motion vectors). Embree only decides which quad a ray hits first; the hit
// distance and point are recomputed here from that quad's plane in plain float arithmetic, so the
// results do not depend on Embree's SIMD width, FMA use or BVH layout.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/vec.h"
#include "gbuffer/camera.h"
#include "gbuffer/scene.h"
#include "gbuffer/transform.h"

namespace svgf::gbuffer {

// Owns an Embree device; one per renderer, shared by its frames.
class EmbreeDevice {
 public:
  EmbreeDevice();
  ~EmbreeDevice();
  EmbreeDevice(const EmbreeDevice&) = delete;
  EmbreeDevice& operator=(const EmbreeDevice&) = delete;
  void* handle() const { return device_; }  // RTCDevice
  void check(const char* what) const;       // throws std::runtime_error on a pending error

 private:
  void* device_ = nullptr;
};

// A quad in world space at this frame (float, as Embree sees it).
struct WorldQuad {
  Vec3 v0, e1, e2;
  Vec3 n;               // unit normal of the front side
  Vec3 u_axis, v_axis;  // unit e1 and e2: pattern coordinates in metres
};

// An emitter quad that emits at this frame (one switched off is not a light).
struct Light {
  int object = 0, quad = 0;
  Vec3 v0, e1, e2, n;
  float area = 0.f;
  Vec3 emission;
  float cdf = 0.f;  // selection probability proportional to power, cumulated
  float pick = 0.f; // selection probability of this light
};

struct Hit {
  int object = -1;  // index into SceneDesc::objects; -1: miss
  int quad = -1;
  float t = 0.f;
  Vec3 p;           // o + t d
  Vec3 n;           // unit normal of the quad's front side
  bool valid() const { return object >= 0; }
};

class FrameScene {
 public:
  FrameScene(const EmbreeDevice& device, const SceneDesc& scene, int frame, int width, int height);
  ~FrameScene();
  FrameScene(const FrameScene&) = delete;
  FrameScene& operator=(const FrameScene&) = delete;

  // Closest hit with t in (0, tmax).
  Hit intersect(Vec3 o, Vec3 d, float tmax) const;
  // Any hit with t in (0, tmax).
  bool occluded(Vec3 o, Vec3 d, float tmax) const;

  const SceneDesc& desc() const { return *desc_; }
  int frame() const { return frame_; }
  const CameraModel& camera() const { return camera_; }
  const CameraModel& prev_camera() const { return prev_camera_; }
  const RigidTransform& transform(int object) const { return transforms_[object]; }
  const RigidTransform& prev_transform(int object) const { return prev_transforms_[object]; }
  // Whether the object's pose differs from the previous frame's (static ones skip the round trip
  // through object space, so their motion is exactly camera motion).
  bool moved(int object) const { return moved_[object] != 0; }
  const Material& material(int object) const { return desc_->objects[object].material; }
  // Radiance the object's front side emits at this frame (material emission times its scale).
  Vec3 emission(int object) const { return emission_[object]; }
  const WorldQuad& quad(int object, int q) const { return quads_[object][q]; }
  const std::vector<Light>& lights() const { return lights_; }
  Vec3 albedo(const Hit& hit) const;  // pattern albedo at the hit (emitters: their albedo field)

 private:
  void build(const EmbreeDevice& device);  // posed quads, lights and the BVH

  const SceneDesc* desc_;
  int frame_;
  CameraModel camera_, prev_camera_;
  std::vector<RigidTransform> transforms_, prev_transforms_;
  std::vector<char> moved_;
  std::vector<Vec3> emission_;
  std::vector<std::vector<WorldQuad>> quads_;
  std::vector<Light> lights_;
  void* scene_ = nullptr;  // RTCScene
};

// Offset along the normal that keeps a new ray off the surface it leaves.
inline float ray_offset(Vec3 p) {
  const float m = max_f(max_f(abs_f(p.x), abs_f(p.y)), abs_f(p.z));
  return 1e-4f * (1.f + m);
}

}  // namespace svgf::gbuffer

#include "gbuffer/frame_scene.h"

#include <embree3/rtcore.h>

#include <cmath>
#include <stdexcept>

#include "gbuffer/vec_ops.h"

namespace svgf::gbuffer {

namespace {

Vec3 to_float(const glm::dvec3& v) {
  return make_vec3(static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z));
}
glm::dvec3 unit(const glm::dvec3& v) { return v / std::sqrt(glm::dot(v, v)); }

}  // namespace

EmbreeDevice::EmbreeDevice() {
  // The same Embree kernels on every x86-64 CPU with AVX (8 wide, no FMA), so which quad a ray
  // hits does not depend on the machine (AVX2/AVX-512 kernels use FMA); Embree's default where
  // AVX is unavailable. About 1.3x slower than AVX-512 here.
  RTCDevice dev = rtcNewDevice("isa=avx");
  if (!dev) dev = rtcNewDevice(nullptr);
  if (!dev) throw std::runtime_error("embree: cannot create a device");
  device_ = dev;
}

EmbreeDevice::~EmbreeDevice() { rtcReleaseDevice(static_cast<RTCDevice>(device_)); }

void EmbreeDevice::check(const char* what) const {
  const RTCError e = rtcGetDeviceError(static_cast<RTCDevice>(device_));
  if (e != RTC_ERROR_NONE)
    throw std::runtime_error(std::string("embree: ") + what + " failed (error " +
                             std::to_string(static_cast<int>(e)) + ")");
}

FrameScene::FrameScene(const EmbreeDevice& device, const SceneDesc& scene, int frame, int width,
                       int height)
    : desc_(&scene), frame_(frame) {
  if (!scene.camera) throw std::invalid_argument("scene '" + scene.name + "' has no camera");
  camera_ = CameraModel(scene.camera(frame), width, height);
  prev_camera_ = CameraModel(scene.camera(frame - 1), width, height);
  const size_t count = scene.objects.size();
  for (size_t i = 0; i < count; ++i) {
    const Pose now = scene.object_pose(i, frame), before = scene.object_pose(i, frame - 1);
    transforms_.emplace_back(now);
    prev_transforms_.emplace_back(before);
    moved_.push_back(now.translation != before.translation || now.yaw_turns != before.yaw_turns);
    emission_.push_back(scene.object_emission(i, frame));
  }
  try {
    build(device);
  } catch (...) {
    if (scene_) rtcReleaseScene(static_cast<RTCScene>(scene_));
    throw;
  }
}

void FrameScene::build(const EmbreeDevice& device) {
  const SceneDesc& scene = *desc_;
  const size_t count = scene.objects.size();
  RTCDevice dev = static_cast<RTCDevice>(device.handle());
  RTCScene rs = rtcNewScene(dev);
  if (!rs) {
    device.check("creating a scene");
    throw std::runtime_error("embree: creating a scene failed");
  }
  scene_ = rs;
  rtcSetSceneFlags(rs, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(rs, RTC_BUILD_QUALITY_HIGH);
  quads_.resize(count);
  float total_power = 0.f;
  for (size_t i = 0; i < count; ++i) {
    const Object& obj = scene.objects[i];
    const RigidTransform& xf = transforms_[i];
    const size_t nq = obj.quads.size();
    RTCGeometry geom = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_QUAD);
    auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 4 * nq));
    auto* ib = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT4, 4 * sizeof(unsigned), nq));
    if (!vb || !ib) {
      rtcReleaseGeometry(geom);
      device.check("allocating geometry");
      throw std::runtime_error("embree: allocating geometry failed");
    }
    for (size_t q = 0; q < nq; ++q) {
      const LocalQuad& lq = obj.quads[q];
      const glm::dvec3 corners[4] = {lq.o, lq.o + lq.e1, lq.o + lq.e1 + lq.e2, lq.o + lq.e2};
      Vec3 fc[4];
      for (int k = 0; k < 4; ++k) {
        fc[k] = to_float(xf.to_world(corners[k]));
        vb[(4 * q + k) * 3 + 0] = fc[k].x;
        vb[(4 * q + k) * 3 + 1] = fc[k].y;
        vb[(4 * q + k) * 3 + 2] = fc[k].z;
        ib[4 * q + k] = static_cast<unsigned>(4 * q + k);
      }
      WorldQuad wq;
      wq.v0 = fc[0];
      wq.e1 = fc[1] - fc[0];
      wq.e2 = fc[3] - fc[0];
      wq.n = to_float(unit(xf.rotate(glm::cross(lq.e1, lq.e2))));
      wq.u_axis = to_float(unit(xf.rotate(lq.e1)));
      wq.v_axis = to_float(unit(xf.rotate(lq.e2)));
      quads_[i].push_back(wq);
      if (obj.material.is_emitter() && luminance(emission_[i]) > 0.f) {
        Light l;
        l.object = static_cast<int>(i);
        l.quad = static_cast<int>(q);
        l.v0 = wq.v0;
        l.e1 = wq.e1;
        l.e2 = wq.e2;
        l.n = wq.n;
        l.area = length(cross(wq.e1, wq.e2));
        l.emission = emission_[i];
        l.pick = l.area * luminance(l.emission);
        total_power = total_power + l.pick;
        lights_.push_back(l);
      }
    }
    rtcCommitGeometry(geom);
    rtcAttachGeometryByID(rs, geom, static_cast<unsigned>(i));
    rtcReleaseGeometry(geom);
  }
  float cdf = 0.f;
  for (Light& l : lights_) {
    l.pick = l.pick / total_power;
    cdf = cdf + l.pick;
    l.cdf = cdf;
  }
  if (!lights_.empty()) lights_.back().cdf = 1.f;
  rtcCommitScene(rs);
  device.check("building the scene");
}

FrameScene::~FrameScene() {
  if (scene_) rtcReleaseScene(static_cast<RTCScene>(scene_));
}

Hit FrameScene::intersect(Vec3 o, Vec3 d, float tmax) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRayHit rh;
  rh.ray.org_x = o.x;
  rh.ray.org_y = o.y;
  rh.ray.org_z = o.z;
  rh.ray.tnear = 0.f;
  rh.ray.dir_x = d.x;
  rh.ray.dir_y = d.y;
  rh.ray.dir_z = d.z;
  rh.ray.time = 0.f;
  rh.ray.tfar = tmax;
  rh.ray.mask = 0xFFFFFFFFu;
  rh.ray.id = 0;
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(static_cast<RTCScene>(scene_), &ctx, &rh);
  Hit hit;
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return hit;
  hit.object = static_cast<int>(rh.hit.geomID);
  hit.quad = static_cast<int>(rh.hit.primID);
  const WorldQuad& q = quads_[hit.object][hit.quad];
  // Distance to the quad's plane, independent of how Embree computed it.
  const float denom = dot(q.n, d);
  const float t = dot(q.n, q.v0 - o) / denom;
  hit.t = (t > 0.f && is_finite(t)) ? t : rh.ray.tfar;
  hit.p = o + d * hit.t;
  hit.n = q.n;
  return hit;
}

bool FrameScene::occluded(Vec3 o, Vec3 d, float tmax) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRay ray;
  ray.org_x = o.x;
  ray.org_y = o.y;
  ray.org_z = o.z;
  ray.tnear = 0.f;
  ray.dir_x = d.x;
  ray.dir_y = d.y;
  ray.dir_z = d.z;
  ray.time = 0.f;
  ray.tfar = tmax;
  ray.mask = 0xFFFFFFFFu;
  ray.id = 0;
  ray.flags = 0;
  rtcOccluded1(static_cast<RTCScene>(scene_), &ctx, &ray);
  return ray.tfar < 0.f;  // Embree sets tfar to -inf on a hit
}

Vec3 FrameScene::albedo(const Hit& hit) const {
  const Material& m = material(hit.object);
  if (m.pattern == Pattern::Constant) return m.albedo;
  const WorldQuad& q = quads_[hit.object][hit.quad];
  const Vec3 r = hit.p - q.v0;
  return pattern_albedo(m, dot(r, q.u_axis), dot(r, q.v_axis));
}

}  // namespace svgf::gbuffer

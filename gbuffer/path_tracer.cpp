#include "gbuffer/path_tracer.h"

#include <cmath>
#include <limits>

#include "gbuffer/det_trig.h"
#include "gbuffer/vec_ops.h"

namespace svgf::gbuffer {

namespace {

constexpr float kInvPi = 0.318309886183790672f;
constexpr float kShadowEnd = 1.f - 1e-4f;  // shadow rays stop just short of the light sample

// Next-event estimate of reflected direct light at p (Lambertian, albedo `albedo`), without the
// path throughput. u[0] picks a light, u[1..2] a point on it.
Vec3 sample_direct(const FrameScene& scene, Vec3 p, Vec3 n, Vec3 albedo, const float u[4],
                   uint64_t& rays) {
  const std::vector<Light>& lights = scene.lights();
  if (lights.empty()) return vec3(0.f);
  size_t k = 0;
  while (k + 1 < lights.size() && !(u[0] < lights[k].cdf)) ++k;
  const Light& l = lights[k];
  const Vec3 y = (l.v0 + l.e1 * u[1]) + l.e2 * u[2];
  const Vec3 o = p + n * ray_offset(p);
  const Vec3 w = y - o;
  const float dist2 = dot(w, w);
  const float dist = std::sqrt(dist2);
  const Vec3 wi = w / dist;
  const float cos_s = dot(n, wi);
  const float cos_l = -dot(l.n, wi);
  if (!(cos_s > 0.f) || !(cos_l > 0.f)) return vec3(0.f);
  ++rays;
  if (scene.occluded(o, w, kShadowEnd)) return vec3(0.f);
  // f = albedo / pi, pdf = pick / area (area measure), G = cos_s cos_l / dist^2.
  const float scale = ((cos_s * cos_l) * l.area) / (dist2 * l.pick);
  return (albedo * l.emission) * (scale * kInvPi);
}

}  // namespace

Vec3 sample_cosine(Vec3 n, float u0, float u1) {
  double s, c;
  sincos_turns_coarse(static_cast<double>(u1), s, c);
  const float r = std::sqrt(u0);
  const float lx = r * static_cast<float>(c);
  const float ly = r * static_cast<float>(s);
  const float lz = std::sqrt(max_f(0.f, 1.f - u0));
  Vec3 t, b;
  orthonormal_basis(n, t, b);
  return (t * lx + b * ly) + n * lz;
}

Radiance trace_path(const FrameScene& scene, const Hit& primary, Vec3 dir, const SampleKey& key,
                    const PathSettings& settings, uint64_t& rays) {
  Radiance out;
  const Material& first = scene.material(primary.object);
  if (first.is_emitter()) {
    if (dot(primary.n, dir) < 0.f) out.direct = scene.emission(primary.object);  // one-sided
    return out;
  }
  Vec3 throughput = vec3(1.f);
  Hit hit = primary;
  for (int bounce = 0;; ++bounce) {
    const Vec3 n = dot(hit.n, dir) < 0.f ? hit.n : neg(hit.n);  // two-sided surfaces
    const Vec3 albedo = scene.albedo(hit);
    float u[4];
    key.draw(static_cast<uint32_t>(bounce), 0, u);
    const Vec3 c = throughput * sample_direct(scene, hit.p, n, albedo, u, rays);
    if (bounce == 0) out.direct += c;
    else out.indirect += c;
    if (bounce >= settings.max_bounces) break;
    throughput = throughput * albedo;
    if (bounce >= settings.rr_start) {
      const float q = min_f(0.95f, max_component(throughput));
      if (!(u[3] < q)) break;
      throughput = throughput / q;
    }
    float v[4];
    key.draw(static_cast<uint32_t>(bounce), 1, v);
    const Vec3 wi = sample_cosine(n, v[0], v[1]);
    ++rays;
    const Hit next = scene.intersect(hit.p + n * ray_offset(hit.p), wi,
                                     std::numeric_limits<float>::infinity());
    if (!next.valid() || scene.material(next.object).is_emitter()) break;
    hit = next;
    dir = wi;
  }
  return out;
}

}  // namespace svgf::gbuffer

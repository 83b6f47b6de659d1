#include "gbuffer/gradient_samples.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "gbuffer/gbuffer.h"
#include "gbuffer/path_tracer.h"
#include "gbuffer/rng.h"
#include "gbuffer/vec_ops.h"

namespace svgf::gbuffer {

namespace {

constexpr int kS = kGradientStratum;
constexpr float kInf = std::numeric_limits<float>::infinity();

int strata(int pixels) { return (pixels + kS - 1) / kS; }

glm::dvec3 to_double(Vec3 v) { return {v.x, v.y, v.z}; }
Vec3 to_float(const glm::dvec3& v) {
  return make_vec3(static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z));
}

// A previous frame's camera sample, carried with its object into the current frame.
struct Carried {
  bool valid = false;
  int source_x = 0, source_y = 0;  // its pixel in the previous frame
  int x = 0, y = 0;                // the pixel it lands on in the current frame
  uint32_t priority = 0;
  Hit before, after;               // the primary hit then, the same surface point now
  Vec3 dir_before, dir_after;      // the camera rays towards them
};

Carried carry(const FrameScene& previous, const FrameScene& current, const StratumPick& pick,
              uint64_t& rays) {
  Carried c;
  c.source_x = pick.x;
  c.source_y = pick.y;
  c.priority = pick.priority;
  Vec3 origin;
  primary_ray(previous.camera(), pick.x, pick.y, origin, c.dir_before);
  ++rays;
  c.before = previous.intersect(origin, c.dir_before, kInf);
  if (!c.before.valid()) return c;  // background: nothing to re-shade
  const int object = c.before.object;
  // The same object-space point where its object is now; a still object's point keeps its bits.
  glm::dvec3 moved = to_double(c.before.p);
  if (current.moved(object))
    moved = current.transform(object).to_world(current.prev_transform(object).to_local(moved));
  const CameraModel& cam = current.camera();
  glm::dvec2 s;
  if (!cam.project(moved, s)) return c;
  if (!(s.x >= 0.0 && s.y >= 0.0 && s.x < cam.width() && s.y < cam.height())) return c;
  c.x = static_cast<int>(std::floor(s.x));
  c.y = static_cast<int>(std::floor(s.y));
  // Visible now: the current camera's ray towards the point first hits its object, there.
  const glm::dvec3 to_point = moved - cam.eye();
  const double dist = std::sqrt(glm::dot(to_point, to_point));
  c.dir_after = to_float(to_point / dist);
  ++rays;
  const Hit seen = current.intersect(to_float(cam.eye()), c.dir_after, kInf);
  const float d = static_cast<float>(dist);
  if (seen.object != object || !(abs_f(seen.t - d) <= kGradientVisibilityTolerance * d))
    return c;
  c.after.object = object;
  c.after.quad = c.before.quad;
  c.after.t = d;
  c.after.p = to_float(moved);
  c.after.n = current.quad(object, c.before.quad).n;
  c.valid = true;
  return c;
}

}  // namespace

StratumPick pick_in_stratum(uint64_t seed, int frame, int sx, int sy, int width, int height) {
  const int x0 = sx * kS, y0 = sy * kS;
  const int w = width - x0 < kS ? width - x0 : kS;  // partial strata at the right and bottom
  const int h = height - y0 < kS ? height - y0 : kS;
  const Philox4 r = philox4x32_10(
      Philox4{{pixel_key(sx, sy), static_cast<uint32_t>(frame), 0u,
               static_cast<uint32_t>(Stream::GradientPick) << 24}},
      static_cast<uint32_t>(seed), static_cast<uint32_t>(seed >> 32));
  const uint32_t k = r.v[0] % static_cast<uint32_t>(w * h);
  return {x0 + static_cast<int>(k) % w, y0 + static_cast<int>(k) / w, r.v[1]};
}

Image gradient_samples(const FrameScene& previous, const FrameScene& current,
                       const RenderSettings& settings, uint64_t& rays) {
  const int w = current.camera().width(), h = current.camera().height();
  if (previous.frame() + 1 != current.frame() || previous.camera().width() != w ||
      previous.camera().height() != h)
    throw std::invalid_argument("gradient samples need the previous frame at the same size");
  const int nx = strata(w), ny = strata(h);
  std::vector<Carried> carried(static_cast<size_t>(nx) * ny);
  std::atomic<uint64_t> traced{0};
  tbb::parallel_for(tbb::blocked_range<int>(0, ny, 1), [&](const tbb::blocked_range<int>& rows) {
    uint64_t n = 0;
    for (int sy = rows.begin(); sy < rows.end(); ++sy)
      for (int sx = 0; sx < nx; ++sx)
        carried[static_cast<size_t>(sy) * nx + sx] = carry(
            previous, current, pick_in_stratum(settings.seed, previous.frame(), sx, sy, w, h), n);
    traced.fetch_add(n, std::memory_order_relaxed);
  });

  // One sample per stratum of the current frame: the lowest priority, on a tie the first source
  // stratum in scan order. Serial, so the choice does not depend on scheduling.
  std::vector<int> winner(carried.size(), -1);
  for (size_t i = 0; i < carried.size(); ++i) {
    const Carried& c = carried[i];
    if (!c.valid) continue;
    int& slot = winner[static_cast<size_t>(c.y / kS) * nx + c.x / kS];
    if (slot < 0 || c.priority < carried[static_cast<size_t>(slot)].priority)
      slot = static_cast<int>(i);
  }

  Image out(w, h, 3);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, winner.size()),
                    [&](const tbb::blocked_range<size_t>& range) {
    uint64_t n = 0;
    for (size_t t = range.begin(); t < range.end(); ++t) {
      if (winner[t] < 0) continue;
      const Carried& c = carried[static_cast<size_t>(winner[t])];
      // The random numbers of the previous frame's `color` sample at its pixel, for both.
      const SampleKey key =
          sample_key(settings, c.source_x, c.source_y, previous.frame(), 0, Stream::Color);
      const Radiance a = trace_path(previous, c.before, c.dir_before, key, settings.path, n);
      const Radiance b = trace_path(current, c.after, c.dir_after, key, settings.path, n);
      out.at(c.x, c.y, 0) = luminance(a.direct + a.indirect);
      out.at(c.x, c.y, 1) = luminance(b.direct + b.indirect);
      out.at(c.x, c.y, 2) = 1.f;
    }
    traced.fetch_add(n, std::memory_order_relaxed);
  });
  rays += traced.load();
  return out;
}

}  // namespace svgf::gbuffer

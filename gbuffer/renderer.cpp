#include "gbuffer/renderer.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "gbuffer/gbuffer.h"
#include "gbuffer/gradient_samples.h"

namespace svgf::gbuffer {

void validate(const RenderSettings& s) {
  auto fail = [](const std::string& what) { throw std::invalid_argument(what); };
  if (s.width < 1 || s.height < 1 || s.width > kMaxImageSide || s.height > kMaxImageSide)
    fail("image size " + std::to_string(s.width) + "x" + std::to_string(s.height) +
         " is impossible (each side 1.." + std::to_string(kMaxImageSide) + ")");
  if (s.spp < 1 || s.spp > kMaxSpp)
    fail("spp " + std::to_string(s.spp) + " out of range 1.." + std::to_string(kMaxSpp));
  if (s.reference_spp < 0 || s.reference_spp > kMaxSpp)
    fail("reference spp " + std::to_string(s.reference_spp) + " out of range 0.." +
         std::to_string(kMaxSpp));
  if (s.path.max_bounces < 0 || s.path.max_bounces > 64 || s.path.rr_start < 0)
    fail("bad path settings");
}

SampleKey sample_key(const RenderSettings& settings, int x, int y, int frame, int sample,
                     Stream stream) {
  SampleKey key;
  key.seed = settings.seed;
  key.pixel = pixel_key(x, y);
  key.frame = static_cast<uint32_t>(frame);
  key.sample = static_cast<uint32_t>(sample);
  key.stream = stream;
  return key;
}

namespace {

struct PixelRadiance {
  Vec3 color, direct, indirect;
};

// Mean over `count` samples of one stream, summed in double in sample order. `halves`, when
// given, also receives the color's mean over samples [0, count/2) and over the rest (summed
// apart, so the mean itself is the same with or without them).
PixelRadiance estimate(const FrameScene& scene, const RenderSettings& settings, int x, int y,
                       const Hit& primary, Vec3 dir, Stream stream, int count, uint64_t& rays,
                       Vec3 (*halves)[2] = nullptr) {
  double sum[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
  double half_sum[2][3] = {{0, 0, 0}, {0, 0, 0}};
  const int first_half = count / 2;
  for (int s = 0; s < count; ++s) {
    const SampleKey key = sample_key(settings, x, y, scene.frame(), s, stream);
    const Radiance r = trace_path(scene, primary, dir, key, settings.path, rays);
    const Vec3 c = r.direct + r.indirect;
    const Vec3 parts[3] = {c, r.direct, r.indirect};
    for (int k = 0; k < 3; ++k) {
      sum[3 * k + 0] += parts[k].x;
      sum[3 * k + 1] += parts[k].y;
      sum[3 * k + 2] += parts[k].z;
    }
    double* h = half_sum[s < first_half ? 0 : 1];
    h[0] += c.x;
    h[1] += c.y;
    h[2] += c.z;
  }
  float mean[9];
  for (int k = 0; k < 9; ++k) mean[k] = static_cast<float>(sum[k] / count);
  if (halves && first_half > 0) {
    const int n[2] = {first_half, count - first_half};
    for (int k = 0; k < 2; ++k)
      (*halves)[k] = make_vec3(static_cast<float>(half_sum[k][0] / n[k]),
                               static_cast<float>(half_sum[k][1] / n[k]),
                               static_cast<float>(half_sum[k][2] / n[k]));
  }
  return {make_vec3(mean[0], mean[1], mean[2]), make_vec3(mean[3], mean[4], mean[5]),
          make_vec3(mean[6], mean[7], mean[8])};
}

// One pixel's part of ReferenceNoise (reference_noise.h): (clamp(a) - clamp(b))^2 per channel, scaled
// to the variance of the whole reference; its sum and sum of squares.
struct NoiseSums {
  double sum = 0, squares = 0, at_clamp = 0;
  void add(const Vec3 (&halves)[2], double scale) {
    const float a[3] = {halves[0].x, halves[0].y, halves[0].z};
    const float b[3] = {halves[1].x, halves[1].y, halves[1].z};
    for (int c = 0; c < 3; ++c) {
      const double d = static_cast<double>(std::clamp(a[c], 0.f, 1.f)) -
                       static_cast<double>(std::clamp(b[c], 0.f, 1.f));
      const double v = d * d * scale;
      sum += v;
      squares += v * v;
      if (a[c] > 1.f || b[c] > 1.f) at_clamp += v;
    }
  }
};

void store(Image& im, int i, Vec3 v) {
  im.plane(0)[i] = v.x;
  im.plane(1)[i] = v.y;
  im.plane(2)[i] = v.z;
}

}  // namespace

Frame Renderer::render(const SceneDesc& desc, int frame, const RenderSettings& settings,
                       RenderCounters* counters, ReferenceNoise* noise) const {
  validate(settings);
  if (frame < 0) throw std::invalid_argument("frame " + std::to_string(frame) + " < 0");
  const int w = settings.width, h = settings.height;
  const FrameScene scene(device_, desc, frame, w, h);
  Frame f;
  f.index = frame;
  f.allocate(w, h);
  f.emission = Image(w, h, 3);
  if (settings.reference_spp > 0) f.reference = Image(w, h, 3);
  if (settings.split) {
    f.direct = Image(w, h, 3);
    f.indirect = Image(w, h, 3);
  }
  f.camera = scene.camera().matrices();
  // The reference's noise (reference_noise.h): summed per row, then over rows in order, so the estimate
  // does not depend on the thread count.
  const int n = settings.reference_spp, n1 = n / 2;
  const bool estimate_noise = noise != nullptr && n >= 2;
  const double noise_scale = static_cast<double>(n1) * (n - n1) / (static_cast<double>(n) * n);
  std::vector<NoiseSums> noise_rows(estimate_noise ? static_cast<size_t>(h) : 0);

  tbb::parallel_for(tbb::blocked_range<int>(0, h, 1), [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y < rows.end(); ++y) {
      if (counters && counters->cancel.load(std::memory_order_relaxed)) return;
      uint64_t rays = 0;
      for (int x = 0; x < w; ++x) {
        const int i = y * w + x;
        Vec3 origin, dir;
        primary_ray(scene.camera(), x, y, origin, dir);
        const Hit hit = scene.intersect(origin, dir, std::numeric_limits<float>::infinity());
        ++rays;
        const GBufferSample g = gbuffer_sample(scene, x, y, hit, dir);
        store(f.position, i, g.position);
        store(f.normal, i, g.normal);
        store(f.albedo, i, g.albedo);
        store(f.emission, i, g.emission);
        f.depth.plane(0)[i] = g.depth;
        f.depth_gradient.plane(0)[i] = g.depth_gradient.x;
        f.depth_gradient.plane(1)[i] = g.depth_gradient.y;
        f.motion.plane(0)[i] = g.motion.x;
        f.motion.plane(1)[i] = g.motion.y;
        f.mesh_id[i] = g.mesh_id;
        if (!hit.valid()) continue;  // black background: color and reference stay 0
        const PixelRadiance c =
            estimate(scene, settings, x, y, hit, dir, Stream::Color, settings.spp, rays);
        store(f.color, i, c.color);
        if (settings.split) {
          store(f.direct, i, c.direct);
          store(f.indirect, i, c.indirect);
        }
        if (settings.reference_spp > 0) {
          Vec3 halves[2];
          const PixelRadiance r = estimate(scene, settings, x, y, hit, dir, Stream::Reference,
                                           settings.reference_spp, rays,
                                           estimate_noise ? &halves : nullptr);
          store(f.reference, i, r.color);
          if (estimate_noise) noise_rows[static_cast<size_t>(y)].add(halves, noise_scale);
        }
      }
      if (counters) {
        counters->rays.fetch_add(rays, std::memory_order_relaxed);
        counters->rows.fetch_add(1, std::memory_order_relaxed);
      }
    }
  });
  if (counters && counters->cancel.load()) throw std::runtime_error("rendering interrupted");
  if (noise) {
    *noise = ReferenceNoise{};
    if (estimate_noise) {
      // Pixels without a surface have an exact reference (0) and add 0 to the sums.
      NoiseSums total;
      for (const NoiseSums& r : noise_rows) {
        total.sum += r.sum;
        total.squares += r.squares;
        total.at_clamp += r.at_clamp;
      }
      const double count = 3.0 * static_cast<double>(w) * h;
      const double mean = total.sum / count;
      const double variance = std::max(0.0, total.squares / count - mean * mean);
      noise->mse = mean;
      noise->standard_error = std::sqrt(variance / count);
      noise->clamped_share = total.sum > 0 ? total.at_clamp / total.sum : 0.0;
    }
  }
  if (settings.gradients) {
    // No earlier frame of this shot: the group is there, with no samples.
    const std::vector<int>& cuts = desc.camera_cuts;
    if (frame == 0 || std::find(cuts.begin(), cuts.end(), frame) != cuts.end()) {
      f.gradient = Image(w, h, 3);
    } else {
      const FrameScene previous(device_, desc, frame - 1, w, h);
      uint64_t rays = 0;
      f.gradient = gradient_samples(previous, scene, settings, rays);
      if (counters) counters->rays.fetch_add(rays, std::memory_order_relaxed);
    }
  }
  return f;
}

}  // namespace svgf::gbuffer

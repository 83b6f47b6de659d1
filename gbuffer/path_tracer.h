#pragma once
// Unidirectional path tracer: next-event estimation at every vertex (one light sample, one shadow
// ray), cosine-weighted bounces, Russian roulette. Emitters are reached only through next-event
// estimation after the camera vertex, so there is no double counting and no MIS to weigh.
#include <cstdint>

#include "core/vec.h"
#include "gbuffer/frame_scene.h"
#include "gbuffer/rng.h"

namespace svgf::gbuffer {

struct PathSettings {
  int max_bounces = 3;  // indirect bounces after the camera vertex
  int rr_start = 1;     // Russian roulette decides continuations from this vertex on (0 = camera)
};

struct Radiance {
  Vec3 direct;    // emission seen by the camera + next-event estimate at the camera vertex
  Vec3 indirect;  // everything gathered at later vertices
};

// One path through the camera ray `dir` whose first hit is `primary` (valid). Adds the number of
// rays it traced (the camera ray not included) to `rays`.
Radiance trace_path(const FrameScene& scene, const Hit& primary, Vec3 dir, const SampleKey& key,
                    const PathSettings& settings, uint64_t& rays);

// Cosine-weighted direction about unit n from two uniforms.
Vec3 sample_cosine(Vec3 n, float u0, float u1);

}  // namespace svgf::gbuffer

#pragma once
// A moving test sequence generated in code: a textured wall (mesh 1, depth 4) with a square
// (mesh 2, depth 2) sliding right by `speed` pixels a frame. The lighting is a smooth ramp, the
// noisy color is the reference times a mean-1 random factor per pixel and frame.
#include <cstdint>
#include <random>

#include "core/frame.h"

namespace svgf::test {

struct SyntheticScene {
  int width = 64;
  int height = 48;
  int square = 14;
  int speed = 2;  // pixels per frame, to the right
  uint32_t seed = 1;

  int square_x(int frame) const { return 6 + speed * frame; }
  int square_y() const { return (height - square) / 2; }
  bool on_square(int x, int y, int frame) const {
    return x >= square_x(frame) && x < square_x(frame) + square && y >= square_y() &&
           y < square_y() + square;
  }

  Frame frame(int k) const {
    Frame f;
    f.index = k;
    f.allocate(width, height);
    f.reference = Image(width, height, 3);
    std::mt19937 rng(seed * 7919u + static_cast<uint32_t>(k));
    std::uniform_real_distribution<float> noise(0.f, 2.f);
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const size_t i = static_cast<size_t>(y) * width + x;
        const bool sq = on_square(x, y, k);
        const float light = 0.3f + 0.7f * float(x) / float(width);
        const float albedo = sq ? 0.6f : (((x / 8) + (y / 8)) % 2 ? 0.8f : 0.25f);
        f.depth.plane(0)[i] = sq ? 2.f : 4.f;
        f.normal.plane(2)[i] = 1.f;
        f.mesh_id[i] = sq ? 2u : 1u;
        f.motion.plane(0)[i] = sq ? -float(speed) : 0.f;  // prev = x + motion
        for (int c = 0; c < 3; ++c) {
          const float tint = c == 0 ? 1.f : (c == 1 ? 0.9f : 0.7f);
          f.albedo.plane(c)[i] = albedo * tint;
          f.reference.plane(c)[i] = albedo * tint * light;
          f.color.plane(c)[i] = f.reference.plane(c)[i] * noise(rng);
        }
        for (int c = 0; c < 3; ++c)
          f.position.plane(c)[i] = c == 0 ? float(x) : (c == 1 ? float(y) : -f.depth.plane(0)[i]);
      }
    return f;
  }
};

}  // namespace svgf::test

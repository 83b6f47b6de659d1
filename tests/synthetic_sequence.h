#pragma once
// A moving test sequence generated in code: a textured wall (mesh 1, depth 4) with a square
// (mesh 2, depth 2) sliding right by `speed` pixels a frame. The lighting is a smooth ramp, the
// noisy color is the reference times a mean-1 random factor per pixel and frame.
#include <algorithm>
#include <cstdint>
#include <random>

#include "core/frame.h"
#include "core/vec.h"

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

  // A-SVGF's gradient samples for frame `f` (from frame 1 on; read by --antilag gradient
  // only), one per 3x3 stratum at a position that moves with the frame: the square's strata
  // changed by half, the rest not at all.
  void add_gradient_samples(Frame& f) const {
    const int k = f.index;
    f.gradient = Image(f.width(), f.height(), 3);
    if (k <= 0) return;
    for (int y = k % kGradientStratum; y < f.height(); y += kGradientStratum)
      for (int x = (k + y) % kGradientStratum; x < f.width(); x += kGradientStratum) {
        const float l = luminance(f.reference.rgb().load(y * f.width() + x));
        f.gradient.at(x, y, 0) = on_square(x, y, k) ? 1.5f * l : l;
        f.gradient.at(x, y, 1) = l;
        f.gradient.at(x, y, 2) = 1.f;
      }
  }
};

// The frame's color split: a third of the reflected light (color - emission) as indirect, the
// rest as direct.
inline Frame with_split(Frame f) {
  f.direct = f.color;
  f.indirect = Image(f.width(), f.height(), 3);
  for (size_t i = 0; i < f.color.data().size(); ++i) {
    const float emitted = f.emission.empty() ? 0.f : f.emission.data()[i];
    f.indirect.data()[i] = std::max(0.f, f.color.data()[i] - emitted) / 3.f;
    f.direct.data()[i] = f.color.data()[i] - f.indirect.data()[i];
  }
  return f;
}

}  // namespace svgf::test

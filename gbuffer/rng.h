#pragma once
// Counter-based random numbers: Philox-4x32-10 (Salmon et al., SC 2011). Every random number of
// the path tracer is a pure function of (seed, pixel, frame, sample, stream, bounce, group), so a
// pixel of any frame renders the same on its own, in any order, on any number of threads.
#include <cstdint>

namespace svgf::gbuffer {

struct Philox4 {
  uint32_t v[4];
};

inline Philox4 philox4x32_10(Philox4 ctr, uint32_t k0, uint32_t k1) {
  for (int round = 0; round < 10; ++round) {
    const uint64_t p0 = static_cast<uint64_t>(0xD2511F53u) * ctr.v[0];
    const uint64_t p1 = static_cast<uint64_t>(0xCD9E8D57u) * ctr.v[2];
    const uint32_t hi0 = static_cast<uint32_t>(p0 >> 32), lo0 = static_cast<uint32_t>(p0);
    const uint32_t hi1 = static_cast<uint32_t>(p1 >> 32), lo1 = static_cast<uint32_t>(p1);
    ctr = Philox4{{hi1 ^ ctr.v[1] ^ k0, lo1, hi0 ^ ctr.v[3] ^ k1, lo0}};
    k0 += 0x9E3779B9u;
    k1 += 0xBB67AE85u;
  }
  return ctr;
}

// Top 24 bits as a float in [0, 1): exactly representable, never 1.
inline float to_unit_float(uint32_t bits) { return static_cast<float>(bits >> 8) * 0x1p-24f; }

// Streams keep the 1-spp color and the reference statistically independent. GradientPick only
// picks the pixel of each A-SVGF stratum (gradient_samples.h); the re-shaded paths reuse the
// Color stream's keys.
enum class Stream : uint32_t { Color = 0, Reference = 1, GradientPick = 2 };

// The counter of one camera sample; bounce and group select the numbers within its path.
struct SampleKey {
  uint64_t seed = 0;
  uint32_t pixel = 0;  // (y << 16) | x
  uint32_t frame = 0;
  uint32_t sample = 0;
  Stream stream = Stream::Color;

  // Four uniforms in [0, 1) for (bounce, group); bounce < 65536, group < 256.
  void draw(uint32_t bounce, uint32_t group, float out[4]) const {
    const uint32_t word3 = (static_cast<uint32_t>(stream) << 24) | (bounce << 8) | group;
    const Philox4 r = philox4x32_10(Philox4{{pixel, frame, sample, word3}},
                                    static_cast<uint32_t>(seed), static_cast<uint32_t>(seed >> 32));
    for (int k = 0; k < 4; ++k) out[k] = to_unit_float(r.v[k]);
  }
};

inline uint32_t pixel_key(int x, int y) {
  return (static_cast<uint32_t>(y) << 16) | static_cast<uint32_t>(x);
}

}  // namespace svgf::gbuffer

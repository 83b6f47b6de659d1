// The sanitize stage's row driver (kernels_cpu/sanitize_rows.cpp) must give the per-pixel
// kernel's planes and per-kind repair tallies exactly (the kernel is what the GPU runs), on
// every instruction-set variant this CPU runs: clean frames, and frames with NaN, Inf, -0,
// negatives, subnormals, huge values and the rule's boundary values in every plane, bad
// normals, bad depth, huge motion, with and without the optional planes (emission, position,
// direct and indirect), rows that are not a whole number of the driver's spans.
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>

#include <catch2/catch.hpp>

#include "core/sanitize.h"
#include "cpu_variant_support.h"
#include "kernels_cpu/parallel_for.h"
#include "test_support.h"

using namespace svgf;

namespace {

using svgf::test::kNaN;
using svgf::test::kInf;
constexpr float kTiny = std::numeric_limits<float>::denorm_min();
constexpr float kFloatMax = std::numeric_limits<float>::max();

// A frame's input planes, in the CPU backend's repaired-copy layout.
enum : int { kColor = 0, kAlbedo = 3, kNormal = 6, kDepth = 9, kDepthDx, kDepthDy, kMotionX,
             kMotionY, kEmission = 14, kPosition = 17, kDirect = 20, kIndirect = 23, kPlanes = 26 };

struct Planes {
  bool emission, position, split;
};

// Values every plane may hold where a pixel goes bad: the rule's boundaries and beyond.
const float kOddValues[] = {kNaN, -kNaN, kInf, -kInf, -0.f, 0.f, -1e-3f, kTiny, -kTiny, 1e-39f,
                            1.f, std::nextafter(1.f, 2.f), kMaxRadiance,
                            std::nextafter(kMaxRadiance, kInf), 2e18f, kMaxGuide,
                            std::nextafter(kMaxGuide, kInf), -kMaxGuide, kMaxMotion,
                            std::nextafter(kMaxMotion, kInf), -kMaxMotion, -3e7f, kFloatMax,
                            -kFloatMax, 1e-31f, 0.5f};

// A plausible frame: radiance in [0, 4], albedo in [0, 1], unit normals (to float rounding),
// surfaces at every pixel but a few background ones, small motion. `bad`: the share of pixels
// given an odd value in a random plane (a normal of a random wrong length at some of them).
Image input(int w, int h, float bad, uint32_t seed) {
  Image im(w, h, kPlanes);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  const int n = w * h;
  for (int i = 0; i < n; ++i) {
    for (int c = 0; c < 3; ++c) {
      im.plane(kColor + c)[i] = u(rng) * 4.f;
      im.plane(kAlbedo + c)[i] = u(rng);
      im.plane(kEmission + c)[i] = u(rng) < 0.9f ? 0.f : u(rng) * 10.f;
      im.plane(kPosition + c)[i] = u(rng) * 200.f - 100.f;
      im.plane(kDirect + c)[i] = u(rng) * 2.f;
      im.plane(kIndirect + c)[i] = u(rng) * 2.f;
    }
    const float a = u(rng) * 6.2831853f, z = u(rng) * 2.f - 1.f, s = std::sqrt(1.f - z * z);
    im.plane(kNormal)[i] = s * std::cos(a);
    im.plane(kNormal + 1)[i] = s * std::sin(a);
    im.plane(kNormal + 2)[i] = z;
    im.plane(kDepth)[i] = u(rng) < 0.05f ? 0.f : 1.f + u(rng) * 50.f;
    im.plane(kDepthDx)[i] = u(rng) * 0.2f - 0.1f;
    im.plane(kDepthDy)[i] = u(rng) * 0.2f - 0.1f;
    im.plane(kMotionX)[i] = u(rng) * 40.f - 20.f;
    im.plane(kMotionY)[i] = u(rng) * 40.f - 20.f;
    if (u(rng) >= bad) continue;
    const int plane = static_cast<int>(u(rng) * kPlanes) % kPlanes;
    const int odd = static_cast<int>(u(rng) * std::size(kOddValues)) % std::size(kOddValues);
    im.plane(plane)[i] = kOddValues[odd];
    if (u(rng) < 0.3f) {  // a normal too short or too long, from zero to beyond the rule's limit
      const float scales[] = {0.f, kTiny, 1e-20f, 0.5f, 0.899f, 0.9f, 1.1f, 1.101f, 3.f, 1e19f};
      const float k = scales[static_cast<int>(u(rng) * 10.f) % 10];
      for (int c = 0; c < 3; ++c) im.plane(kNormal + c)[i] *= k;
    }
  }
  return im;
}

InputPlanes planes_in(const Image& im, Planes with) {
  InputPlanes p;
  p.color = const_cast<Image&>(im).rgb(kColor);
  p.albedo = const_cast<Image&>(im).rgb(kAlbedo);
  p.normal = const_cast<Image&>(im).rgb(kNormal);
  if (with.emission) p.emission = const_cast<Image&>(im).rgb(kEmission);
  if (with.position) p.position = const_cast<Image&>(im).rgb(kPosition);
  if (with.split) {
    p.direct = const_cast<Image&>(im).rgb(kDirect);
    p.indirect = const_cast<Image&>(im).rgb(kIndirect);
  }
  p.depth = im.plane(kDepth);
  p.depth_dx = im.plane(kDepthDx);
  p.depth_dy = im.plane(kDepthDy);
  p.motion_x = im.plane(kMotionX);
  p.motion_y = im.plane(kMotionY);
  return p;
}

// The repair pass as the backend runs it: in place on a copy of the input.
SanitizeInputs repairing(Image& copy, Planes with) {
  InputPlanesOut o;
  o.color = copy.rgb(kColor);
  o.albedo = copy.rgb(kAlbedo);
  o.normal = copy.rgb(kNormal);
  if (with.emission) o.emission = copy.rgb(kEmission);
  if (with.position) o.position = copy.rgb(kPosition);
  if (with.split) {
    o.direct = copy.rgb(kDirect);
    o.indirect = copy.rgb(kIndirect);
  }
  o.depth = copy.plane(kDepth);
  o.depth_dx = copy.plane(kDepthDx);
  o.depth_dy = copy.plane(kDepthDy);
  o.motion_x = copy.plane(kMotionX);
  o.motion_y = copy.plane(kMotionY);
  return SanitizeInputs{copy.width(), planes_in(copy, with), o};
}

void require_same_tallies(const Tallies& got, const Tallies& expected, const std::string& what) {
  for (int b = 0; b < kTallyBits; ++b) {
    INFO(what << ", bit " << b);
    REQUIRE(got.count[b] == expected.count[b]);
  }
}

}  // namespace

TEST_CASE("cpu rows: sanitize rows equal the per-pixel kernel bitwise, tallies included",
          "[cpu_rows]") {
  // Widths around the driver's 64-pixel spans.
  const int sizes[][2] = {{1280, 6}, {67, 13}, {64, 3}, {1, 5}, {130, 7}, {200, 1}};
  const float bad_shares[] = {0.f, 0.002f, 0.3f};
  uint32_t seed = 1700;
  Tallies all;  // over the adversarial frames with every plane: each kind must occur
  for (const auto& size : sizes)
    for (float bad : bad_shares) {
      const int w = size[0], h = size[1];
      const Image in = input(w, h, bad, ++seed);
      for (int mask = 0; mask < 8; ++mask) {
        const Planes with{(mask & 1) != 0, (mask & 2) != 0, (mask & 4) != 0};
        const std::string what = std::to_string(w) + "x" + std::to_string(h) + ", bad share " +
                                 std::to_string(bad) + ", emission " +
                                 std::to_string(with.emission) + ", position " +
                                 std::to_string(with.position) + ", split " +
                                 std::to_string(with.split);
        const SanitizeInputs scan{w, planes_in(in, with), {}};
        const Tallies expected = cpu::tally_pixels(w, h, scan);
        Image repaired = in;
        cpu::for_each_pixel(w, h, repairing(repaired, with));
        if (bad == 0.f) REQUIRE(!expected.any());
        if (mask == 7) all += expected;
        test::for_each_runnable_variant([&](const cpu::CpuVariant& v) {
          require_same_tallies(v.sanitize_rows(scan, w, h), expected,
                               what + ", scan on " + v.name);
          Image got = in;
          const Tallies written = v.sanitize_rows(repairing(got, with), w, h);
          require_same_tallies(written, expected, what + ", repair on " + v.name);
          test::require_identical(got, repaired, what + ", repair on " + v.name);
        });
      }
    }
  for (int b = 0; b < kRepairKinds; ++b) {
    INFO("repair kind " << b << " never occurred: the inputs do not test it");
    REQUIRE(all.count[b] > 0);
  }
}

#pragma once
// The input rule every frame passes before any stage of any method reads it (docs/bad-input.md).
// The backend runs SanitizeInputs as the frame's first stage, "sanitize": on the CPU as a
// read-only scan that repairs a copy only when something is wrong, on CUDA in place on the
// uploaded planes, where SVGF's packed flavors may instead run it in the first kernel that reads
// the inputs (FrameInputs::sanitize_pending, methods/svgf/pipeline.h). Either way a clean value
// is never changed (the rule is the identity on good input and on its own output), so a clean
// frame costs one read and bits do not depend on which path ran.
#include <cstdint>

#include "core/arith.h"
#include "core/hd.h"
#include "core/vec.h"
#include "core/views.h"

namespace svgf {

// Radiance above this is not a measurement but a broken sample (1e8 is ~1000x a direct view of
// the sun in exposure-normalized units); bounding it keeps every filter sum finite: squared
// demodulated luminance (1e8 / albedo floor 1e-3)^2 = 1e22, far from float's 3.4e38.
inline constexpr float kMaxRadiance = 1e8f;
// Depth, depth gradient and world position beyond this magnitude are not geometry: bounded,
// their differences and squared distances (the JBF's plane term) stay finite.
inline constexpr float kMaxGuide = 1e18f;
// Motion is clamped to this many pixels: any larger vector leaves the image all the same (no
// history), and x + motion stays within the range where float -> int is defined (floor_small).
inline constexpr float kMaxMotion = 16777216.f;  // 2^24
// A surface normal is used as stored when |n|^2 lies in [0.81, 1.21] (|n| within 10% of 1:
// half floats and 8-bit encodings stay far inside); otherwise it is renormalized.
inline constexpr float kMinNormalLength2 = 0.81f;
inline constexpr float kMaxNormalLength2 = 1.21f;

// What SanitizeInputs repaired at a pixel: one bit per kind, counted per frame by the engines
// (FrameReport::repairs).
enum InputRepair : uint32_t {
  kRepairColor = 1u << 0,     // a color component NaN, Inf, negative or > kMaxRadiance: set to 0
                              // (also one of direct or indirect, the split of color)
  kRepairAlbedo = 1u << 1,    // an albedo component outside [0, 1]: clamped (NaN: 1)
  kRepairEmission = 1u << 2,  // as color, for emission
  kRepairNormal = 1u << 3,    // a surface normal of the wrong length: renormalized
  kRepairSurface = 1u << 4,   // non-finite or absurd depth, gradient, normal or position:
                              // the pixel became background (no neighbour match, no history)
  kRepairMotion = 1u << 5,    // motion non-finite or beyond kMaxMotion: clamped (no history)
};
inline constexpr int kRepairKinds = 6;

// Radiance (color, emission): NaN, +-Inf, negative and > kMaxRadiance become 0 (no light), the
// one value that cannot brighten or darken a history beyond what a dark sample would. -0 stays.
SVGF_HD bool radiance_ok(float v) { return v >= 0.f && v <= kMaxRadiance; }  // false for NaN
SVGF_HD float sanitize_radiance(float v, bool& replaced) {
  const bool ok = radiance_ok(v);
  replaced = replaced || !ok;
  return ok ? v : 0.f;
}
// Whether sanitize_radiance leaves every component of c as it is (& not &&: no branch, so a
// vector loop can test it, kernels_cpu/sanitize_rows.cpp).
SVGF_HD bool radiance_ok(Vec3 c) { return radiance_ok(c.x) & radiance_ok(c.y) & radiance_ok(c.z); }
SVGF_HD Vec3 sanitize_radiance(Vec3 c, bool& replaced) {
  return make_vec3(sanitize_radiance(c.x, replaced), sanitize_radiance(c.y, replaced),
                   sanitize_radiance(c.z, replaced));
}

// Albedo lies in [0, 1] (Open Image Denoise's rule for its albedo input): clamped; NaN becomes 1,
// the "untextured" convention, so the pixel's illumination is its color.
SVGF_HD float sanitize_albedo(float v, bool& replaced) {
  const bool ok = v >= 0.f && v <= 1.f;
  replaced = replaced || !ok;
  return ok ? v : (v < 0.f ? 0.f : 1.f);  // NaN fails v < 0: 1
}
SVGF_HD Vec3 sanitize_albedo(Vec3 a, bool& replaced) {
  return make_vec3(sanitize_albedo(a.x, replaced), sanitize_albedo(a.y, replaced),
                   sanitize_albedo(a.z, replaced));
}

SVGF_HD bool bounded(float v, float limit) { return v >= -limit && v <= limit; }  // false for NaN
SVGF_HD bool bounded(Vec3 v, float limit) {
  return bounded(v.x, limit) && bounded(v.y, limit) && bounded(v.z, limit);
}

// Motion: NaN becomes +kMaxMotion (off the image: no history), anything else is clamped.
SVGF_HD float sanitize_motion(float v, bool& replaced) {
  const bool ok = bounded(v, kMaxMotion);
  replaced = replaced || !ok;
  return ok ? v : (v < 0.f ? -kMaxMotion : kMaxMotion);
}

// A bounded surface normal of any nonzero length, brought to unit length; zero (or too small to
// scale) returns false. Scaled by its largest component first, so that a tiny normal's squared
// length is not lost to subnormals.
SVGF_HD bool renormalized(Vec3& n) {
  const float m = max_f(max_f(abs_f(n.x), abs_f(n.y)), abs_f(n.z));
  if (!(m >= 1e-30f)) return false;  // zero, subnormal or NaN
  const Vec3 s = n / m;
  n = s / ExactArith::sqrt(dot(s, s));  // dot(s, s) in [1, 3]; IEEE sqrt on both sides
  return true;
}

// The guides' part of the rule (sanitize_pixel's): a surface (depth > 0) needs every guide
// finite and bounded and a normal that can be brought to unit length; a background pixel
// (depth <= 0) needs finite guides only. Depth NaN or +-Inf, or any failure, makes the pixel
// clean background: all guides 0. Returns `repairs` with kRepairNormal or kRepairSurface added
// where it repaired. A function of the pixel's guides alone, so a stage may apply it where it
// reads a pixel's guides before the sanitize stage ran (methods/svgf/gradient.h:
// sanitized_stratum_guide); on guides it already passed it changes nothing.
// The bits come in and go out (not OR-ed by the caller) and it is always inlined: so GCC
// if-converts sanitize_pixel in the CPU's vector scan (kernels_cpu/sanitize_rows.cpp), which
// otherwise stays scalar, 4x slower (2.5 -> 10.7 ms at 720p on an Intel Xeon VM).
SVGF_HD_INLINE uint32_t sanitize_guides(uint32_t repairs, float& depth, float& depth_dx,
                                        float& depth_dy, Vec3& normal, Vec3& position,
                                        bool has_position) {
  const bool surface = depth > 0.f;
  const float limit = surface ? kMaxGuide : 3.40282347e38f;  // background: finite is enough
  bool guides_ok = bounded(depth, limit) && bounded(depth_dx, limit) &&
                   bounded(depth_dy, limit) && bounded(normal, limit) &&
                   (!has_position || bounded(position, limit));
  if (guides_ok && surface) {
    const float n2 = dot(normal, normal);
    if (!(n2 >= kMinNormalLength2 && n2 <= kMaxNormalLength2)) {
      guides_ok = renormalized(normal);
      if (guides_ok) repairs |= kRepairNormal;
    }
  }
  if (!guides_ok) {
    depth = depth_dx = depth_dy = 0.f;
    normal = Vec3();
    position = Vec3();
    repairs |= kRepairSurface;
  }
  return repairs;
}

// One pixel of a frame's inputs, as stored by the backend.
struct InputPixel {
  Vec3 color, albedo, emission, normal, position;
  float depth, depth_dx, depth_dy, motion_x, motion_y;
};

// The rule for one pixel; returns the InputRepair bits of what it changed. `has_emission` and
// `has_position`: whether the frame has those planes (absent planes are not checked).
// Always inlined: the CPU's scan runs it as a vector loop (kernels_cpu/sanitize_rows.cpp).
SVGF_HD_INLINE uint32_t sanitize_pixel(InputPixel& p, bool has_emission, bool has_position) {
  uint32_t repairs = 0;
  bool bad = false;
  p.color = sanitize_radiance(p.color, bad);
  if (bad) repairs |= kRepairColor;
  bad = false;
  p.albedo = sanitize_albedo(p.albedo, bad);
  if (bad) repairs |= kRepairAlbedo;
  if (has_emission) {
    bad = false;
    p.emission = sanitize_radiance(p.emission, bad);
    if (bad) repairs |= kRepairEmission;
  }
  bad = false;
  p.motion_x = sanitize_motion(p.motion_x, bad);
  p.motion_y = sanitize_motion(p.motion_y, bad);
  if (bad) repairs |= kRepairMotion;
  return sanitize_guides(repairs, p.depth, p.depth_dx, p.depth_dy, p.normal, p.position,
                         has_position);
}

// A frame's inputs as one backend stores them: `in` read, repaired pixels written to `out`
// (which may be `in` itself, or hold no planes: a dry run that only reports). Optional planes
// (emission, position) are absent when `in` has none. Returns the InputRepair bits.
struct InputPlanes {
  ConstRgbView color, albedo, emission, normal, position;
  ConstRgbView direct, indirect;  // optional, both or neither: the split of color
  const float* depth = nullptr;
  const float* depth_dx = nullptr;
  const float* depth_dy = nullptr;
  const float* motion_x = nullptr;
  const float* motion_y = nullptr;
};
struct InputPlanesOut {
  RgbView color, albedo, emission, normal, position;
  RgbView direct, indirect;
  float* depth = nullptr;
  float* depth_dx = nullptr;
  float* depth_dy = nullptr;
  float* motion_x = nullptr;
  float* motion_y = nullptr;
};

struct SanitizeInputs {
  int width = 0;
  InputPlanes in;
  InputPlanesOut out;  // no planes: report only

  SVGF_HD uint32_t operator()(int x, int y) const {
    const int i = y * width + x;
    const bool has_emission = in.emission.r != nullptr;
    const bool has_position = in.position.r != nullptr;
    InputPixel p;
    p.color = in.color.load(i);
    p.albedo = in.albedo.load(i);
    p.emission = in.emission.load_or_zero(i);
    p.normal = in.normal.load(i);
    p.position = in.position.load_or_zero(i);
    p.depth = in.depth[i];
    p.depth_dx = in.depth_dx[i];
    p.depth_dy = in.depth_dy[i];
    p.motion_x = in.motion_x[i];
    p.motion_y = in.motion_y[i];
    uint32_t repairs = sanitize_pixel(p, has_emission, has_position);
    // The split of color follows color's rule, counted as color.
    bool split_bad = false;
    Vec3 direct, indirect;
    if (in.direct.r != nullptr) {
      direct = sanitize_radiance(in.direct.load(i), split_bad);
      indirect = sanitize_radiance(in.indirect.load(i), split_bad);
      if (split_bad) repairs |= kRepairColor;
    }
    if (repairs == 0 || out.depth == nullptr) return repairs;
    if (split_bad) {
      out.direct.store(i, direct);
      out.indirect.store(i, indirect);
    }
    // Only what changed is written: in place on the device, a clean pixel costs no store.
    if (repairs & kRepairColor) out.color.store(i, p.color);
    if (repairs & kRepairAlbedo) out.albedo.store(i, p.albedo);
    if (repairs & kRepairEmission) out.emission.store(i, p.emission);
    if (repairs & kRepairMotion) {
      out.motion_x[i] = p.motion_x;
      out.motion_y[i] = p.motion_y;
    }
    if (repairs & (kRepairNormal | kRepairSurface)) out.normal.store(i, p.normal);
    if (repairs & kRepairSurface) {
      out.depth[i] = p.depth;
      out.depth_dx[i] = p.depth_dx;
      out.depth_dy[i] = p.depth_dy;
      if (has_position) out.position.store(i, p.position);
    }
    return repairs;
  }
};

}  // namespace svgf

#pragma once
// What the committed fixtures are: their on-disk storage, the generator tag in their manifests,
// the render settings a manifest implies, and the value-by-value comparison `verify` uses.
#include <string>
#include <vector>

#include "core/frame.h"
#include "gbuffer/renderer.h"
#include "io/exr_frame.h"
#include "io/sequence.h"

namespace svgf::gbuffer {

inline constexpr int kGeneratorVersion = 3;  // bump whenever any output bit changes (3: moving-shadow remade)
std::string generator_tag();                 // "svgf-fixtures 1"

// Half for color, reference, direct, indirect, albedo, normal and position (position follows
// from depth and camera at float precision anyway); float for depth, depth gradient and motion,
// whose precision reprojection needs. The gradient group is FLOAT (io/exr_frame.h).
io::FrameStorage fixture_storage();

// The value a float takes after a round trip through `storage` (half rounds to nearest even).
float quantize(float v, io::PixelStorage storage);

// Render settings a manifest was generated with.
RenderSettings settings_from_manifest(const io::Manifest& manifest);

struct CompareOptions {
  bool reference = true;   // compare the reference channel when the file has one
  float tolerance = 0.f;   // 0: bitwise; else |a - b| <= tolerance * max(1, |a|) passes
};

struct PixelDiff {
  int x = 0, y = 0;
  double stored = 0.0, rendered = 0.0;  // rendered: after quantizing to the stored precision
};

struct ChannelDiff {
  std::string channel;            // e.g. "color.G", "mesh_id", "camera"
  size_t count = 0;               // values that differ
  double max_abs = 0.0;           // largest |stored - rendered|
  std::vector<PixelDiff> pixels;  // the first few, in scan order
};

// Differences between a frame read from a file and a fresh render quantized as stored. Channels
// absent from the file are skipped; channels the file has and the render lacks are reported.
std::vector<ChannelDiff> compare_frames(const Frame& stored, const Frame& rendered,
                                        const io::FrameStorage& storage,
                                        const CompareOptions& options);

std::string describe(const ChannelDiff& d);  // one line, with the first few pixels

}  // namespace svgf::gbuffer

#pragma once
// The project's frame file: one multi-channel OpenEXR per frame (docs/frame-format.md).
#include <cstddef>
#include <string>

#include "core/frame.h"
#include "io/io_error.h"

namespace svgf::io {

enum class PixelStorage { Half, Float };

// How each channel group is stored on disk. The reader accepts HALF or FLOAT for every float
// channel (it converts to float); mesh_id is always UINT.
struct FrameStorage {
  PixelStorage color = PixelStorage::Float;      // color, emission, direct, indirect
  PixelStorage reference = PixelStorage::Float;  // reference
  PixelStorage albedo = PixelStorage::Half;
  PixelStorage normal = PixelStorage::Half;
  PixelStorage position = PixelStorage::Float;
  PixelStorage depth = PixelStorage::Float;      // depth and depth gradient
  PixelStorage motion = PixelStorage::Float;
  // The gradient group is always FLOAT: its two luminances are compared with each other.
};

// Channel names, in one place.
namespace channel {
inline constexpr const char* kColor[3] = {"color.R", "color.G", "color.B"};
inline constexpr const char* kAlbedo[3] = {"albedo.R", "albedo.G", "albedo.B"};
inline constexpr const char* kNormal[3] = {"normal.X", "normal.Y", "normal.Z"};
inline constexpr const char* kPosition[3] = {"position.X", "position.Y", "position.Z"};
inline constexpr const char* kDepth = "depth.Z";
inline constexpr const char* kDepthGradient[2] = {"depth_gradient.X", "depth_gradient.Y"};
inline constexpr const char* kMotion[2] = {"motion.X", "motion.Y"};
inline constexpr const char* kMeshId = "mesh_id";
inline constexpr const char* kEmission[3] = {"emission.R", "emission.G", "emission.B"};
inline constexpr const char* kReference[3] = {"reference.R", "reference.G", "reference.B"};
inline constexpr const char* kDirect[3] = {"direct.R", "direct.G", "direct.B"};
inline constexpr const char* kIndirect[3] = {"indirect.R", "indirect.G", "indirect.B"};
inline constexpr const char* kGradient[3] = {"gradient.previous", "gradient.current",
                                             "gradient.mask"};
}  // namespace channel

// Writes `frame` to `path` atomically (a temporary file in the same folder, then rename).
// Header attributes: svgf.format_version, svgf.frame, svgf.world_to_view, svgf.view_to_clip.
void write_frame(const std::string& path, const Frame& frame, const FrameStorage& storage = {});

// Reads a frame file. Throws IoError naming the file (and channel) when the file is missing,
// is not an OpenEXR file, lacks a required channel, has a channel of the wrong pixel type, or
// has a data window other than (0,0)-(w-1,h-1).
Frame read_frame(const std::string& path);
// read_frame from the bytes of a frame file (a frame held in memory, a fuzzer's input); `name`
// stands for the file in error messages. The same checks and errors.
Frame read_frame_from_memory(const char* data, size_t size, const std::string& name);

// What a frame file's header says. read_frame_header checks the header as read_frame does
// (data window, format version, attribute types, every required channel present with its pixel
// type, optional groups all or nothing) without reading or allocating any pixels, so a whole
// sequence can be validated before anything is written.
struct FrameHeader {
  int width = 0, height = 0;
  bool has_index = false;  // svgf.frame present
  int index = 0;           // svgf.frame; 0 when absent
  bool has_direct = false, has_indirect = false;  // the optional split of color
};

namespace detail {
// read_frame that also reports whether the file carried svgf.frame (Sequence::read needs it)
// and, given an expected size (a manifest's), refuses another size from the header alone,
// before any channel is read or any pixel memory allocated (a small file can claim 30000^2).
struct ExpectedSize {
  int width = 0, height = 0;  // 0: any
  std::string source;         // named in the message, e.g. "manifest"
};
Frame read_frame(const std::string& path, bool* has_frame_index, const ExpectedSize& expected = {});
}  // namespace detail

// Throws IoError naming the file (and channel) for everything read_frame would refuse before
// reading pixels; given an expected size, for another size too.
FrameHeader read_frame_header(const std::string& path, const detail::ExpectedSize& expected = {});

// Writes a linear RGB image (channels R, G, B, FLOAT) atomically: the denoiser's output.
void write_rgb_exr(const std::string& path, const Image& rgb);
// Reads an R, G, B image (HALF or FLOAT) written by write_rgb_exr or any other tool.
Image read_rgb_exr(const std::string& path);

}  // namespace svgf::io

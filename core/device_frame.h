#pragma once
// A frame whose buffers already live in GPU memory, as a renderer holds its G-buffer: what
// Denoiser::denoise_device reads (issue 14, item 3; docs/api.md, "Frames on the GPU"). Each
// channel group is a strided view, as Open Image Denoise's shared buffers: the address of pixel
// (0, 0)'s first channel, and the bytes from one pixel, one row and one channel to the next, so
// planar planes, interleaved RGB, RGBA with a spare alpha and pitched rows are all read where
// they lie. CUDA-free: core/ knows no CUDA type (the backend checks that the addresses are
// device memory).
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "core/camera.h"

namespace svgf {

// Channels of 32-bit values (float; mesh_id: uint32) in device memory.
struct DeviceImageView {
  const void* data = nullptr;  // pixel (0, 0), channel 0
  size_t pixel_stride = 0;     // bytes from (x, y) to (x + 1, y)
  size_t row_stride = 0;       // bytes from (x, y) to (x, y + 1)
  size_t channel_stride = 0;   // bytes from channel c to c + 1 (4: interleaved)

  bool empty() const { return data == nullptr; }

  // `channels` planes of width x height values one after the other (this project's own layout).
  static DeviceImageView planar(const void* data, int width, int height) {
    const size_t row = static_cast<size_t>(width) * 4;
    return {data, 4, row, row * static_cast<size_t>(height)};
  }
  // `pixel_floats` values per pixel (3: RGB, 4: RGBA, whose fourth is not read), rows
  // `row_stride` bytes apart (0: packed, width * pixel_floats * 4).
  static DeviceImageView interleaved(const void* data, int width, int pixel_floats,
                                     size_t row_stride = 0) {
    const size_t pixel = static_cast<size_t>(pixel_floats) * 4;
    return {data, pixel, row_stride ? row_stride : pixel * static_cast<size_t>(width), 4};
  }
};

// Where the denoised color goes: three float channels in device memory, any layout as above.
// Written once, at the end of the frame's work; nothing else of it is read or written.
struct DeviceOutputView {
  void* data = nullptr;
  size_t pixel_stride = 0, row_stride = 0, channel_stride = 0;

  bool empty() const { return data == nullptr; }
  DeviceImageView as_input() const { return {data, pixel_stride, row_stride, channel_stride}; }

  static DeviceOutputView planar(void* data, int width, int height) {
    const DeviceImageView v = DeviceImageView::planar(data, width, height);
    return {data, v.pixel_stride, v.row_stride, v.channel_stride};
  }
  static DeviceOutputView interleaved(void* data, int width, int pixel_floats,
                                      size_t row_stride = 0) {
    const DeviceImageView v = DeviceImageView::interleaved(data, width, pixel_floats, row_stride);
    return {data, v.pixel_stride, v.row_stride, v.channel_stride};
  }
};

// The channels of core/frame.h's Frame, with the same meanings, units and rules (docs/
// frame-format.md). The optional ones are empty views when absent.
struct DeviceFrame {
  DeviceFrame(int width, int height) : width_(width), height_(height) {}
  int width() const { return width_; }
  int height() const { return height_; }

  int index = 0;  // frame number within its sequence (named in errors)
  Camera camera;  // host values; the identity when the renderer gives none
  DeviceImageView color;           // 3: noisy radiance, linear HDR
  DeviceImageView albedo;          // 3
  DeviceImageView normal;          // 3: world-space unit normal (0 on background)
  DeviceImageView depth;           // 1: linear view depth (> 0 on surfaces)
  DeviceImageView depth_gradient;  // 2: d depth/dx, d depth/dy
  DeviceImageView motion;          // 2: pixels to the previous frame
  DeviceImageView mesh_id;         // 1: uint32 per pixel
  DeviceImageView emission;        // 3, optional
  DeviceImageView position;        // 3, optional: world positions (the JBF and BMFR need them)
  DeviceImageView direct;          // 3, optional: with indirect, for SVGF's split filtering
  DeviceImageView indirect;        // 3, optional
  // 3, optional: A-SVGF's gradient samples. Unlike a host frame's, whose mask the denoiser
  // reads to see whether any stratum holds a sample, a device frame's are read on the GPU only
  // (no round trip): leave the view empty on a frame without samples (the first frame, the one
  // after a cut), and the statistics anti-lag runs as it does for a host frame with none.
  DeviceImageView gradient;

 private:
  int width_, height_;
};

// A device frame's output and the caller's CUDA stream (a cudaStream_t; nullptr: the legacy
// default stream): the target of a method's frame on the device path.
struct DeviceTarget {
  DeviceOutputView image;
  void* stream = nullptr;
};

// Every channel group of a device frame with its name and channel count, for checks and copies.
template <class F>
void for_each_device_channel(const DeviceFrame& f, F&& visit) {
  visit("color", f.color, 3, false);
  visit("albedo", f.albedo, 3, false);
  visit("normal", f.normal, 3, false);
  visit("depth", f.depth, 1, false);
  visit("depth_gradient", f.depth_gradient, 2, false);
  visit("motion", f.motion, 2, false);
  visit("mesh_id", f.mesh_id, 1, false);
  visit("emission", f.emission, 3, true);
  visit("position", f.position, 3, true);
  visit("direct", f.direct, 3, true);
  visit("indirect", f.indirect, 3, true);
  visit("gradient", f.gradient, 3, true);
}

// The layout rules a view must follow, checked on the host before anything is enqueued:
// 4-byte aligned address and strides, a pixel at least one value wide, rows that do not
// overlap, and channels that neither overlap each other within a pixel nor fall between
// pixels. Returns an empty string when the view is fine, else what is wrong.
inline std::string device_view_problem(const DeviceImageView& v, int width, int height,
                                       int channels) {
  const auto addr = reinterpret_cast<uintptr_t>(v.data);
  if (addr % 4 || v.pixel_stride % 4 || v.row_stride % 4 || v.channel_stride % 4)
    return "its address and strides must be multiples of 4 bytes";
  if (v.pixel_stride < 4) return "its pixel stride is below 4 bytes";
  if (v.row_stride < v.pixel_stride * static_cast<size_t>(width))
    return "its row stride (" + std::to_string(v.row_stride) + " bytes) is less than a row of " +
           std::to_string(width) + " pixels of " + std::to_string(v.pixel_stride) + " bytes";
  if (channels > 1) {
    const size_t last = v.channel_stride * static_cast<size_t>(channels - 1);
    const bool in_pixel = v.channel_stride >= 4 && last + 4 <= v.pixel_stride;
    const bool planes = v.channel_stride >= v.row_stride * static_cast<size_t>(height);
    if (!in_pixel && !planes)
      return "its channel stride (" + std::to_string(v.channel_stride) +
             " bytes) is neither within a pixel of " + std::to_string(v.pixel_stride) +
             " bytes nor a whole plane of " + std::to_string(v.row_stride * height) + " bytes";
  }
  return {};
}

// std::invalid_argument naming the frame and the first channel that is missing or badly laid
// out; the output likewise.
inline void check_device_frame(const DeviceFrame& f, const DeviceOutputView& out) {
  const std::string frame = "frame " + std::to_string(f.index) + " (device): ";
  if (f.width() <= 0 || f.height() <= 0)
    throw std::invalid_argument(frame + "size " + std::to_string(f.width()) + "x" +
                                std::to_string(f.height()) + " is empty");
  for_each_device_channel(f, [&](const char* name, const DeviceImageView& v, int channels,
                                 bool optional) {
    if (v.empty()) {
      if (optional) return;
      throw std::invalid_argument(frame + "channel '" + name + "' has no device address");
    }
    const std::string problem = device_view_problem(v, f.width(), f.height(), channels);
    if (!problem.empty())
      throw std::invalid_argument(frame + "channel '" + name + "': " + problem);
  });
  if (out.empty()) throw std::invalid_argument(frame + "the output has no device address");
  const std::string problem = device_view_problem(out.as_input(), f.width(), f.height(), 3);
  if (!problem.empty()) throw std::invalid_argument(frame + "the output: " + problem);
}

}  // namespace svgf

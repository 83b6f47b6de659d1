#pragma once
// The device path's copies (Denoiser::denoise_device): a caller's channels, in whatever strided
// layout they lie (core/device_frame.h), into the denoiser's planes, and its output plane back
// out. One launch copies every channel of a frame, as 32-bit words (a float's bits and a mesh
// id's alike: a NaN's payload arrives unchanged, for the sanitize stage to repair). Host-
// compilable: the pixel kernel is launched through the engine, instantiated by the methods'
// .cu files like every other.
#include <cstddef>
#include <cstdint>
#include <stdexcept>

#include "core/device_frame.h"
#include "core/hd.h"

namespace svgf::cuda {

// One channel: bytes from pixel to pixel and row to row on each side.
struct ChannelCopy {
  const char* from = nullptr;
  size_t from_pixel = 0, from_row = 0;
  char* to = nullptr;
  size_t to_pixel = 0, to_row = 0;
};

struct StridedCopy {
  // 30 channels at most (every channel group of a DeviceFrame); 48 bytes each keep the kernel
  // parameter well under CUDA's 4 KB.
  static constexpr int kMaxChannels = 32;
  ChannelCopy channel[kMaxChannels];
  int count = 0;

  void add(const ChannelCopy& c) {
    if (count == kMaxChannels) throw std::logic_error("StridedCopy: more than 32 channels");
    channel[count++] = c;
  }
  // Channel c of a strided view into (or out of) a plane of width x height floats.
  static ChannelCopy from_view(const DeviceImageView& v, int c, float* plane, int width) {
    return {static_cast<const char*>(v.data) + static_cast<size_t>(c) * v.channel_stride,
            v.pixel_stride, v.row_stride, reinterpret_cast<char*>(plane), 4,
            static_cast<size_t>(width) * 4};
  }
  static ChannelCopy to_view(const float* plane, int width, const DeviceOutputView& v, int c) {
    return {reinterpret_cast<const char*>(plane), 4, static_cast<size_t>(width) * 4,
            static_cast<char*>(v.data) + static_cast<size_t>(c) * v.channel_stride,
            v.pixel_stride, v.row_stride};
  }

  SVGF_HD void operator()(int x, int y) const {
    for (int k = 0; k < count; ++k) {
      const ChannelCopy& c = channel[k];
      const uint32_t word = *reinterpret_cast<const uint32_t*>(
          c.from + static_cast<size_t>(y) * c.from_row + static_cast<size_t>(x) * c.from_pixel);
      *reinterpret_cast<uint32_t*>(c.to + static_cast<size_t>(y) * c.to_row +
                                   static_cast<size_t>(x) * c.to_pixel) = word;
    }
  }
};

}  // namespace svgf::cuda

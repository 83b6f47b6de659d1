#pragma once
// Host-side owning image: planar float channels, channel c of pixel (x, y) at
// data[(c * height + y) * width + x]. Views into it (core/views.h) are what kernels see.
#include <algorithm>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/views.h"

namespace svgf {

class Image {
 public:
  Image() = default;
  Image(int width, int height, int channels, float fill = 0.f)
      : width_(width), height_(height), channels_(channels),
        data_(static_cast<size_t>(width) * height * channels, fill) {
    if (width < 0 || height < 0 || channels < 0)
      throw std::invalid_argument("Image: negative size");
  }

  // Gives the image this shape, reallocating (zero-filled) only when the shape differs; otherwise
  // the contents stay as they were. For outputs that are fully overwritten every frame.
  void ensure_shape(int width, int height, int channels) {
    if (width != width_ || height != height_ || channels != channels_)
      *this = Image(width, height, channels);
  }

  int width() const { return width_; }
  int height() const { return height_; }
  int channels() const { return channels_; }
  bool empty() const { return data_.empty(); }
  size_t pixel_count() const { return static_cast<size_t>(width_) * height_; }

  float* plane(int c) { return data_.data() + c * pixel_count(); }
  const float* plane(int c) const { return data_.data() + c * pixel_count(); }
  float& at(int x, int y, int c) { return plane(c)[static_cast<size_t>(y) * width_ + x]; }
  float at(int x, int y, int c) const { return plane(c)[static_cast<size_t>(y) * width_ + x]; }

  RgbView rgb(int first = 0) { return {plane(first), plane(first + 1), plane(first + 2)}; }
  ConstRgbView rgb(int first = 0) const {
    return {plane(first), plane(first + 1), plane(first + 2)};
  }

  // A copy of channels first .. first + count - 1.
  Image channels_from(int first, int count) const {
    if (first < 0 || count < 0 || first + count > channels_)
      throw std::invalid_argument("Image: channels " + std::to_string(first) + ".." +
                                  std::to_string(first + count - 1) + " of " +
                                  std::to_string(channels_));
    Image out(width_, height_, count);
    for (int c = 0; c < count; ++c)
      std::copy(plane(first + c), plane(first + c) + pixel_count(), out.plane(c));
    return out;
  }

  std::vector<float>& data() { return data_; }
  const std::vector<float>& data() const { return data_; }

 private:
  int width_ = 0;
  int height_ = 0;
  int channels_ = 0;
  std::vector<float> data_;
};

}  // namespace svgf

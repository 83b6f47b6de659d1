#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace svgf::io {

// Writes 8-bit interleaved RGB (width*height*3 bytes) as a PNG, atomically. Throws IoError.
void write_png_rgb8(const std::string& path, const uint8_t* rgb, int width, int height);

// The same PNG as bytes in memory (for pages that embed their images). Throws IoError.
std::string encode_png_rgb8(const uint8_t* rgb, int width, int height);

// An 8-bit RGB image (any PNG, converted: gray, palette, 16-bit and alpha over black).
struct Rgb8Image {
  int width = 0, height = 0;
  std::vector<uint8_t> rgb;  // interleaved, width*height*3 bytes
};
// Decodes PNG bytes; `what` names them in the IoError thrown for anything that is not a PNG.
Rgb8Image decode_png_rgb8(const std::string& bytes, const std::string& what);

}  // namespace svgf::io

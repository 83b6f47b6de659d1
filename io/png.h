#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace svgf::io {

// Writes 8-bit interleaved RGB (width*height*3 bytes) as a PNG, atomically. Throws IoError.
void write_png_rgb8(const std::string& path, const uint8_t* rgb, int width, int height);

}  // namespace svgf::io

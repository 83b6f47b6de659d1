#pragma once
// Single images in the formats other renderers write, read into planar float channels (for
// svgf import, docs/import.md): OpenEXR, Radiance .hdr (RGBE) and PFM. Every reader is strict:
// anything it does not understand is an IoError naming the file and what is wrong, never a guess.
#include <cstddef>
#include <string>

#include "core/image.h"
#include "io/io_error.h"

namespace svgf::io {

// Reads `path` by its extension (case-insensitive): .exr, .hdr / .pic, .pfm. Rows top to bottom.
// Channels: EXR gives R[,G[,B]] (those present, in that order; A is ignored), else X[,Y[,Z]],
// else Y, else Z, else its only channel; .hdr gives 3; PFM 3 (PF) or 1 (Pf).
Image read_image(const std::string& path);

// The readers on bytes held in memory (a fuzzer's input); `name` stands for the file in messages.
// Radiance .hdr: "#?RADIANCE" or "#?RGBE", FORMAT=32-bit_rle_rgbe (xyze is refused), EXPOSURE
// divided out, resolution line "-Y H +X W" only, scanlines flat or new-style RLE (old-style RLE
// is refused). A pixel (r, g, b, e) is (c + 0.5) * 2^(e - 136), 0 when e = 0 (Radiance's colr).
Image read_hdr_from_memory(const char* data, size_t size, const std::string& name);
// PFM: "PF" (RGB) or "Pf" (gray), width, height, scale (< 0: little-endian, > 0: big-endian,
// its magnitude ignored), then exactly width * height * channels floats, rows bottom to top.
Image read_pfm_from_memory(const char* data, size_t size, const std::string& name);
Image read_exr_image(const std::string& path);

// Writes 1 (Y), 2 (R, G) or 3 (R, G, B) FLOAT channels as one EXR, atomically: per-buffer files
// for svgf import's round trip.
void write_image_exr(const std::string& path, const Image& image);

}  // namespace svgf::io

#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

namespace svgf::io {

// SHA-256 (FIPS 180-4, computed by OpenSSL) as lowercase hex.
std::string sha256_hex(const void* data, size_t size);
// Of a whole file; throws IoError naming the file if it cannot be read.
std::string sha256_file(const std::string& path);

}  // namespace svgf::io

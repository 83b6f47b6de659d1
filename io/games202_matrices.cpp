#include "io/games202_matrices.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "io/atomic_file.h"

namespace svgf::io {

static_assert(sizeof(float) == 4 && sizeof(int32_t) == 4, "the .mat layout");

SceneMatrices read_games202_matrices_from_memory(const char* data, size_t size,
                                                 const std::string& name) {
  if (size < 4) throw IoError(name + ": truncated (no object count)");
  int32_t count = 0;
  std::memcpy(&count, data, 4);
  if (count < 0 || count > (1 << 20))
    throw IoError(name + ": object count " + std::to_string(count) + " outside 0..2^20");
  const size_t need = 4 + (static_cast<size_t>(count) + 2) * 64;
  if (size != need)
    throw IoError(name + ": " + std::to_string(size) + " bytes, an object count of " +
                  std::to_string(count) + " needs " + std::to_string(need) +
                  " (int32 count, then count + 2 float 4x4 matrices)");
  std::vector<Matrix4> all(static_cast<size_t>(count) + 2);
  for (size_t m = 0; m < all.size(); ++m)
    for (int k = 0; k < 16; ++k) {
      float v;
      std::memcpy(&v, data + 4 + m * 64 + k * 4, 4);
      if (!std::isfinite(v))
        throw IoError(name + ": matrix " + std::to_string(m) + " entry " + std::to_string(k) +
                      " is not finite");
      all[m][static_cast<size_t>(k)] = v;
    }
  SceneMatrices s;
  s.world_to_screen = all.back();
  all.pop_back();
  s.world_to_camera = all.back();
  all.pop_back();
  s.object_to_world = std::move(all);
  return s;
}

SceneMatrices read_games202_matrices(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw IoError(path + ": file does not exist");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(path + ": cannot open file for reading");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return read_games202_matrices_from_memory(bytes.data(), bytes.size(), path);
}

void write_games202_matrices(const std::string& path, const SceneMatrices& m) {
  std::string bytes(4, '\0');
  const int32_t count = static_cast<int32_t>(m.object_to_world.size());
  std::memcpy(&bytes[0], &count, 4);
  auto put = [&](const Matrix4& a) {
    for (double d : a) {
      const float v = static_cast<float>(d);
      bytes.append(reinterpret_cast<const char*>(&v), 4);
    }
  };
  for (const Matrix4& a : m.object_to_world) put(a);
  put(m.world_to_camera);
  put(m.world_to_screen);
  write_file_atomically(path, bytes);
}

}  // namespace svgf::io

#pragma once
// The GAMES202 homework 5 camera and object matrices (matrix_N.mat, one per frame): an int32
// count, then count + 2 row-major float32 4x4 matrices acting on column vectors: object -> world
// for each object id 0 .. count-1, then world -> camera, then world -> screen ([0, W) x [0, H)
// in pixels, row 0 at the top). Native byte order (little-endian on every machine that wrote one).
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "core/matrix4.h"
#include "io/io_error.h"

namespace svgf::io {

using svgf::Matrix4;  // row-major, acts on column vectors (core/matrix4.h)

struct SceneMatrices {
  std::vector<Matrix4> object_to_world;  // by object id
  Matrix4 world_to_camera{};
  Matrix4 world_to_screen{};
};

// Throws IoError naming the file: missing, shorter or longer than its count says, a negative
// count, a non-finite entry.
SceneMatrices read_games202_matrices(const std::string& path);
SceneMatrices read_games202_matrices_from_memory(const char* data, size_t size,
                                                 const std::string& name);
// The file read_games202_matrices reads (for tests and exporters); atomic.
void write_games202_matrices(const std::string& path, const SceneMatrices& m);

}  // namespace svgf::io

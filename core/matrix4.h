#pragma once
// 4x4 matrices in double, row-major, acting on column vectors (the frame format's convention,
// docs/frame-format.md): what the host derives from cameras (core/previous_depth.h) and from
// imported scene matrices (app/import_derive.h).
#include <array>
#include <cmath>
#include <utility>

namespace svgf {

using Matrix4 = std::array<double, 16>;

inline Matrix4 multiply(const Matrix4& a, const Matrix4& b) {
  Matrix4 r{};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      double s = 0;
      for (int k = 0; k < 4; ++k) s += a[i * 4 + k] * b[k * 4 + j];
      r[i * 4 + j] = s;
    }
  return r;
}

// False when `m` is singular (or nearly: |pivot| below 1e-300).
inline bool invert(const Matrix4& m, Matrix4& out) {
  // Gauss-Jordan with partial pivoting on [m | I].
  double a[4][8];
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 8; ++j) a[i][j] = j < 4 ? m[i * 4 + j] : (j - 4 == i ? 1.0 : 0.0);
  for (int c = 0; c < 4; ++c) {
    int pivot = c;
    for (int r = c + 1; r < 4; ++r)
      if (std::fabs(a[r][c]) > std::fabs(a[pivot][c])) pivot = r;
    if (!(std::fabs(a[pivot][c]) > 1e-300)) return false;
    if (pivot != c)
      for (int j = 0; j < 8; ++j) std::swap(a[c][j], a[pivot][j]);
    const double inv = 1.0 / a[c][c];
    for (int j = 0; j < 8; ++j) a[c][j] *= inv;
    for (int r = 0; r < 4; ++r)
      if (r != c && a[r][c] != 0.0) {
        const double f = a[r][c];
        for (int j = 0; j < 8; ++j) a[r][j] -= f * a[c][j];
      }
  }
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) out[i * 4 + j] = a[i][j + 4];
  return true;
}

// A float matrix (a Camera's) in double.
inline Matrix4 to_double(const std::array<float, 16>& m) {
  Matrix4 r{};
  for (int k = 0; k < 16; ++k) r[k] = static_cast<double>(m[k]);
  return r;
}

}  // namespace svgf

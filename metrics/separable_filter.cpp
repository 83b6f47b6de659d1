#include "metrics/separable_filter.h"

#include <algorithm>
#include <cstddef>

namespace svgf::metrics {

int border_index(int p, int n, FilterBorder border) {
  if (border == FilterBorder::clamp) return std::min(std::max(p, 0), n - 1);
  // Mirror without repeating the edge (…2 1 | 0 1 2 … n-1 | n-2 …), folded as often as a window
  // wider than the line needs.
  if (n == 1) return 0;
  while (p < 0 || p >= n) p = p < 0 ? -p : 2 * (n - 1) - p;
  return p;
}

namespace {

// One row with kernel k: the interior (every tap inside the row) loops over taps outside and
// pixels inside, so it vectorizes across x; the border pixels look their taps up one by one.
void convolve_row(const double* __restrict row, int w, const std::vector<double>& k,
                  FilterBorder border, double* __restrict out) {
  const int r = static_cast<int>(k.size() / 2);
  const int begin = std::min(r, w), end = std::max(begin, w - r);  // interior [begin, end)
  auto edge_pixel = [&](int x) {
    double s = 0;
    for (int d = -r; d <= r; ++d) s += k[d + r] * row[border_index(x + d, w, border)];
    out[x] = s;
  };
  for (int x = 0; x < begin; ++x) edge_pixel(x);
  for (int x = end; x < w; ++x) edge_pixel(x);
  for (int x = begin; x < end; ++x) out[x] = 0;
  for (int d = -r; d <= r; ++d) {
    const double kd = k[d + r];
    const double* in = row + d;
    for (int x = begin; x < end; ++x) out[x] += kd * in[x];
  }
}

}  // namespace

void separable_convolve(const std::vector<double>& src, int w, int h, const std::vector<double>& kx,
                        const std::vector<double>& ky, FilterBorder border,
                        std::vector<double>& out) {
  const size_t n = static_cast<size_t>(w) * h;
  // Scratch kept per thread: a fresh plane per call would be mmap'ed and page-faulted anew.
  thread_local std::vector<double> rows;
  if (rows.size() < n) rows.resize(n);
  out.resize(n);
  for (int y = 0; y < h; ++y)
    convolve_row(&src[static_cast<size_t>(y) * w], w, kx, border, &rows[static_cast<size_t>(y) * w]);
  const int r = static_cast<int>(ky.size() / 2);
  for (int y = 0; y < h; ++y) {
    double* __restrict acc = &out[static_cast<size_t>(y) * w];
    for (int x = 0; x < w; ++x) acc[x] = 0;
    for (int d = -r; d <= r; ++d) {
      const double kd = ky[d + r];
      const double* __restrict in = &rows[static_cast<size_t>(border_index(y + d, h, border)) * w];
      for (int x = 0; x < w; ++x) acc[x] += kd * in[x];
    }
  }
}

}  // namespace svgf::metrics

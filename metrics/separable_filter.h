#pragma once
// Separable convolution of a double plane, shared by FLIP (edges clamped) and SSIM (edges
// mirrored, BORDER_REFLECT_101). Every output pixel is summed as s = 0; s += k[d] * v for d from
// -r to r in order, whichever loop order computes it, so the vectorized form gives the bits of the
// naive one (tests/metrics_filters_test.cpp checks it against naive loops).
#include <vector>

namespace svgf::metrics {

enum class FilterBorder { clamp, reflect101 };

// The index that stands for position p past the edge of a line of n pixels.
int border_index(int p, int n, FilterBorder border);

// out = src convolved by rows with kx, then by columns with ky (odd lengths, centred). `out` is
// resized to w * h; src and out must differ. A thread's scratch row buffer is reused across calls.
void separable_convolve(const std::vector<double>& src, int w, int h, const std::vector<double>& kx,
                        const std::vector<double>& ky, FilterBorder border,
                        std::vector<double>& out);

}  // namespace svgf::metrics

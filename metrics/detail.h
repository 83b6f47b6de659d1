#pragma once
// How much of a reference's detail a denoised image keeps (issue 13: thin geometry and texture;
// docs/metrics.md, "Detail: edges and high frequencies"). Both work on the Rec. 709 luminance of
// values clamped to [0, 1] (as PSNR does), so an emitter's HDR edge does not outweigh the rest.
#include <cstdint>
#include <vector>

#include "core/image.h"

namespace svgf::metrics {

// Clamped luminance per pixel.
std::vector<double> clamped_luminance(const Image& image);

// Sobel gradient magnitude of a luminance plane (border pixels repeat the edge), divided by 8:
// a central difference, so a unit step between two columns gives 0.5 on both.
std::vector<double> gradient_magnitude(const std::vector<double>& luminance, int width,
                                       int height);

// Edge pixels: those where the reference's gradient magnitude is at least `floor` and among the
// `fraction` largest of the image (ties at the cut all count).
std::vector<uint8_t> edge_pixels(const Image& reference, double fraction = 0.1,
                                 double floor = 1e-3);

// Pearson correlation of the test's and the reference's gradient magnitudes over the
// reference's edge pixels: 1 where every edge keeps its relative strength, near 0 where the
// edges are blurred away or drowned in noise. NaN with fewer than 2 edge pixels or when either
// side is constant there. Scale-free: an image of half the reference's brightness scores 1.
double edge_preservation(const Image& test, const Image& reference, double fraction = 0.1);

// High-frequency energy (sum of squares of luminance minus its 3x3 box mean, border pixels
// repeating the edge) of the test over the reference's: 1 where the detail is kept, below 1
// where it is blurred, above 1 where noise is added. NaN when the reference has none.
double high_frequency_ratio(const Image& test, const Image& reference);

}  // namespace svgf::metrics

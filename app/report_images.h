#pragma once
// The images report.html embeds (app/html_report.h): linear RGB tone-mapped as the PNG previews
// of svgf denoise are (core/tonemap.h), error maps colour-mapped; each box-downscaled by a whole
// factor to at most kHtmlMaxImagePixels pixels (the mean of linear values).
#include <string>
#include <vector>

#include "app/html_report.h"
#include "core/frame.h"
#include "core/image.h"

namespace svgf::app {

// The first `channels` channels of `image`, averaged over factor x factor boxes (the mean of
// linear values; the last row and column of boxes may be cut by the image's edge).
Image box_downscaled(const Image& image, int factor, int channels);

// Channels 0-2 of `linear_rgb`, tone-mapped at `exposure`.
HtmlImage preview_image(const std::string& name, const Image& linear_rgb, float exposure);
// Channel 0 of `error_map` (values in [0, 1], as metrics::flip_map gives) through the colour
// scale of error_map_colour_bar.
HtmlImage error_map_image(const std::string& name, const Image& error_map);
// The error maps' colour scale: an approximation of matplotlib's magma (9 stops, linear between),
// black (no error) through purple and orange to pale yellow (1).
HtmlColourBar error_map_colour_bar();

// The FLIP map (metrics/flip.h) of the images as their previews show them: up to
// kHtmlMaxImagePixels pixels, the map itself; beyond, the map of both images clamped to [0, 1]
// and downscaled, for an observer with pixels per degree divided by the factor (the same view
// of the whole image). Bounds its cost (the full map of a 1080p frame: 3.3 s on one core).
Image preview_flip_map(const Image& test, const Image& reference);

// svgf denoise's set for one frame: noisy, denoised and, where the frame has a reference, the
// reference and preview_flip_map of the denoised image against it.
std::vector<HtmlImage> denoise_images(const Frame& in, const Image& out, float exposure);

// svgf compare's set for one frame: A, B and the FLIP map of A against B, at exposure 1; with
// `noisy` (B is a sequence: its frame's color) noisy, A, reference and the map.
std::vector<HtmlImage> compare_images(const Image& a, const Image& b, const Image* noisy,
                                      const Image& flip_map);

}  // namespace svgf::app

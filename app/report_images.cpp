#include "app/report_images.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <iterator>

#include "core/tonemap.h"
#include "io/png.h"
#include "metrics/flip.h"

namespace svgf::app {
namespace {

struct Rgb {
  uint8_t r, g, b;
};
// matplotlib's magma at 0, 1/8, ..., 1 (rounded to 8 bits).
const Rgb kMagma[] = {{0, 0, 4},      {28, 16, 68},    {79, 18, 123},
                      {129, 37, 129}, {181, 54, 122},  {229, 80, 100},
                      {251, 135, 97}, {254, 194, 135}, {252, 253, 191}};

// The smallest whole factor that leaves `image` at most kHtmlMaxImagePixels pixels.
int downscale_factor(const Image& image) {
  int factor = 1;
  auto pixels = [&](int f) {
    return int64_t{(image.width() + f - 1) / f} * ((image.height() + f - 1) / f);
  };
  while (pixels(factor) > kHtmlMaxImagePixels) ++factor;
  return factor;
}

// box_downscaled by downscale_factor(image).
Image downscaled(const Image& image, int channels) {
  return box_downscaled(image, downscale_factor(image), channels);
}

Rgb magma(float v) {
  const float t = std::min(1.f, std::max(0.f, std::isnan(v) ? 0.f : v)) * 8.f;
  const int i = std::min(7, static_cast<int>(t));
  const float f = t - static_cast<float>(i);
  auto mix = [&](uint8_t a, uint8_t b) {
    return static_cast<uint8_t>(std::lround(a + (static_cast<float>(b) - a) * f));
  };
  return {mix(kMagma[i].r, kMagma[i + 1].r), mix(kMagma[i].g, kMagma[i + 1].g),
          mix(kMagma[i].b, kMagma[i + 1].b)};
}

}  // namespace

Image box_downscaled(const Image& image, int factor, int channels) {
  if (factor <= 1) return image.channels_from(0, channels);
  const int w = (image.width() + factor - 1) / factor, h = (image.height() + factor - 1) / factor;
  Image out(w, h, channels);
  for (int c = 0; c < channels; ++c)
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        double sum = 0;
        int count = 0;
        for (int yy = y * factor; yy < std::min(image.height(), (y + 1) * factor); ++yy)
          for (int xx = x * factor; xx < std::min(image.width(), (x + 1) * factor); ++xx, ++count)
            sum += image.at(xx, yy, c);
        out.at(x, y, c) = static_cast<float>(sum / count);
      }
  return out;
}

HtmlImage preview_image(const std::string& name, const Image& linear_rgb, float exposure) {
  const Image small = downscaled(linear_rgb, 3);
  const int w = small.width(), h = small.height();
  std::vector<uint8_t> rgb(small.pixel_count() * 3);
  const TonemapKernel tonemap{w, small.rgb(), rgb.data(), exposure};
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) tonemap(x, y);
  return {name, io::encode_png_rgb8(rgb.data(), w, h)};
}

HtmlImage error_map_image(const std::string& name, const Image& error_map) {
  const Image small = downscaled(error_map, 1);
  std::vector<uint8_t> rgb(small.pixel_count() * 3);
  for (size_t i = 0; i < small.pixel_count(); ++i) {
    const Rgb c = magma(small.plane(0)[i]);
    rgb[3 * i] = c.r;
    rgb[3 * i + 1] = c.g;
    rgb[3 * i + 2] = c.b;
  }
  return {name, io::encode_png_rgb8(rgb.data(), small.width(), small.height())};
}

HtmlColourBar error_map_colour_bar() {
  HtmlColourBar bar{"FLIP error", {}};
  for (const Rgb& c : kMagma) {
    char hex[8];
    std::snprintf(hex, sizeof hex, "#%02x%02x%02x", c.r, c.g, c.b);
    bar.colours.push_back(hex);
  }
  return bar;
}

Image preview_flip_map(const Image& test, const Image& reference) {
  const int factor = downscale_factor(test);
  if (factor == 1) return metrics::flip_map(test, reference);
  auto clamped = [](const Image& image) {  // as flip_map does before anything else
    Image c = image.channels_from(0, 3);
    for (float& v : c.data()) v = std::isnan(v) ? 0.f : std::min(1.f, std::max(0.f, v));
    return downscaled(c, 3);
  };
  metrics::FlipOptions observer;
  observer.pixels_per_degree /= factor;
  return metrics::flip_map(clamped(test), clamped(reference), observer);
}

std::vector<HtmlImage> denoise_images(const Frame& in, const Image& out, float exposure) {
  std::vector<HtmlImage> images{preview_image("noisy", in.color, exposure),
                                preview_image("denoised", out, exposure)};
  if (in.has_reference()) {
    images.push_back(preview_image("reference", in.reference, exposure));
    images.push_back(error_map_image("FLIP error", preview_flip_map(out, in.reference)));
  }
  return images;
}

std::vector<HtmlImage> compare_images(const Image& a, const Image& b, const Image* noisy,
                                      const Image& flip_map) {
  std::vector<HtmlImage> images;
  if (noisy) images.push_back(preview_image("noisy", *noisy, 1.f));
  images.push_back(preview_image("A", a, 1.f));
  images.push_back(preview_image(noisy ? "reference" : "B", b, 1.f));
  images.push_back(error_map_image("FLIP error", flip_map));
  return images;
}

}  // namespace svgf::app

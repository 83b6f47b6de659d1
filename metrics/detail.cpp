#include "metrics/detail.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "metrics/display_range.h"

namespace svgf::metrics {
namespace {

void check_same(const Image& a, const Image& b, const char* what) {
  if (a.width() != b.width() || a.height() != b.height() || a.channels() < 3 ||
      b.channels() < 3)
    throw std::invalid_argument(std::string(what) +
                                ": images of different sizes or fewer than 3 channels");
}

double at(const std::vector<double>& p, int w, int h, int x, int y) {
  x = std::min(std::max(x, 0), w - 1);
  y = std::min(std::max(y, 0), h - 1);
  return p[static_cast<size_t>(y) * w + x];
}

std::vector<double> high_pass(const std::vector<double>& lum, int w, int h) {
  std::vector<double> out(lum.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double sum = 0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) sum += at(lum, w, h, x + dx, y + dy);
      const size_t i = static_cast<size_t>(y) * w + x;
      out[i] = lum[i] - sum / 9.0;
    }
  return out;
}

}  // namespace

std::vector<double> clamped_luminance(const Image& image) {
  if (image.channels() < 3) throw std::invalid_argument("clamped_luminance: fewer than 3 channels");
  std::vector<double> lum(image.pixel_count());
  for (size_t i = 0; i < lum.size(); ++i)
    lum[i] = 0.2126 * clamp01(image.plane(0)[i]) + 0.7152 * clamp01(image.plane(1)[i]) +
             0.0722 * clamp01(image.plane(2)[i]);
  return lum;
}

std::vector<double> gradient_magnitude(const std::vector<double>& lum, int w, int h) {
  if (lum.size() != static_cast<size_t>(w) * h)
    throw std::invalid_argument("gradient_magnitude: plane size does not match");
  std::vector<double> g(lum.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const auto p = [&](int dx, int dy) { return at(lum, w, h, x + dx, y + dy); };
      const double gx = (p(1, -1) + 2 * p(1, 0) + p(1, 1)) - (p(-1, -1) + 2 * p(-1, 0) + p(-1, 1));
      const double gy = (p(-1, 1) + 2 * p(0, 1) + p(1, 1)) - (p(-1, -1) + 2 * p(0, -1) + p(1, -1));
      g[static_cast<size_t>(y) * w + x] = std::sqrt(gx * gx + gy * gy) / 8.0;
    }
  return g;
}

std::vector<uint8_t> edge_pixels(const Image& reference, double fraction, double floor) {
  const std::vector<double> g =
      gradient_magnitude(clamped_luminance(reference), reference.width(), reference.height());
  std::vector<uint8_t> edge(g.size(), 0);
  if (g.empty() || !(fraction > 0)) return edge;
  std::vector<double> sorted = g;
  const size_t keep = std::min(sorted.size(), std::max<size_t>(
      1, static_cast<size_t>(std::ceil(fraction * static_cast<double>(sorted.size())))));
  std::nth_element(sorted.begin(), sorted.begin() + (keep - 1), sorted.end(), std::greater<>());
  const double cut = std::max(sorted[keep - 1], floor);
  for (size_t i = 0; i < g.size(); ++i) edge[i] = g[i] >= cut ? 1 : 0;
  return edge;
}

double edge_preservation(const Image& test, const Image& reference, double fraction) {
  check_same(test, reference, "edge_preservation");
  const int w = reference.width(), h = reference.height();
  const std::vector<double> gt = gradient_magnitude(clamped_luminance(test), w, h);
  const std::vector<double> gr = gradient_magnitude(clamped_luminance(reference), w, h);
  const std::vector<uint8_t> edge = edge_pixels(reference, fraction);
  double n = 0, st = 0, sr = 0;
  for (size_t i = 0; i < edge.size(); ++i)
    if (edge[i]) {
      n += 1;
      st += gt[i];
      sr += gr[i];
    }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (n < 2) return nan;
  const double mt = st / n, mr = sr / n;
  double ctt = 0, crr = 0, ctr = 0;
  for (size_t i = 0; i < edge.size(); ++i)
    if (edge[i]) {
      ctt += (gt[i] - mt) * (gt[i] - mt);
      crr += (gr[i] - mr) * (gr[i] - mr);
      ctr += (gt[i] - mt) * (gr[i] - mr);
    }
  if (!(ctt > 0) || !(crr > 0)) return nan;
  return ctr / std::sqrt(ctt * crr);
}

double high_frequency_ratio(const Image& test, const Image& reference) {
  check_same(test, reference, "high_frequency_ratio");
  const int w = reference.width(), h = reference.height();
  const std::vector<double> ht = high_pass(clamped_luminance(test), w, h);
  const std::vector<double> hr = high_pass(clamped_luminance(reference), w, h);
  double et = 0, er = 0;
  for (size_t i = 0; i < ht.size(); ++i) {
    et += ht[i] * ht[i];
    er += hr[i] * hr[i];
  }
  if (!(er > 0)) return std::numeric_limits<double>::quiet_NaN();
  return et / er;
}

}  // namespace svgf::metrics

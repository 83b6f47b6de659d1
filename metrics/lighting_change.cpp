#include "metrics/lighting_change.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace svgf::metrics {
namespace {

double luminance(const Image& im, size_t i) {
  return 0.2126 * im.plane(0)[i] + 0.7152 * im.plane(1)[i] + 0.0722 * im.plane(2)[i];
}

void check_same_size(const Image& a, const Image& b, const char* what) {
  if (a.width() != b.width() || a.height() != b.height() || a.channels() < 3 ||
      b.channels() < 3)
    throw std::invalid_argument(std::string("lighting_change: ") + what +
                                ": images of different sizes or fewer than 3 channels");
}

double mean_luminance(const Image& im, const PixelMask& m) {
  double sum = 0;
  for (size_t i = 0; i < m.inside.size(); ++i)
    if (m.inside[i]) sum += luminance(im, i);
  return sum / static_cast<double>(m.count);
}

}  // namespace

ShadowFinder::ShadowFinder(const std::vector<Image>& references,
                           const std::vector<std::vector<uint32_t>>& mesh_ids, ShadowRule rule)
    : references_(references), mesh_ids_(mesh_ids), rule_(rule) {
  if (references.empty() || references.size() != mesh_ids.size())
    throw std::invalid_argument("ShadowFinder: one mesh-id plane per reference, at least one");
  for (size_t k = 0; k < references.size(); ++k) {
    check_same_size(references[0], references[k], "ShadowFinder");
    if (mesh_ids[k].size() != references[k].pixel_count())
      throw std::invalid_argument("ShadowFinder: mesh ids of frame " + std::to_string(k) +
                                  " do not match its reference's size");
  }
}

ShadowRegions ShadowFinder::regions(size_t frame) const {
  const Image& ref = references_.at(frame);
  const std::vector<uint32_t>& mesh = mesh_ids_[frame];
  const int w = ref.width(), h = ref.height();
  const size_t n = ref.pixel_count();
  // Each pixel's unshadowed level: its brightest reference on the same mesh over the sequence.
  std::vector<double> level(n, 0.0);
  for (size_t k = 0; k < references_.size(); ++k)
    for (size_t i = 0; i < n; ++i)
      if (mesh_ids_[k][i] == mesh[i]) level[i] = std::max(level[i], luminance(references_[k], i));
  ShadowRegions r;
  r.shadow.inside.assign(n, 0);
  r.lit.inside.assign(n, 0);
  for (size_t i = 0; i < n; ++i)
    if (mesh[i] != 0 && level[i] > 0 && luminance(ref, i) < rule_.shadow_fraction * level[i]) {
      r.shadow.inside[i] = 1;
      ++r.shadow.count;
    }
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = static_cast<size_t>(y) * w + x;
      if (mesh[i] == 0 || r.shadow.inside[i] || !(luminance(ref, i) > rule_.lit_fraction * level[i]))
        continue;
      bool near_shadow = false;
      for (int dy = -rule_.ring; dy <= rule_.ring && !near_shadow; ++dy)
        for (int dx = -rule_.ring; dx <= rule_.ring; ++dx) {
          const int qx = x + dx, qy = y + dy;
          if (qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
          const size_t q = static_cast<size_t>(qy) * w + qx;
          if (r.shadow.inside[q] && mesh[q] == mesh[i]) {
            near_shadow = true;
            break;
          }
        }
      if (near_shadow) {
        r.lit.inside[i] = 1;
        ++r.lit.count;
      }
    }
  return r;
}

double shadow_contrast(const Image& image, const ShadowRegions& regions) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (regions.shadow.count == 0 || regions.lit.count == 0) return nan;
  if (regions.shadow.inside.size() != image.pixel_count() || image.channels() < 3)
    throw std::invalid_argument("shadow_contrast: regions and image of different sizes");
  const double lit = mean_luminance(image, regions.lit);
  if (!(lit > 0)) return nan;
  return 1.0 - mean_luminance(image, regions.shadow) / lit;
}

PixelMask changed_pixels(const Image& reference_before, const Image& reference_after,
                         const std::vector<uint32_t>& mesh_before,
                         const std::vector<uint32_t>& mesh_after, float relative, float floor) {
  check_same_size(reference_before, reference_after, "changed_pixels");
  const size_t n = reference_after.pixel_count();
  if (mesh_before.size() != n || mesh_after.size() != n)
    throw std::invalid_argument("changed_pixels: mesh ids and references of different sizes");
  PixelMask m;
  m.inside.assign(n, 0);
  for (size_t i = 0; i < n; ++i) {
    if (mesh_before[i] != mesh_after[i] || mesh_after[i] == 0) continue;
    const double a = luminance(reference_before, i), b = luminance(reference_after, i);
    if (std::abs(a - b) > std::max<double>(relative * std::max(a, b), floor)) {
      m.inside[i] = 1;
      ++m.count;
    }
  }
  return m;
}

double relmse_in(const Image& test, const Image& reference, const PixelMask& mask) {
  check_same_size(test, reference, "relmse_in");
  if (mask.inside.size() != test.pixel_count())
    throw std::invalid_argument("relmse_in: mask and images of different sizes");
  if (mask.count == 0) return std::numeric_limits<double>::quiet_NaN();
  double sum = 0;
  for (int c = 0; c < 3; ++c) {
    const float* t = test.plane(c);
    const float* r = reference.plane(c);
    for (size_t i = 0; i < mask.inside.size(); ++i) {
      if (!mask.inside[i]) continue;
      const double d = double(t[i]) - double(r[i]);
      sum += d * d / (double(r[i]) * double(r[i]) + 0.01);
    }
  }
  return sum / (3.0 * static_cast<double>(mask.count));
}

int lag_frames(const std::vector<double>& error_db, size_t change, size_t window,
               double tolerance_db) {
  if (window < 1 || change < window || change >= error_db.size())
    throw std::invalid_argument("lag_frames: needs window >= 1 frames before the change");
  double steady = 0;
  for (size_t k = change - window; k < change; ++k) steady += error_db[k];
  steady /= static_cast<double>(window);
  for (size_t k = change; k < error_db.size(); ++k)
    if (error_db[k] <= steady + tolerance_db) return static_cast<int>(k - change);
  return -1;
}

int lag_frames(const std::vector<double>& error_db, const std::vector<double>& baseline_db,
               size_t change, double tolerance_db) {
  if (baseline_db.size() != error_db.size() || change >= error_db.size())
    throw std::invalid_argument("lag_frames: a baseline per frame, the change inside");
  for (size_t k = change; k < error_db.size(); ++k)
    if (error_db[k] <= baseline_db[k] + tolerance_db) return static_cast<int>(k - change);
  return -1;
}

std::vector<double> restart_baseline(const std::vector<double>& error_db, size_t change) {
  if (change == 0 || change >= error_db.size())
    throw std::invalid_argument("restart_baseline: the change must be inside the sequence");
  std::vector<double> b = error_db;
  for (size_t k = change; k < error_db.size(); ++k) b[k] = error_db[k - change];
  return b;
}

StaticConvergence static_convergence(const std::vector<double>& psnr, size_t settled) {
  if (psnr.size() <= settled)
    throw std::invalid_argument("static_convergence: needs frames after the settled one");
  StaticConvergence c;
  for (size_t k = settled; k + 1 < psnr.size(); ++k)
    c.worst_drop = std::max(c.worst_drop, psnr[k] - psnr[k + 1]);
  c.gain = psnr.back() - psnr[settled];
  return c;
}

}  // namespace svgf::metrics

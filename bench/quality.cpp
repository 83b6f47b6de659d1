#include "bench/quality.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "metrics/display_range.h"
#include "metrics/flip.h"
#include "metrics/image_metrics.h"
#include "metrics/ssim.h"

namespace svgf::bench {
namespace {

using metrics::clamp01;

void check_same(const Image& a, const Image& b) {
  if (a.width() != b.width() || a.height() != b.height() || a.channels() < 3 || b.channels() < 3)
    throw std::invalid_argument("temporal metrics: images differ in size or channels");
}

}  // namespace

double mean_abs_change(const Image& a, const Image& b) {
  check_same(a, b);
  double sum = 0;
  for (int c = 0; c < 3; ++c)
    for (size_t i = 0; i < a.pixel_count(); ++i)
      sum += std::abs(clamp01(a.plane(c)[i]) - clamp01(b.plane(c)[i]));
  return a.pixel_count() ? sum / (3.0 * static_cast<double>(a.pixel_count())) : 0.0;
}

double mean_abs_error_change(const Image& out, const Image& ref, const Image& prev_out,
                             const Image& prev_ref) {
  check_same(out, ref);
  check_same(out, prev_out);
  check_same(out, prev_ref);
  double sum = 0;
  for (int c = 0; c < 3; ++c)
    for (size_t i = 0; i < out.pixel_count(); ++i) {
      const double e = clamp01(out.plane(c)[i]) - clamp01(ref.plane(c)[i]);
      const double e_prev = clamp01(prev_out.plane(c)[i]) - clamp01(prev_ref.plane(c)[i]);
      sum += std::abs(e - e_prev);
    }
  return out.pixel_count() ? sum / (3.0 * static_cast<double>(out.pixel_count())) : 0.0;
}

FrameQuality QualityTracker::add(const Image& out, const Image& reference, bool cut) {
  FrameQuality q;
  q.psnr = metrics::psnr(out, reference);
  q.ssim = metrics::ssim(out, reference);
  q.relmse = metrics::relmse(out, reference);
  q.flip = metrics::flip(out, reference);
  if (has_prev_ && !cut) {
    q.error_change = mean_abs_error_change(out, reference, prev_out_, prev_ref_);
    q.output_change = mean_abs_change(out, prev_out_);
  }
  prev_out_ = out;
  prev_ref_ = reference;
  has_prev_ = true;
  return q;
}

}  // namespace svgf::bench

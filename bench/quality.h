#pragma once
// Per-frame quality of a denoised sequence against its reference: PSNR, SSIM, relMSE and FLIP
// (metrics/), plus two temporal-stability measures (docs/metrics.md):
//  - error change: mean over pixels and channels of |e_t - e_(t-1)| with e = out - reference on
//    values clamped to [0, 1]: flicker of the error, which a reference that itself moves (the
//    scene animates) does not count;
//  - output change: mean |out_t - out_(t-1)| on clamped values: flicker of the output, the
//    measure for a static scene, where the ideal output does not change at all.
// Both are undefined on a sequence's first frame and on a camera cut.
#include <optional>

#include "core/image.h"

namespace svgf::bench {

struct FrameQuality {
  double psnr = 0, ssim = 0, relmse = 0, flip = 0;
  std::optional<double> error_change, output_change;
};

double mean_abs_change(const Image& a, const Image& b);
double mean_abs_error_change(const Image& out, const Image& ref, const Image& prev_out,
                             const Image& prev_ref);

// Feeds a sequence's frames in order.
class QualityTracker {
 public:
  FrameQuality add(const Image& out, const Image& reference, bool cut);

 private:
  Image prev_out_, prev_ref_;
  bool has_prev_ = false;
};

}  // namespace svgf::bench

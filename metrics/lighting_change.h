#pragma once
// How a denoiser follows lighting that changes (issue 12; docs/metrics.md, "Shadow contrast and
// lag"): the contrast of a moving shadow against its reference's, and the lag, in frames, until
// the error returns to its steady level after the light changes. Both find their regions from
// the sequence's references and mesh ids alone, so any rendered sequence with a still camera
// can be measured (the measures compare pixels across frames).
#include <cstdint>
#include <vector>

#include "core/image.h"

namespace svgf::metrics {

// A set of pixels of one frame.
struct PixelMask {
  std::vector<uint8_t> inside;  // width * height, 1 = in the region
  size_t count = 0;
};

// Where a moving shadow lies in one frame, and the lit pixels of the same surfaces around it.
// A pixel's unshadowed level is the largest luminance its reference reaches over the sequence on
// frames where it shows the same mesh; the pixel is in shadow where its reference lies below
// `shadow_fraction` of that level, lit where it lies above `lit_fraction` of it within `ring`
// pixels (Chebyshev distance) of a shadow pixel of the same mesh. Background pixels (mesh 0)
// never count; nor do pixels between the two fractions (penumbrae).
struct ShadowRule {
  float shadow_fraction = 0.5f;
  float lit_fraction = 0.9f;
  int ring = 4;
};

struct ShadowRegions {
  PixelMask shadow, lit;
};

class ShadowFinder {
 public:
  // references[k] and mesh_ids[k] of every frame k of the sequence (equal sizes, still camera).
  ShadowFinder(const std::vector<Image>& references,
               const std::vector<std::vector<uint32_t>>& mesh_ids, ShadowRule rule = {});
  ShadowRegions regions(size_t frame) const;

 private:
  const std::vector<Image>& references_;
  const std::vector<std::vector<uint32_t>>& mesh_ids_;
  ShadowRule rule_;
};

// 1 - mean luminance over the shadow / mean luminance over the lit pixels (Rec. 709, linear):
// 0 where the shadow is gone, 1 for a black shadow. NaN when a region is empty or the lit mean
// is not positive.
double shadow_contrast(const Image& image, const ShadowRegions& regions);

// Pixels whose reference luminance changes between frames `before` and `after` by more than
// `relative` of the larger of the two (and at least `floor`), on the same mesh in both.
PixelMask changed_pixels(const Image& reference_before, const Image& reference_after,
                         const std::vector<uint32_t>& mesh_before,
                         const std::vector<uint32_t>& mesh_after, float relative = 0.25f,
                         float floor = 1e-3f);

// relMSE (image_metrics.h) over the pixels of `mask` only; NaN for an empty mask.
double relmse_in(const Image& test, const Image& reference, const PixelMask& mask);

// The lag after a change at frame `change`: the first k >= 0 with
// error_db[change + k] <= steady + tolerance_db, where steady is the mean of error_db over the
// `window` frames before the change (error in dB, lower is better, e.g. 10 log10 relMSE).
// -1 when the error never returns within the sequence. Needs change >= window >= 1.
int lag_frames(const std::vector<double>& error_db, size_t change, size_t window = 3,
               double tolerance_db = 1.0);

// The same against a baseline per frame: the first k >= 0 with
// error_db[change + k] <= baseline_db[change + k] + tolerance_db; -1 if never.
int lag_frames(const std::vector<double>& error_db, const std::vector<double>& baseline_db,
               size_t change, double tolerance_db = 1.0);

// The steady level of a sequence too short to reach one before the change (a history that
// still converges when the light changes): frame change + k is held to the error of frame k,
// the same pixels at the same history age after the sequence began. Frames before `change`
// keep their own error. A method that restarts exactly the changed pixels then lags 0 or 1
// frames; one that keeps the old light lags until its history forgets it.
std::vector<double> restart_baseline(const std::vector<double>& error_db, size_t change);

// A still scene's convergence (issue 12, item 4) from its PSNR per frame: the largest drop from
// one frame to the next after frame `settled`, and the gain from frame `settled` to the last.
// The rule: no drop above 0.1 dB, a gain of at least 2 dB (by frame 63). Needs more frames than
// `settled`.
struct StaticConvergence {
  double worst_drop = 0;  // dB
  double gain = 0;        // dB
  bool meets_rule() const { return worst_drop <= 0.1 && gain >= 2.0; }
};
StaticConvergence static_convergence(const std::vector<double>& psnr, size_t settled = 4);

}  // namespace svgf::metrics

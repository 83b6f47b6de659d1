#pragma once
// BMFR: blockwise multi-order feature regression (Koskela et al. 2019, ACM TOG 38(5)). Defaults
// are the paper's and the authors' OpenCL implementation's (bmfr.cpp / bmfr.cl, docs/bmfr.md).
#include <cmath>
#include <stdexcept>
#include <string>

namespace svgf {

// What a block does with features that its pixels do not tell apart (a flat wall: the normal is
// constant, so n.xyz repeat the constant feature; the QR would divide by zero).
enum class BmfrRankStrategy {
  // The paper's: a small uniform noise (± noise_amount) added to every feature but the constant
  // one, so no column is ever exactly dependent (the authors' add_random, NOISE_AMOUNT 1e-2).
  Noise,
  // No noise; a column whose norm left after the earlier columns' reflections falls under
  // skip_threshold times the block's largest column norm is skipped (weight 0): the
  // numerical-rank rule of rank-revealing least squares.
  Skip,
};

inline const char* to_string(BmfrRankStrategy s) {
  return s == BmfrRankStrategy::Noise ? "noise" : "skip";
}
// "noise|skip"; throws std::invalid_argument naming the value.
inline BmfrRankStrategy parse_bmfr_rank_strategy(const std::string& s) {
  if (s == "noise") return BmfrRankStrategy::Noise;
  if (s == "skip") return BmfrRankStrategy::Skip;
  throw std::invalid_argument("--bmfr-rank must be noise or skip, got '" + s + "'");
}

struct BmfrParams {
  // Pre-accumulation of the noisy color (paper Sec. 4.1): blend toward this frame by
  // max(1 / (history + 1), alpha): a plain average until 1 / alpha samples (BLEND_ALPHA 0.2).
  float pre_alpha = 0.2f;
  // Post-accumulation of the regression's output with the same reprojection (SECOND_BLEND_ALPHA).
  float post_alpha = 0.1f;
  // A previous sample is taken when its world position lies within this squared distance
  // (POSITION_LIMIT_SQUARED 0.01, scene units) and its normal within this squared distance
  // (NORMAL_LIMIT_SQUARED 1: under 60 degrees).
  float position_limit_sq = 0.01f;
  float normal_limit_sq = 1.f;
  BmfrRankStrategy rank_strategy = BmfrRankStrategy::Noise;
  float noise_amount = 0.01f;     // NOISE_AMOUNT
  float skip_threshold = 1e-3f;   // Skip: the relative norm under which a column is dropped
  float albedo_epsilon = 1e-3f;   // as SVGF's demodulation (core/modulation.h)
  // The paper's optional last stage (Sec. 4.4): temporal anti-aliasing of the output
  // (core/taa.h), blending toward this frame by taa_alpha (TAA_BLEND_ALPHA 0.2). Off by default,
  // as the paper's quality numbers are given without it.
  bool taa = false;
  float taa_alpha = 0.2f;

  // std::invalid_argument naming the flag and its range.
  void validate() const {
    auto fail = [](const std::string& what) { throw std::invalid_argument("bmfr: " + what); };
    auto in_unit = [&](float v, const char* flag) {
      if (!(v > 0.f && v <= 1.f))
        fail(std::string(flag) + " must be in (0, 1], got " + std::to_string(v));
    };
    in_unit(pre_alpha, "--bmfr-pre-alpha");
    in_unit(post_alpha, "--bmfr-post-alpha");
    in_unit(taa_alpha, "--bmfr-taa-alpha");
    auto positive = [&](float v, const char* flag) {
      if (!(std::isfinite(v) && v > 0.f))
        fail(std::string(flag) + " must be finite and > 0, got " + std::to_string(v));
    };
    positive(position_limit_sq, "--bmfr-position-limit");
    positive(normal_limit_sq, "--bmfr-normal-limit");
    if (!(noise_amount >= 0.f && noise_amount <= 1.f))
      fail("--bmfr-noise must be in [0, 1], got " + std::to_string(noise_amount));
    if (!(skip_threshold >= 0.f && skip_threshold < 1.f))
      fail("--bmfr-skip-threshold must be in [0, 1), got " + std::to_string(skip_threshold));
    positive(albedo_epsilon, "albedo_epsilon");
  }
};

}  // namespace svgf

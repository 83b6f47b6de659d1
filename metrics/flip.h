#pragma once
// LDR-FLIP (Andersson, Nilsson, Akenine-Moller, Oskarsson, Astrom and Fairchild, "FLIP: A
// Difference Evaluator for Alternating Images", HPG 2020), written from the paper's description;
// docs/metrics.md gives the steps, the constants and this project's input convention.
#include "core/image.h"

namespace svgf::metrics {

struct FlipOptions {
  // Observer: pixels per degree of visual angle. The paper's default, 67, is a 0.7 m wide 4K
  // display seen from 0.7 m.
  double pixels_per_degree = 67.0;
};

// Per-pixel FLIP error in [0, 1] (1 channel, same size as the inputs). Inputs are linear RGB;
// values are clamped to [0, 1] first (NaN counts as 0), the LDR range the metric is defined on.
Image flip_map(const Image& test, const Image& reference, const FlipOptions& options = {});
// Mean of flip_map: 0 for identical images.
double flip(const Image& test, const Image& reference, const FlipOptions& options = {});
// The mean of a flip_map (what flip() returns), for callers that keep the map.
double flip_mean(const Image& map);

}  // namespace svgf::metrics

#pragma once
// Quality on the evaluation set (gbuffer/eval_set.*, `svgf-fixtures eval`): every configuration
// of the charts (quality_configs, CPU exact) over every complete sequence of the set's folder,
// PSNR/FLIP/... per frame against the references, written as one JSON that `chart-data
// --quality` reads in place of the fixture quality (docs/benchmarks.md).
#include <string>

namespace svgf::bench {

struct EvalQualityOptions {
  std::string set_dir;   // one sequence folder per scene (manifest.json once complete)
  std::string out_file;  // the quality JSON
  int threads = 0;       // 0: all
  std::string command;
};

// The references' own noise (gbuffer/reference_noise.h, ReferenceNoise): each frame's estimate, from
// the reference's two halves, is in the sequence's eval.json. A method's MSE against the
// reference is its MSE against the true image plus that noise, so the file's `psnr_corrected`
// is 10 log10(1 / (MSE - noise)) per frame: the PSNR against the true image, which the charts
// take. A scene counts in the "clean" means (and is corrected) when every frame has an estimate
// and at most kMaxClampedShare of it comes from values at PSNR's clamp, where the estimate is
// biased low (reference_noise.h); the others are named with the reason, measured PSNR only.
inline constexpr double kMaxClampedShare = 0.05;

int run_eval_quality(const EvalQualityOptions& o);

}  // namespace svgf::bench

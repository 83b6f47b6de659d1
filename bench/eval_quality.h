#pragma once
// Quality on the evaluation set (gbuffer/eval_set.*, `svgf-fixtures eval`): every configuration
// of the charts (quality_configs, CPU exact) over every complete sequence of the set's folder,
// PSNR/FLIP/... per frame against the references, written as one JSON that `chart-data
// --quality` reads in place of the fixture quality (docs/benchmarks.md).
#include <map>
#include <string>

namespace svgf::bench {

struct EvalQualityOptions {
  std::string set_dir;   // one sequence folder per scene (manifest.json once complete)
  std::string out_file;  // the quality JSON
  int threads = 0;       // 0: all
  std::string command;
};

// One reference's own noise PSNR per scene of the set (docs/gbuffer.md "Reference noise",
// 640x360, 256 spp, frame 0). A scene counts in the "clean" means when its reference is at
// least kCleanReferenceDb: there the reference is 8 dB or more above the 27-32 dB that the
// methods score, so the measured differences are the methods'. Scenes not in the table
// (unmeasured) are left out of the clean means too.
const std::map<std::string, double>& reference_noise_db();
inline constexpr double kCleanReferenceDb = 35.0;

int run_eval_quality(const EvalQualityOptions& o);

}  // namespace svgf::bench

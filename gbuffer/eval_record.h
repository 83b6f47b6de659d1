#pragma once
// eval.json, the evaluation set's record of one sequence folder (eval_set.h): the parameters it
// is rendered with, the SHA-256 of each frame written so far (so a later run can tell which
// frames to keep and whether the parameters changed) and each frame's reference noise.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "gbuffer/reference_noise.h"

namespace svgf::gbuffer {

struct EvalRecord {
  std::string scene;
  std::string generator;  // generator_tag()
  int width = 0, height = 0, frames = 0, spp = 0, reference_spp = 0;
  uint64_t seed = 0;
  bool split = false, gradients = false;
  std::vector<std::string> sha256;  // per frame; "" where none is written yet
  // Per frame, the reference's noise: NaN fields where none is recorded (not written yet, a
  // reference under 2 samples, or a record from before it was kept).
  std::vector<ReferenceNoise> reference_noise;
  // False for a record from before the noise was kept (format 1): its frames have none.
  bool records_reference_noise = true;

  bool complete() const;
};

// The frames' mean reference noise MSE, and the share of it at the clamp (ReferenceNoise's
// clamped_share over the whole sequence); NaN unless every frame has them.
struct SequenceNoise {
  double mse, clamped_share;
};
SequenceNoise sequence_reference_noise(const EvalRecord& record);

// The parameters that differ, as "size 320x180 in the cache, 640x360 asked" phrases.
std::vector<std::string> parameter_differences(const EvalRecord& cached, const EvalRecord& wanted);

// <dir>/eval.json. read: nullopt when absent; throws std::runtime_error naming the file when it
// cannot be parsed. write: atomically.
std::optional<EvalRecord> read_eval_record(const std::string& dir);
void write_eval_record(const std::string& dir, const EvalRecord& record);

}  // namespace svgf::gbuffer

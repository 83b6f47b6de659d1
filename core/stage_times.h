#pragma once
// Time spent per stage of one frame, keyed by the stage's name. Core knows no method: each
// method names its own stages (e.g. methods/svgf/stages.h) and the engines record whatever name
// they are given. The transfers between host and device are the engines' own two stages.
#include <string>
#include <utility>
#include <vector>

namespace svgf {

// The engines' own stages (CUDA only): host -> device and device -> host; on the device path
// (Denoiser::denoise_device) the copies from the caller's buffers into the denoiser's planes and
// from its output plane into the caller's output.
inline constexpr const char* kUploadStage = "upload";
inline constexpr const char* kDownloadStage = "download";
inline constexpr const char* kCopyInStage = "copy_in";
inline constexpr const char* kCopyOutStage = "copy_out";

// Every method's first stage, run by the backend on the frame's inputs (core/sanitize.h).
inline constexpr const char* kSanitizeStage = "sanitize";

inline bool is_transfer_stage(const std::string& name) {
  return name == kUploadStage || name == kDownloadStage || name == kCopyInStage ||
         name == kCopyOutStage;
}

// Milliseconds per stage, in the order the stages first ran (a stage run several times, like
// the a-trous iterations, adds up under one name).
class StageTimes {
 public:
  void add(const char* stage, double ms) {
    for (auto& e : entries_)
      if (e.first == stage) {
        e.second += ms;
        return;
      }
    entries_.emplace_back(stage, ms);
  }
  // 0 for a stage that did not run.
  double operator[](const std::string& stage) const {
    for (const auto& e : entries_)
      if (e.first == stage) return e.second;
    return 0.0;
  }
  const std::vector<std::pair<std::string, double>>& entries() const { return entries_; }
  // Sum of the filtering stages, transfers excluded.
  double filter_ms() const {
    double t = 0;
    for (const auto& e : entries_)
      if (!is_transfer_stage(e.first)) t += e.second;
    return t;
  }
  void clear() { entries_.clear(); }

 private:
  std::vector<std::pair<std::string, double>> entries_;
};

}  // namespace svgf

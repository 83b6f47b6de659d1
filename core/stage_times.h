#pragma once
// Names of the pipeline's stages, for timings and reports.
#include <array>

namespace svgf {

enum class Stage : int {
  Demodulate = 0,
  Reproject,
  Variance,
  Atrous,      // all a-trous iterations together
  Feedback,    // copying the feedback tap into the color history
  Remodulate,
  Upload,      // host -> device (CUDA only)
  Download,    // device -> host (CUDA only)
  Count
};

inline const char* stage_name(Stage s) {
  switch (s) {
    case Stage::Demodulate: return "demodulate";
    case Stage::Reproject: return "reproject";
    case Stage::Variance: return "variance";
    case Stage::Atrous: return "atrous";
    case Stage::Feedback: return "feedback";
    case Stage::Remodulate: return "remodulate";
    case Stage::Upload: return "upload";
    case Stage::Download: return "download";
    default: return "?";
  }
}

constexpr int kStageCount = static_cast<int>(Stage::Count);

// Milliseconds spent in each stage during one frame.
struct StageTimes {
  std::array<double, kStageCount> ms{};
  double& operator[](Stage s) { return ms[static_cast<int>(s)]; }
  double operator[](Stage s) const { return ms[static_cast<int>(s)]; }
  // Sum of the filtering stages, transfers excluded.
  double filter_ms() const {
    double t = 0;
    for (int s = 0; s < static_cast<int>(Stage::Upload); ++s) t += ms[s];
    return t;
  }
};

}  // namespace svgf

#pragma once
// SVGF's stage and debug-buffer names: what its reports time and what read_buffer() returns.
#include <string>
#include <vector>

#include "core/stage_times.h"

namespace svgf::svgf_stage {

inline constexpr const char* kDemodulate = "demodulate";  // fast mode: + reproject, one launch
inline constexpr const char* kReproject = "reproject";
inline constexpr const char* kVariance = "variance";
inline constexpr const char* kAtrous = "atrous";          // all iterations together
inline constexpr const char* kFeedback = "feedback";      // copy of the feedback tap
inline constexpr const char* kRemodulate = "remodulate";  // fast mode: in the last iteration
inline constexpr const char* kSplitSum = "split_sum";     // direct + indirect (split frames)

// A split frame runs every stage once per signal (the times add) and then kSplitSum.
inline std::vector<std::string> all() {
  return {kSanitizeStage, kDemodulate, kReproject, kVariance, kAtrous, kFeedback, kRemodulate,
          kSplitSum};
}

}  // namespace svgf::svgf_stage

namespace svgf::svgf_buffer {

inline constexpr const char* kIllumination = "illumination";  // 3: demodulated input
inline constexpr const char* kAccumulated = "accumulated";    // 4: color + temporal variance
inline constexpr const char* kMoments = "moments";            // 2: E[l], E[l^2]
inline constexpr const char* kHistoryLength = "history_length";  // 1
inline constexpr const char* kColorHistory = "color_history";    // 3: the feedback tap

inline std::vector<std::string> all() {
  return {kIllumination, kAccumulated, kMoments, kHistoryLength, kColorHistory};
}

}  // namespace svgf::svgf_buffer

#pragma once
// SVGF's stage and debug-buffer names: what its reports time and what read_buffer() returns.
#include <string>
#include <vector>

#include "core/stage_times.h"

namespace svgf::svgf_stage {

// A-SVGF (--antilag gradient, on frames with gradient samples), before the reprojection.
inline constexpr const char* kGradient = "gradient";                // samples per stratum
inline constexpr const char* kGradientAtrous = "gradient_atrous";   // all iterations together
inline constexpr const char* kGradientLambda = "gradient_lambda";
inline constexpr const char* kDemodulate = "demodulate";  // CUDA: + reproject, one launch
inline constexpr const char* kReproject = "reproject";
inline constexpr const char* kVariance = "variance";
inline constexpr const char* kAtrous = "atrous";          // all iterations together
inline constexpr const char* kFeedback = "feedback";      // copy of the feedback tap
inline constexpr const char* kRemodulate = "remodulate";  // CUDA: in the last iteration
inline constexpr const char* kTaa = "taa";                // only with --svgf-taa on
inline constexpr const char* kSplitSum = "split_sum";     // direct + indirect (split frames)

// A split frame runs every stage but the gradients' and TAA once per signal (the times add),
// then kSplitSum.
inline std::vector<std::string> all(bool taa) {
  std::vector<std::string> v = {kSanitizeStage, kGradient, kGradientAtrous, kGradientLambda,
                                kDemodulate,    kReproject, kVariance,     kAtrous,
                                kFeedback,      kRemodulate, kSplitSum};
  if (taa) v.push_back(kTaa);
  return v;
}

}  // namespace svgf::svgf_stage

namespace svgf::svgf_buffer {

inline constexpr const char* kIllumination = "illumination";  // 3: demodulated input
inline constexpr const char* kAccumulated = "accumulated";    // 4: color + temporal variance
inline constexpr const char* kMoments = "moments";            // 2: E[l], E[l^2]
inline constexpr const char* kHistoryLength = "history_length";  // 1
inline constexpr const char* kColorHistory = "color_history";    // 3: the feedback tap
inline constexpr const char* kTaaHistory = "taa_history";        // 3: only with --svgf-taa on

// The illumination and the accumulation are frame scratch: readable only where the denoiser
// keeps them apart (EngineConfig::keep_scratch; else the a-trous buffers reuse their memory).
inline std::vector<std::string> all(bool taa, bool scratch) {
  std::vector<std::string> v;
  if (scratch) v = {kIllumination, kAccumulated};
  for (const char* name : {kMoments, kHistoryLength, kColorHistory}) v.push_back(name);
  if (taa) v.push_back(kTaaHistory);
  return v;
}

}  // namespace svgf::svgf_buffer

#pragma once
// Where a frame's wall time goes in svgf denoise: each frame's read, denoise and write times, and
// what they add up to against the wall time of the whole frame loop (docs/cli.md, "Where the
// time goes"). With frames overlapping, the wall time per frame is less than the stages' sum.
#include <vector>

#include <nlohmann/json.hpp>

namespace svgf::app {

// One frame's stages, in milliseconds of wall time each.
struct FrameTimes {
  double read_ms = 0;     // reading and decoding the input EXR
  double denoise_ms = 0;  // the denoiser alone: report.json's time_ms
  double write_ms = 0;    // output EXR, preview PNG, the report's row and images
};

struct TimingSummary {
  int frames = 0, in_flight = 0;
  double median_read_ms = 0, median_denoise_ms = 0, median_write_ms = 0;
  double stage_sum_ms_per_frame = 0;  // mean of read + denoise + write
  double wall_ms_per_frame = 0;       // the frame loop's wall time / frames
  double speedup = 0;                 // stage sum / wall: what overlapping the stages gained
};

// `loop_ms`: the frame loop's wall time; `in_flight`: the frames it held at most.
TimingSummary summarize_timing(const std::vector<FrameTimes>& frames, double loop_ms,
                               int in_flight);

nlohmann::json to_json(const TimingSummary& t);

}  // namespace svgf::app

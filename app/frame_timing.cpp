#include "app/frame_timing.h"

#include "core/order_stats.h"

namespace svgf::app {

TimingSummary summarize_timing(const std::vector<FrameTimes>& frames, double loop_ms,
                               int in_flight) {
  TimingSummary t;
  t.frames = static_cast<int>(frames.size());
  t.in_flight = in_flight;
  if (frames.empty()) return t;
  std::vector<double> read, denoise, write;
  double sum = 0;
  for (const FrameTimes& f : frames) {
    read.push_back(f.read_ms);
    denoise.push_back(f.denoise_ms);
    write.push_back(f.write_ms);
    sum += f.read_ms + f.denoise_ms + f.write_ms;
  }
  t.median_read_ms = order_stats(read).median;
  t.median_denoise_ms = order_stats(denoise).median;
  t.median_write_ms = order_stats(write).median;
  t.stage_sum_ms_per_frame = sum / t.frames;
  t.wall_ms_per_frame = loop_ms / t.frames;
  t.speedup = loop_ms > 0 ? sum / loop_ms : 0;
  return t;
}

nlohmann::json to_json(const TimingSummary& t) {
  return {{"frames_in_flight", t.in_flight},
          {"median_read_ms", t.median_read_ms},
          {"median_denoise_ms", t.median_denoise_ms},
          {"median_write_ms", t.median_write_ms},
          {"stage_sum_ms_per_frame", t.stage_sum_ms_per_frame},
          {"wall_ms_per_frame", t.wall_ms_per_frame},
          {"speedup_over_stage_sum", t.speedup}};
}

}  // namespace svgf::app

#pragma once
// Feeds the tools' shared progress bar (cli/progress_bar.h) from the renderer's atomic counters:
// its own thread polls them 10 times a second, shows the frames rendered (a frame partly
// rendered counts in part) and the rays per second so far, and forwards SIGINT to the renderer
// (counters.cancel).
#include <atomic>
#include <cstdint>
#include <string>
#include <thread>

#include "cli/progress_bar.h"
#include "gbuffer/renderer.h"

namespace svgf::gbuffer::tool {

class Progress {
 public:
  // `frames` of `rows_per_frame` rows each; `label`: e.g. the scene name.
  Progress(std::string label, int frames, int rows_per_frame, RenderCounters& counters);
  ~Progress();  // stops the polling thread and draws the last line
  double seconds() const { return bar_.seconds(); }

 private:
  void show();
  int rows_per_frame_;
  RenderCounters& counters_;  // cancel is set here when the user interrupts
  cli::ProgressBar bar_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

std::string format_rate(double rays_per_second);  // "12.3 Mrays/s"

}  // namespace svgf::gbuffer::tool

#pragma once
// A progress bar on stderr, redrawn by its own thread from the renderer's atomic counters, with
// the achieved rays per second. It also forwards SIGINT to the renderer (counters.cancel).
#include <atomic>
#include <chrono>
#include <cstdint>
#include <string>
#include <thread>
#include <utility>

#include "gbuffer/renderer.h"

namespace svgf::gbuffer::tool {

class Progress {
 public:
  // `total_rows`: rows of all frames of the task; `label`: e.g. the scene name.
  Progress(std::string label, uint64_t total_rows, RenderCounters& counters);
  ~Progress();  // stops the display thread and ends the line
  void set_frame(int done, int total) { frame_done_ = done; frame_total_ = total; }
  double seconds() const;

 private:
  void draw(bool final);
  std::string label_;
  uint64_t total_rows_;
  RenderCounters& counters_;  // cancel is set here when the user interrupts
  std::atomic<int> frame_done_{0}, frame_total_{0};
  std::atomic<bool> stop_{false};
  bool tty_;
  std::chrono::steady_clock::time_point start_;
  std::thread thread_;
};

std::string format_rate(double rays_per_second);  // "12.3 Mrays/s"

}  // namespace svgf::gbuffer::tool

#include "tool/progress.h"

#include "tool/commands.h"

#include <chrono>
#include <cstdio>

namespace svgf::gbuffer::tool {

std::string format_rate(double r) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.2f Mrays/s", r / 1e6);
  return buf;
}

Progress::Progress(std::string label, int frames, int rows_per_frame, RenderCounters& counters)
    : rows_per_frame_(rows_per_frame > 0 ? rows_per_frame : 1), counters_(counters),
      bar_(std::move(label), frames) {
  thread_ = std::thread([this] {
    while (!stop_.load()) {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      if (interrupted()) counters_.cancel = true;
      show();  // the bar decides what to draw: in place on a terminal, a line now and then in a log
    }
  });
}

Progress::~Progress() {
  stop_ = true;
  thread_.join();
  show();  // all rows done draws the last line; an interrupted run's line is ended by the bar
}

void Progress::show() {
  const double t = bar_.seconds();
  const double rate = t > 0.0 ? static_cast<double>(counters_.rays.load()) / t : 0.0;
  bar_.update(static_cast<double>(counters_.rows.load()) / rows_per_frame_, format_rate(rate));
}

}  // namespace svgf::gbuffer::tool

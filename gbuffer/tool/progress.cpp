#include "tool/progress.h"

#include "tool/commands.h"

#include <unistd.h>

#include <cstdio>

namespace svgf::gbuffer::tool {

std::string format_rate(double r) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.2f Mrays/s", r / 1e6);
  return buf;
}

Progress::Progress(std::string label, uint64_t total_rows, RenderCounters& counters)
    : label_(std::move(label)), total_rows_(total_rows ? total_rows : 1), counters_(counters),
      tty_(isatty(STDERR_FILENO) != 0), start_(std::chrono::steady_clock::now()) {
  thread_ = std::thread([this] {
    int ticks = 0;
    while (!stop_.load()) {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      if (interrupted()) counters_.cancel = true;
      // Redraw in place on a terminal; a line every 10 s into a log.
      if (tty_ || (++ticks % 100) == 0) draw(false);
    }
  });
}

Progress::~Progress() {
  stop_ = true;
  thread_.join();
  draw(true);
}

double Progress::seconds() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void Progress::draw(bool final) {
  const double t = seconds();
  const uint64_t rows = counters_.rows.load();
  const double frac = static_cast<double>(rows) / static_cast<double>(total_rows_);
  const double rate = t > 0.0 ? static_cast<double>(counters_.rays.load()) / t : 0.0;
  constexpr int kWidth = 30;
  const int filled = static_cast<int>(frac * kWidth + 1e-9);
  std::string bar(static_cast<size_t>(filled < kWidth ? filled : kWidth), '#');
  bar.resize(kWidth, '-');
  const double eta = frac > 0.0 ? t / frac - t : 0.0;
  std::fprintf(stderr, "%s%-16s [%s] %5.1f%%  frame %d/%d  %s  %.1fs elapsed, ~%.0fs left%s",
               tty_ ? "\r" : "", label_.c_str(), bar.c_str(), 100.0 * frac, frame_done_.load(),
               frame_total_.load(), format_rate(rate).c_str(), t, final ? 0.0 : eta,
               (final || !tty_) ? "\n" : "");
  std::fflush(stderr);
}

}  // namespace svgf::gbuffer::tool

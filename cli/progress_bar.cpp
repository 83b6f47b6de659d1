#include "cli/progress_bar.h"

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace svgf::cli {

namespace {

constexpr int kBarWidth = 30;
constexpr double kRedrawSeconds = 0.1;  // a terminal's redraw rate
constexpr double kLogSeconds = 10.0;    // a log's longest silence

double steady_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

}  // namespace

std::string format_duration(double s) {
  if (!(s > 0.0)) s = 0.0;  // NaN too
  char buf[32];
  if (s < 59.95) {
    std::snprintf(buf, sizeof buf, "%.1f s", s);
  } else if (s < 3599.5) {
    const long r = std::lround(s);
    std::snprintf(buf, sizeof buf, "%ldm%02lds", r / 60, r % 60);
  } else {
    const long m = std::lround(s / 60.0);
    std::snprintf(buf, sizeof buf, "%ldh%02ldm", m / 60, m % 60);
  }
  return buf;
}

std::string format_progress(const std::string& label, double done, int total, double elapsed_s,
                            const std::string& detail, const std::string& rate_unit) {
  const double fraction = total > 0 ? std::clamp(done / total, 0.0, 1.0) : 0.0;
  const int filled = std::min(kBarWidth, static_cast<int>(fraction * kBarWidth + 1e-9));
  std::string line = label + " [" + std::string(filled, '#') +
                     std::string(kBarWidth - filled, '.') + "] ";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%5.1f%%  %d/%d  ", 100.0 * fraction,
                static_cast<int>(std::floor(std::max(done, 0.0) + 1e-9)), total);
  line += buf;
  line += format_duration(elapsed_s);
  // Time left at the rate so far; none before any progress, nor once done.
  if (fraction > 0.0 && fraction < 1.0)
    line += ", ~" + format_duration(elapsed_s / fraction - elapsed_s) + " left";
  if (!rate_unit.empty() && done > 0.0 && elapsed_s > 0.0) {
    const double rate = done / elapsed_s;
    std::snprintf(buf, sizeof buf, ", %.*f %s", rate < 10.0 ? 2 : 1, rate, rate_unit.c_str());
    line += buf;
  }
  if (!detail.empty()) line += "  " + detail;
  return line;
}

ProgressBar::ProgressBar(std::string label, int total) : ProgressBar(std::move(label), total, {}) {}

ProgressBar::ProgressBar(std::string label, int total, Terminal terminal)
    : label_(std::move(label)), total_(total), terminal_(std::move(terminal)) {
  if (!terminal_.clock) terminal_.clock = steady_seconds;
  tty_ = terminal_.tty >= 0 ? terminal_.tty != 0 : isatty(fileno(terminal_.out)) != 0;
  start_ = terminal_.clock();
}

ProgressBar::~ProgressBar() {
  if (open_line_) {
    std::fputc('\n', terminal_.out);
    std::fflush(terminal_.out);
  }
}

double ProgressBar::seconds() const { return terminal_.clock() - start_; }

void ProgressBar::update(double done, const std::string& detail) {
  if (finished_ || total_ <= 0) return;
  const bool finished = done >= total_;
  const double now = terminal_.clock();
  const int tenth = static_cast<int>(std::floor(10.0 * std::max(done, 0.0) / total_));
  const bool due = tty_ ? last_draw_ < 0.0 || now - last_draw_ >= kRedrawSeconds
                        : tenth != last_tenth_ || now - last_draw_ >= kLogSeconds;
  if (!due && !finished) return;
  last_draw_ = now;
  last_tenth_ = tenth;
  finished_ = finished;
  draw(done, detail, finished);
}

int ProgressBar::columns() const {
  if (terminal_.width > 0) return terminal_.width;
  winsize size{};
  if (ioctl(fileno(terminal_.out), TIOCGWINSZ, &size) == 0 && size.ws_col > 0) return size.ws_col;
  return 80;
}

void ProgressBar::draw(double done, const std::string& detail, bool finished) {
  std::string line = format_progress(label_, done, total_, seconds(), detail, rate_unit_);
  if (!tty_) {
    std::fprintf(terminal_.out, "%s\n", line.c_str());
    std::fflush(terminal_.out);
    return;
  }
  // One column short of the width: a line filling the last column wraps on some terminals.
  size_t cut = static_cast<size_t>(std::max(1, columns() - 1));
  if (line.size() > cut) {
    while (cut > 0 && (static_cast<unsigned char>(line[cut]) & 0xC0) == 0x80) --cut;  // UTF-8
    line.resize(cut);
  }
  const size_t length = line.size();
  if (length < last_length_) line.append(last_length_ - length, ' ');
  last_length_ = length;
  std::fprintf(terminal_.out, "\r%s%s", line.c_str(), finished ? "\n" : "");
  std::fflush(terminal_.out);
  open_line_ = !finished;
}

}  // namespace svgf::cli

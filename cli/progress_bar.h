#pragma once
// The progress line every tool draws on stderr (svgf denoise, svgf-fixtures generate and verify).
// On a terminal it redraws in place, at most 10 times a second, cut to the terminal's width; into
// a log it writes a line at every tenth of the work and at least every 10 s, so logs stay short
// and a slow step still shows signs of life. Both show the elapsed time and the time left.
#include <cstdio>
#include <functional>
#include <string>
#include <utility>

namespace svgf::cli {

// "4.2 s", "3m07s", "1h02m".
std::string format_duration(double seconds);

// One line, without the terminal's '\r':
// "denoise [###############...............]  50.0%  5/10  2.0 s, ~2.0 s left  3.1 ms, PSNR 31 dB".
// `done` may be fractional (a frame partly rendered); the count shows the whole units.
// `rate_unit` (e.g. "fps"): when set, the units per second over the whole run so far follow the
// times ("2.0 s, ~2.0 s left, 2.50 fps"), once something is done.
std::string format_progress(const std::string& label, double done, int total, double elapsed_s,
                            const std::string& detail, const std::string& rate_unit = "");

class ProgressBar {
 public:
  // Where the bar draws and how it tells time; tests give a buffer, a width and a fake clock.
  struct Terminal {
    std::FILE* out = stderr;
    int tty = -1;                   // 1: a terminal, 0: a log, -1: ask isatty
    int width = 0;                  // columns of a terminal; 0: ask it (80 when it does not say)
    std::function<double()> clock;  // seconds; empty: the steady clock
  };

  // `total`: units of work (frames); `label`: what is being done, e.g. "denoise" or a scene.
  ProgressBar(std::string label, int total);
  ProgressBar(std::string label, int total, Terminal terminal);
  // Ends a line left open on a terminal (a run stopped half way), so an error starts a new one.
  ~ProgressBar();
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  // Reaching `total` draws the last line (elapsed time, no estimate) and ends it; later
  // updates are ignored.
  void update(double done, const std::string& detail = "");
  double seconds() const;  // since the bar was made
  // Shows the throughput since the bar was made, in `unit` ("fps"): format_progress.
  void show_rate(std::string unit) { rate_unit_ = std::move(unit); }

 private:
  void draw(double done, const std::string& detail, bool finished);
  int columns() const;

  std::string label_;
  std::string rate_unit_;  // empty: no rate shown
  int total_;
  Terminal terminal_;
  bool tty_;
  double start_;
  double last_draw_ = -1.0;  // clock time of the last line drawn; < 0: none yet
  int last_tenth_ = -1;      // tenth of the work at the last log line
  size_t last_length_ = 0;   // of the line on the terminal, to blank what a shorter one leaves
  bool open_line_ = false;   // a terminal line drawn but not ended
  bool finished_ = false;
};

}  // namespace svgf::cli

#pragma once
// A one-line progress bar on stderr. On a terminal it redraws in place; otherwise (CI logs) it
// prints a line at every 10% so logs stay short.
#include <cstdio>
#include <string>

#include <unistd.h>

namespace svgf::app {

class ProgressBar {
 public:
  ProgressBar(std::string label, int total)
      : label_(std::move(label)), total_(total), tty_(isatty(fileno(stderr)) != 0) {}

  void update(int done, const std::string& detail) {
    if (total_ <= 0) return;
    const int width = 30;
    const int filled = done * width / total_;
    if (tty_) {
      std::fprintf(stderr, "\r%s [%s%s] %d/%d %s   ", label_.c_str(), std::string(filled, '#').c_str(),
                   std::string(width - filled, '.').c_str(), done, total_, detail.c_str());
      if (done == total_) std::fputc('\n', stderr);
    } else if (done * 10 / total_ != last_decile_ || done == total_) {
      last_decile_ = done * 10 / total_;
      std::fprintf(stderr, "%s %d/%d %s\n", label_.c_str(), done, total_, detail.c_str());
    }
    std::fflush(stderr);
  }

 private:
  std::string label_;
  int total_;
  bool tty_;
  int last_decile_ = -1;
};

}  // namespace svgf::app

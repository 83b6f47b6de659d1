// The tools' shared progress bar: the line, when it draws (terminal and log), and how it ends.
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "cli/progress_bar.h"

using svgf::cli::format_duration;
using svgf::cli::format_progress;
using svgf::cli::ProgressBar;

namespace {

// A bar drawing into memory with a clock the test sets.
struct FakeTerminal {
  char* buffer = nullptr;
  size_t size = 0;
  std::FILE* out = open_memstream(&buffer, &size);
  double now = 100.0;

  ProgressBar::Terminal terminal(bool tty, int width = 200) {
    ProgressBar::Terminal t;
    t.out = out;
    t.tty = tty ? 1 : 0;
    t.width = width;
    t.clock = [this] { return now; };
    return t;
  }
  std::string text() {
    std::fflush(out);
    return std::string(buffer, size);
  }
  ~FakeTerminal() {
    std::fclose(out);
    std::free(buffer);
  }
};

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

}  // namespace

TEST_CASE("format_duration: seconds, minutes, hours", "[cli][progress]") {
  CHECK(format_duration(0.0) == "0.0 s");
  CHECK(format_duration(-3.0) == "0.0 s");
  CHECK(format_duration(4.24) == "4.2 s");
  CHECK(format_duration(59.9) == "59.9 s");
  CHECK(format_duration(59.96) == "1m00s");
  CHECK(format_duration(187.0) == "3m07s");
  CHECK(format_duration(3725.0) == "1h02m");
}

TEST_CASE("format_progress: bar, percentage, count, elapsed, time left, detail",
          "[cli][progress]") {
  CHECK(format_progress("denoise", 5, 10, 2.0, "3.1 ms") ==
        "denoise [###############...............]  50.0%  5/10  2.0 s, ~2.0 s left  3.1 ms");
  // A frame partly rendered: the count shows whole frames, the bar and percentage the rest.
  CHECK(format_progress("cut", 2.5, 10, 10.0, "") ==
        "cut [#######.......................]  25.0%  2/10  10.0 s, ~30.0 s left");
  // Nothing done yet: no estimate; done: no estimate either.
  CHECK(format_progress("x", 0, 4, 1.0, "") ==
        "x [..............................]   0.0%  0/4  1.0 s");
  CHECK(format_progress("x", 4, 4, 75.0, "") ==
        "x [##############################] 100.0%  4/4  1m15s");
}

// Issue 14, item 4: svgf denoise shows its frames per second over the whole run so far.
TEST_CASE("format_progress: the rate over the whole run, when asked for", "[cli][progress]") {
  CHECK(format_progress("denoise", 5, 10, 2.0, "3.1 ms", "fps") ==
        "denoise [###############...............]  50.0%  5/10  2.0 s, ~2.0 s left, 2.50 fps"
        "  3.1 ms");
  CHECK(format_progress("denoise", 40, 40, 2.0, "", "fps") ==
        "denoise [##############################] 100.0%  40/40  2.0 s, 20.0 fps");
  // Nothing done, or no time yet: no rate.
  CHECK(format_progress("x", 0, 4, 1.0, "", "fps") ==
        "x [..............................]   0.0%  0/4  1.0 s");
  CHECK(format_progress("x", 1, 4, 0.0, "", "fps").find("fps") == std::string::npos);
  FakeTerminal term;
  {
    ProgressBar bar("denoise", 4, term.terminal(false));
    bar.show_rate("fps");
    term.now += 0.5;
    bar.update(1);
  }
  CHECK(term.text() ==
        "denoise [#######.......................]  25.0%  1/4  0.5 s, ~1.5 s left, 2.00 fps\n");
}

TEST_CASE("progress in a log: a line at every tenth and after 10 s of silence", "[cli][progress]") {
  FakeTerminal term;
  {
    ProgressBar bar("denoise", 20, term.terminal(false));
    for (int done = 1; done <= 20; ++done) {
      term.now += 0.5;
      bar.update(done, "f" + std::to_string(done));
    }
    bar.update(20, "after the end");  // ignored
  }
  const std::vector<std::string> out = lines(term.text());
  REQUIRE(out.size() == 11);  // the first update, then 2, 4, ..., 20 frames
  CHECK(out[0] == "denoise [#.............................]   5.0%  1/20  0.5 s, ~9.5 s left  f1");
  CHECK(out[1] == "denoise [###...........................]  10.0%  2/20  1.0 s, ~9.0 s left  f2");
  CHECK(out[10] == "denoise [##############################] 100.0%  20/20  10.0 s  f20");

  FakeTerminal slow;
  {
    ProgressBar bar("render", 100, slow.terminal(false));
    bar.update(0.5);   // first call: a line
    slow.now += 9.0;
    bar.update(0.6);   // same tenth, 9 s: none
    slow.now += 2.0;
    bar.update(0.7);   // 11 s since the last line: a line
  }
  const std::vector<std::string> slow_out = lines(slow.text());
  REQUIRE(slow_out.size() == 2);
  CHECK(slow_out[1].find("0/100  11.0 s") != std::string::npos);
  CHECK(slow.text().find('\r') == std::string::npos);
}

TEST_CASE("progress on a terminal: redrawn in place, at most 10 times a second, cut to the width",
          "[cli][progress]") {
  FakeTerminal term;
  {
    ProgressBar bar("denoise", 3, term.terminal(true, 50));
    bar.update(1, "a long detail that does not fit the terminal");
    bar.update(2, "too soon");  // same instant: not drawn
    term.now += 0.2;
    bar.update(2, "");
    term.now += 0.01;
    bar.update(3, "");  // the last frame is always drawn, and ends the line
  }
  const std::string text = term.text();
  const std::string first = "\rdenoise [##########....................]  33.3%  ";
  const std::string second = "\rdenoise [####################..........]  66.7%  ";
  const std::string last = "\rdenoise [##############################] 100.0%  ";
  REQUIRE(first.size() == 50);  // '\r' and 49 columns: one short of the width
  REQUIRE(text == first + second + last + "\n");
  CHECK(text.find("too soon") == std::string::npos);
}

TEST_CASE("progress on a terminal: a shorter line blanks the longer one's rest; a bar left open "
          "ends its line", "[cli][progress]") {
  FakeTerminal term;
  {
    ProgressBar bar("x", 10, term.terminal(true));
    bar.update(1, "long detail");
    term.now += 1.0;
    bar.update(2, "");
  }  // destroyed half way: the line is ended so an error message starts on its own
  const std::string text = term.text();
  const std::string one = format_progress("x", 1, 10, 0.0, "long detail");
  const std::string two = format_progress("x", 2, 10, 1.0, "");
  REQUIRE(two.size() < one.size());
  CHECK(text == "\r" + one + "\r" + two + std::string(one.size() - two.size(), ' ') + "\n");
}

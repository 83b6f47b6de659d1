#pragma once
// The tools' usage error and CLI11's class names, without CLI11 itself: its header costs about
// 10 s of compiler time per file at -O3 (its validators are objects every file constructs), so
// only the files that build a command line include cli/command_line.h.
#include <stdexcept>

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace svgf::cli {

// A bad or missing argument, or an impossible combination: the tool exits with 2.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace svgf::cli

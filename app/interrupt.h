#pragma once
// SIGINT and SIGTERM during svgf denoise. The handler only records the signal (the one thing
// that is async-signal-safe to do); the run looks at it between frames and between the input
// checks and stops there by throwing Interrupted, so removing the staging folder and writing
// the failure report run as ordinary code, during unwinding (docs/frame-format.md, "Signals").
#include <stdexcept>

namespace svgf::app {

class Interrupted : public std::runtime_error {
 public:
  explicit Interrupted(int signal_number);
  int signal_number() const { return signal_number_; }

 private:
  int signal_number_;
};

// Installs the handlers for its lifetime and puts the previous ones back afterwards. Each
// handler resets itself (SA_RESETHAND): a second Ctrl-C while the first is being honoured gets
// the default action and ends the process at once (its staging folder is then cleared by the
// next run).
class InterruptGuard {
 public:
  InterruptGuard();
  ~InterruptGuard();
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;
};

// Throws Interrupted when SIGINT or SIGTERM arrived since the guard was installed.
void throw_if_interrupted();

}  // namespace svgf::app

#include "app/interrupt.h"

#include <signal.h>

#include <string>

namespace svgf::app {
namespace {

volatile sig_atomic_t g_signal = 0;  // the signal received, 0 for none

void record_signal(int signal_number) { g_signal = signal_number; }

constexpr int kSignals[] = {SIGINT, SIGTERM};
struct sigaction g_previous[2];

const char* signal_name(int signal_number) {
  return signal_number == SIGINT ? "SIGINT" : signal_number == SIGTERM ? "SIGTERM" : "a signal";
}

}  // namespace

Interrupted::Interrupted(int signal_number)
    : std::runtime_error(std::string("interrupted by ") + signal_name(signal_number)),
      signal_number_(signal_number) {}

InterruptGuard::InterruptGuard() {
  g_signal = 0;
  struct sigaction action {};
  action.sa_handler = record_signal;
  sigemptyset(&action.sa_mask);
  // SA_RESTART: reads and writes in progress finish instead of failing with EINTR; the run
  // stops at its next check.
  action.sa_flags = SA_RESTART | SA_RESETHAND;
  for (int i = 0; i < 2; ++i) sigaction(kSignals[i], &action, &g_previous[i]);
}

InterruptGuard::~InterruptGuard() {
  for (int i = 0; i < 2; ++i) sigaction(kSignals[i], &g_previous[i], nullptr);
}

void throw_if_interrupted() {
  if (const int s = g_signal; s != 0) throw Interrupted(s);
}

}  // namespace svgf::app

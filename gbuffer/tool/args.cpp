#include <cerrno>
#include <csignal>
#include <cstdlib>

#include "gbuffer/renderer.h"
#include "tool/commands.h"

namespace svgf::gbuffer::tool {

namespace {
volatile std::sig_atomic_t g_interrupted = 0;
extern "C" void on_signal(int) { g_interrupted = 1; }
}  // namespace

bool interrupted() { return g_interrupted != 0; }

void install_interrupt_handler() {
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
}

std::string default_fixture_dir() { return SVGF_FIXTURES_DIR; }

namespace {

int side(const std::string& which, const std::string& value) {
  // Digits only (no sign, space or trailing text), then a range check.
  const bool digits = !value.empty() && value.size() <= 9 &&
                      value.find_first_not_of("0123456789") == std::string::npos;
  const long v = digits ? std::strtol(value.c_str(), nullptr, 10) : 0;
  if (v < 1 || v > kMaxImageSide)
    throw UsageError("--size: the " + which + " " + value + " is not an integer in 1.." +
                     std::to_string(kMaxImageSide));
  return static_cast<int>(v);
}

}  // namespace

void parse_size(const std::string& value, int& width, int& height) {
  const size_t x = value.find('x');
  if (x == std::string::npos) throw UsageError("--size " + value + ": expected WxH, e.g. 128x128");
  width = side("width", value.substr(0, x));
  height = side("height", value.substr(x + 1));
}

}  // namespace svgf::gbuffer::tool

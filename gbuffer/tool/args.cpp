#include <csignal>
#include <cstdlib>
#include <limits>

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

const std::string& value_of(const Args& args, size_t& i) {
  if (i + 1 >= args.size()) throw UsageError("option " + args[i] + " needs a value");
  return args[++i];
}

int parse_int(const std::string& option, const std::string& value, int lo, int hi) {
  char* end = nullptr;
  const long v = std::strtol(value.c_str(), &end, 10);
  if (value.empty() || *end != '\0' || v < lo || v > hi)
    throw UsageError(option + " " + value + ": expected an integer in " + std::to_string(lo) +
                     ".." + std::to_string(hi));
  return static_cast<int>(v);
}

uint64_t parse_u64(const std::string& option, const std::string& value) {
  char* end = nullptr;
  const unsigned long long v = std::strtoull(value.c_str(), &end, 10);
  if (value.empty() || value[0] == '-' || *end != '\0')
    throw UsageError(option + " " + value + ": expected a non-negative integer");
  return static_cast<uint64_t>(v);
}

void parse_size(const std::string& value, int& width, int& height) {
  const size_t x = value.find('x');
  if (x == std::string::npos) throw UsageError("--size " + value + ": expected WxH, e.g. 128x128");
  width = parse_int("--size width", value.substr(0, x), 1, kMaxImageSide);
  height = parse_int("--size height", value.substr(x + 1), 1, kMaxImageSide);
}

}  // namespace svgf::gbuffer::tool

#pragma once
// The subcommands of svgf-fixtures. Each returns the process exit status; bad input throws
// UsageError (exit 2), other failures std::exception (exit 1).
#include <stdexcept>
#include <string>
#include <vector>

namespace svgf::gbuffer::tool {

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

using Args = std::vector<std::string>;

int run_generate(const Args& args);
int run_verify(const Args& args);
int run_list(const Args& args);

// Default fixture folder: <source tree>/fixtures (SVGF_FIXTURES_DIR at build time).
std::string default_fixture_dir();

// Argument helpers.
int parse_int(const std::string& option, const std::string& value, int lo, int hi);
uint64_t parse_u64(const std::string& option, const std::string& value);
void parse_size(const std::string& value, int& width, int& height);
// The value after args[i] (advancing i); UsageError when there is none.
const std::string& value_of(const Args& args, size_t& i);

// Set by SIGINT/SIGTERM: the renderer stops at the next row and nothing is committed.
bool interrupted();
void install_interrupt_handler();

}  // namespace svgf::gbuffer::tool

#pragma once
// The subcommands of svgf-fixtures. Each adds itself to the tool's command line and sets
// `status` to the exit status when it has run; bad input throws UsageError (exit 2), other
// failures std::exception (exit 1).
#include <string>

#include "cli/usage_error.h"

namespace svgf::gbuffer::tool {

using cli::UsageError;

void add_generate(CLI::App& tool, int& status);
void add_verify(CLI::App& tool, int& status);
void add_list(CLI::App& tool, int& status);
void add_eval(CLI::App& tool, int& status);
void add_reference_noise(CLI::App& tool, int& status);

// Default fixture folder: <source tree>/fixtures (SVGF_FIXTURES_DIR at build time).
std::string default_fixture_dir();

// "WxH" (each side in 1..kMaxImageSide); UsageError naming --size.
void parse_size(const std::string& value, int& width, int& height);

// Set by SIGINT/SIGTERM: the renderer stops at the next row and nothing is committed.
bool interrupted();
void install_interrupt_handler();

}  // namespace svgf::gbuffer::tool

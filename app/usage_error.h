#pragma once
// The svgf subcommands' usage error (exit 2) is the tools' shared one. CLI11 itself only comes
// with cli/command_line.h, in the files that build a command line.
#include "cli/usage_error.h"

namespace svgf::app {
using cli::UsageError;
}  // namespace svgf::app

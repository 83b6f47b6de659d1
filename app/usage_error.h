#pragma once
// The svgf subcommands' usage error (exit 2) is the tools' shared one.
#include "cli/command_line.h"

namespace svgf::app {
using cli::UsageError;
}  // namespace svgf::app

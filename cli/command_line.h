#pragma once
// The tools' command lines (svgf, svgf-fixtures, svgf-bench) on CLI11: one way to parse, to
// print --help and to report a bad argument (named, with its range; exit 2) for all three.
#include <CLI/CLI.hpp>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli/usage_error.h"

namespace svgf::cli {

// An App with the project's help layout. `name` is what the user types ("svgf denoise").
void style(CLI::App& app);

// Parses `args` (without the program name) into `app`. Returns false when --help was asked for
// (the help of the subcommand named, on stdout); a bad argument is a UsageError naming it.
bool parse(CLI::App& app, const std::vector<std::string>& args);

// A flag taking on or off.
CLI::Option* add_on_off(CLI::App& app, const std::string& name, bool& value,
                        const std::string& help);
// Rejects NaN (inf passes: ranges say whether it may).
extern const CLI::Validator NotNaN;
// A validator passing what `parse` accepts (it throws std::invalid_argument otherwise); the
// message is the exception's from "must" on, if it says "must", after the flag's name.
template <class Parse>
CLI::Validator accepted_by(Parse parse) {
  return CLI::Validator(
      [parse](std::string& s) {
        try {
          parse(s);
          return std::string();
        } catch (const std::invalid_argument& e) {
          const std::string what = e.what();
          const size_t must = what.find("must");
          return must == std::string::npos ? what : what.substr(must);
        }
      },
      "");
}
// A finite number > 0.
extern const CLI::Validator PositiveFinite;

// Adds a subcommand to `tool` that sets `status` when it has run; returns it.
using AddSubcommand = CLI::App* (*)(CLI::App& tool, int& status);
// Runs one subcommand on its own, as `tool NAME args...` would (for tests and callers): the
// status it set, 0 after --help; a bad argument throws UsageError.
int run_subcommand(const std::string& tool, AddSubcommand add, const std::vector<std::string>& args);

// A tool's main(): parses argv into `app` (`tool help` is `tool --help`), then returns `run()`
// (the status the parsed subcommand set). A UsageError prints "tool: what" and where help is, exit 2; any other
// exception "tool: error: what", exit 1.
int run_main(CLI::App& app, int argc, char** argv, const std::function<int()>& run);

}  // namespace svgf::cli

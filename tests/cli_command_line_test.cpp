// The tools' shared command line (cli/command_line.h): what a bad argument says, --help, and the
// exit status run_main maps each outcome to.
#include <stdexcept>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "cli/command_line.h"

namespace cli = svgf::cli;

namespace {

// A tool with one subcommand `go --level N --mode on|off --scale X` that sets status to level.
struct Tool {
  CLI::App app{"a tool", "tool"};
  int status = 0, level = 1;
  bool mode = false;
  double scale = 1;
  Tool() {
    cli::style(app);
    app.require_subcommand(1);
    CLI::App* go = app.add_subcommand("go", "go");
    go->add_option("--level", level, "level")->check(CLI::Range(0, 5));
    cli::add_on_off(*go, "--mode", mode, "mode");
    go->add_option("--scale", scale, "scale")->check(cli::PositiveFinite);
    go->callback([this] {
      if (level == 4) throw std::runtime_error("level 4 fails");
      if (level == 5) throw cli::UsageError("level 5 is a usage error");
      status = level;
    });
  }
  int main(std::vector<std::string> args) {
    args.insert(args.begin(), "tool");
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    return cli::run_main(app, static_cast<int>(argv.size()), argv.data(), [this] { return status; });
  }
};

std::string usage_error(std::vector<std::string> args) {
  Tool t;
  try {
    cli::parse(t.app, args);
  } catch (const cli::UsageError& e) {
    return e.what();
  }
  return "accepted";
}

}  // namespace

TEST_CASE("cli: a bad value is a usage error naming its flag and range", "[cli]") {
  CHECK(usage_error({"go", "--level", "9"}) == "--level: Value 9 not in range 0 to 5");
  CHECK(usage_error({"go", "--level", "x"}) == "--level: Value x not in range 0 to 5");
  CHECK(usage_error({"go", "--mode", "yes"}) == "--mode: must be on or off, got 'yes'");
  CHECK(usage_error({"go", "--scale", "0"}) == "--scale: must be a finite number > 0, got '0'");
  CHECK(usage_error({"go", "--scale", "inf"}) ==
        "--scale: must be a finite number > 0, got 'inf'");
  CHECK(usage_error({"go", "--nope"}) == "The following argument was not expected: --nope");
  CHECK(usage_error({"go", "--level"}) == "--level: 1 required INT:INT in [0 - 5] missing");
  CHECK(usage_error({}) == "A subcommand is required");
  CHECK(usage_error({"go", "--level=3", "--mode", "on", "--scale", "0.5"}) == "accepted");
}

TEST_CASE("cli: on|off and --help", "[cli]") {
  Tool t;
  REQUIRE(cli::parse(t.app, {"go", "--mode", "on"}));
  CHECK(t.mode);
  Tool off;
  off.mode = true;
  REQUIRE(cli::parse(off.app, {"go", "--mode", "off"}));
  CHECK_FALSE(off.mode);
  Tool help;
  CHECK_FALSE(cli::parse(help.app, {"go", "--help"}));  // printed; nothing ran
  CHECK(help.status == 0);
}

TEST_CASE("cli: run_main exits 2 for a usage error, 1 for a failure, else the status",
          "[cli]") {
  CHECK(Tool().main({"go", "--level", "3"}) == 3);
  CHECK(Tool().main({"go", "--level", "7"}) == 2);
  CHECK(Tool().main({"go", "--level", "5"}) == 2);
  CHECK(Tool().main({"go", "--level", "4"}) == 1);
  CHECK(Tool().main({"stop"}) == 2);  // "unknown command 'stop' (go)"
  CHECK(Tool().main({"--help"}) == 0);
  CHECK(Tool().main({"help"}) == 0);
}

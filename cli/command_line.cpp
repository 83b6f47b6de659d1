#include "cli/command_line.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "io/printable.h"

namespace svgf::cli {

void style(CLI::App& app) {
  app.get_formatter()->column_width(30);
  app.get_formatter()->label("REQUIRED", "");
  app.option_defaults()->always_capture_default(false);
}

bool parse(CLI::App& app, const std::vector<std::string>& args) {
  std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI11 pops from the back
  try {
    app.parse(reversed);
    return true;
  } catch (const CLI::CallForHelp&) {
    std::fputs(app.help().c_str(), stdout);  // the selected subcommand's help
    return false;
  } catch (const CLI::CallForAllHelp&) {
    std::fputs(app.help("", CLI::AppFormatMode::All).c_str(), stdout);
    return false;
  } catch (const CLI::ParseError& e) {
    throw UsageError(e.what());
  }
}

CLI::Option* add_on_off(CLI::App& app, const std::string& name, bool& value,
                        const std::string& help) {
  const CLI::Validator on_off(
      [](std::string& s) { return s == "on" || s == "off" ? "" : "must be on or off, got '" + s + "'"; },
      "");
  return app.add_option(name, value, help)->type_name("on|off")->check(on_off);
}

const CLI::Validator NotNaN(
    [](std::string& s) {
      double v = 0;
      return CLI::detail::lexical_cast(s, v) && std::isnan(v) ? "must be a number, got '" + s + "'"
                                                              : std::string();
    },
    "");

const CLI::Validator PositiveFinite(
    [](std::string& s) {
      double v = 0;
      return CLI::detail::lexical_cast(s, v) && v > 0 && std::isfinite(v)
                 ? std::string()
                 : "must be a finite number > 0, got '" + s + "'";
    },
    "");

int run_subcommand(const std::string& tool, AddSubcommand add, const std::vector<std::string>& args) {
  CLI::App app("", tool);
  style(app);
  int status = 0;
  std::vector<std::string> all = {add(app, status)->get_name()};
  all.insert(all.end(), args.begin(), args.end());
  return parse(app, all) ? status : 0;
}

int run_main(CLI::App& app, int argc, char** argv, const std::function<int()>& run) {
  const std::string tool = app.get_name();
  std::vector<std::string> args(argv + 1, argv + argc);
  if (!args.empty() && args[0] == "help") args[0] = "--help";  // `tool help`
  try {
    if (!parse(app, args)) return 0;
    return run();
  } catch (const UsageError& e) {
    const std::vector<CLI::App*> chosen = app.get_subcommands();
    std::string what = e.what();
    if (chosen.empty() && !args.empty() && args[0][0] != '-') {  // CLI11: "A subcommand is required"
      std::string names;
      for (const CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; }))
        names += (names.empty() ? "" : ", ") + sub->get_name();
      what = "unknown command '" + args[0] + "' (" + names + ")";
    }
    const std::string help = tool + (chosen.empty() ? "" : " " + chosen[0]->get_name()) + " --help";
    std::fprintf(stderr, "%s: %s\n(%s lists the options)\n", tool.c_str(),
                 io::printable(what).c_str(), help.c_str());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: error: %s\n", tool.c_str(), io::printable(e.what()).c_str());
    return 1;
  }
}

}  // namespace svgf::cli

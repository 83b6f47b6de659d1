#pragma once
// Minimal command-line parsing: positional arguments and --name value / --flag options.
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace svgf::app {

class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Options {
 public:
  // `valued` options take a value, `flags` do not; anything else starting with -- is an error.
  Options(const std::vector<std::string>& args, const std::set<std::string>& valued,
          const std::set<std::string>& flags);
  const std::vector<std::string>& positional() const { return positional_; }
  bool has(const std::string& name) const { return values_.count(name) != 0; }
  std::string get(const std::string& name, const std::string& fallback) const;
  int get_int(const std::string& name, int fallback, int lo, int hi) const;
  float get_float(const std::string& name, float fallback) const;
  bool get_on_off(const std::string& name, bool fallback) const;  // the value "on" or "off"

 private:
  std::vector<std::string> positional_;
  std::map<std::string, std::string> values_;
};

}  // namespace svgf::app

#pragma once
// The method parameter flags, shared by `svgf denoise` and `svgf-bench` so that a flag means
// the same in both (docs/benchmarks.md).
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "app/usage_error.h"
#include "pipeline/make_denoiser.h"

namespace svgf::app {

class MethodParamFlags {
 public:
  // Adds the flags to `app` in the group "method parameters", each with its range (a CLI11
  // validator) and help naming the methods that read it and the default. `*this` must outlive
  // the parse and not move.
  void add_to(CLI::App& app);
  // UsageError for a flag given that `method` does not read (a name that is no project method,
  // e.g. an OpenCV baseline, reads none): a run must not be labelled with a setting it ignored.
  void check_apply(const std::string& method) const;
  // Sets every method's parameters in `c` (c.method chosen): --svgf-preset first, then the flags
  // given, in any order; then validates them (params.h: the rules across fields); a bad value is
  // a UsageError naming its flag.
  void read(DenoiserConfig& c) const;

 private:
  std::string preset_;
  std::vector<std::pair<CLI::Option*, std::vector<std::string>>> readers_;
  std::vector<std::function<void(DenoiserConfig&)>> given_;  // the flags given, each setting its field
};

}  // namespace svgf::app

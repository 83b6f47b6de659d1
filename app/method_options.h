#pragma once
// The method parameter flags, shared by `svgf denoise` and `svgf-bench` so that a flag means
// the same in both (docs/benchmarks.md).
#include <set>
#include <string>

#include "app/options.h"
#include "pipeline/make_denoiser.h"

namespace svgf::app {

// The flags' usage lines (each "  --flag ARG  which method: what (default)").
extern const char* const kMethodParamUsage;
// The flags, each taking a value.
const std::set<std::string>& method_param_flags();
// Reads every method's parameters into `c` and validates them; a bad value is a UsageError
// naming its flag.
void read_method_params(const Options& o, DenoiserConfig& c);
// UsageError for a parameter flag given that `method` does not read (a name that is no project
// method, e.g. an OpenCV baseline, reads none): a benchmark must not label a run with a setting
// it ignored.
void check_params_apply(const Options& o, const std::string& method);

}  // namespace svgf::app

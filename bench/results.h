#pragma once
// The suite results (cpu.json, gpu.json from `svgf-bench suite`) as the chart tables, the
// summary and the targets read them: loaded and checked once, then looked up by suite, section
// and configuration key.
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace svgf::bench {

using json = nlohmann::json;

// Keys of the default configurations (SvgfParams' iterations and feedback tap, pinned by
// tests/bench_methods_test.cpp), which the per-scene curves and tables single out.
inline const char* const kDefaultCpu = "svgf cpu exact it4 tap-1";
inline const char* const kDefaultExact = "svgf cuda exact it4 tap-1";
inline const char* const kDefaultFast = "svgf cuda fast it4 tap-1";
inline const char* const kWaveletCpu = "wavelet cpu exact it4 k5";
inline const char* const kWaveletFast = "wavelet cuda fast it4 k5";
inline const char* const kJbfCpu = "jbf cpu exact r16";
inline const char* const kJbfAtrousCpu = "jbf-atrous cpu exact l4";
inline const char* const kBmfrCpu = "bmfr cpu exact noise";
inline const char* const kBmfrSkipCpu = "bmfr cpu exact skip";
inline const char* const kBmfrFast = "bmfr cuda fast noise";

struct Results {
  std::map<std::string, json> suites;  // by suite name ("cpu", "gpu")
  // `svgf-bench quality`'s file (the evaluation set), when given: its quality replaces the
  // suites' (the fixtures'); null otherwise.
  json eval_quality;

  const json* suite(const std::string& name) const;
  // A section's timing entries, without those that failed, in file order.
  std::vector<const json*> timings(const std::string& suite, const std::string& section) const;
  // Per-scene quality entries of configuration `key`: from eval_quality when loaded, else each
  // scene from the first suite (gpu, then cpu) that has it.
  std::map<std::string, json> quality(const std::string& key) const;
};

// Every suite JSON in `dir` (files without a "suite" member are not suite results and are
// skipped). Entries of OpenCV baselines from before their "cv-" names are read with them. A file that does not parse, or an entry without a field the writers read, is an
// error naming the file.
Results load_results(const std::string& dir);
// Loads `svgf-bench quality`'s file into r.eval_quality (errors name the file).
void load_eval_quality(Results& r, const std::string& file);

// One timing entry.
std::string size_of(const json& e);  // "1920x1080"
double mpix(const json& e);          // megapixels
double median_ms(const json& e);     // filter stages, median per frame
double p95_ms(const json& e);
// A JSON value as a number, NaN when it is none (a missing metric).
double num(const json& v);

}  // namespace svgf::bench

// bench/targets.json judged by the generic evaluator on made-up suite results: ratios across
// sections and methods (row by row), a metric read from a named stage, and the file itself
// (it loads, and a malformed row is an error naming the target).
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "bench/chart_data.h"
#include "bench/targets.h"

using namespace svgf::bench;
namespace fs = std::filesystem;

namespace {

// A timing entry with what the targets read: its frame time and, optionally, its stages.
json entry(const std::string& section, const std::string& key, json config, int width, int height,
           double frame_ms, json stages = json::array()) {
  return {{"group", section},
          {"key", key},
          {"label", key},
          {"input", {{"width", width}, {"height", height}, {"scene", "cornell-moving"}}},
          {"config", std::move(config)},
          {"frame_ms", {{"filter", {{"median", frame_ms}, {"p95", frame_ms}}}}},
          {"stages", std::move(stages)}};
}

json stage(const std::string& name, double ms, json extra = json::object()) {
  json s = {{"stage", name}, {"ms", {{"median", ms}}}};
  s.update(extra);
  return s;
}

// The verdicts of target `id`, by row label (the description's parenthesis).
std::vector<TargetResult> results_of(const std::vector<TargetResult>& all, const std::string& id) {
  std::vector<TargetResult> v;
  for (const TargetResult& t : all)
    if (t.id == id) v.push_back(t);
  return v;
}

const TargetResult& row(const std::vector<TargetResult>& rows, const std::string& label) {
  for (const TargetResult& t : rows)
    if (t.target.find("(" + label + ")") != std::string::npos) return t;
  FAIL("no row " << label);
  static const TargetResult none;
  return none;
}

}  // namespace

TEST_CASE("issue 10's targets: JBF a-trous against SVGF's iterations, stage ratios, cost a tap",
          "[bench][targets]") {
  const json targets = load_targets(default_targets_path());
  json gpu = {{"suite", "gpu"}, {"timings", json::array()}};
  json& g = gpu["timings"];
  for (const std::string mode : {"exact", "fast"})
    for (int n = 1; n <= 4; ++n) {
      // SVGF at n iterations takes n ms; the JBF a-trous n - 0.5 ms, except exact at 3 levels.
      const double jbf_ms = mode == "exact" && n == 3 ? 3.5 : n - 0.5;
      g.push_back(entry("iterations", "svgf cuda " + mode + " it" + std::to_string(n),
                        {{"method", "svgf"}, {"mode", mode}, {"iterations", n}}, 1920, 1080, n));
      g.push_back(entry("jbf", "jbf-atrous cuda " + mode + " l" + std::to_string(n),
                        {{"method", "jbf-atrous"}, {"mode", mode}, {"levels", n}}, 1920, 1080,
                        jbf_ms));
    }
  // The chart size's a-trous entry must not be taken for the 1080p one.
  g.push_back(entry("jbf", "jbf-atrous cuda fast l4", {{"method", "jbf-atrous"}, {"mode", "fast"},
                                                        {"levels", 4}},
                    1280, 720, 100));
  for (const std::string mode : {"exact", "fast"})
    g.push_back(entry("jbf", "jbf cuda " + mode + " r16",
                      {{"method", "jbf"}, {"mode", mode}, {"levels", 0}}, 1920, 1080, 20,
                      {stage("sanitize", 0.1),
                       stage("filter", 19.8,
                             {{"pct_of_ops", mode == "exact" ? 61.0 : 42.0},
                              {"per_tap", {{"ns", 0.015}, {"ops", 96}}},
                              {"pct_of_copy_bw", 0.5},
                              {"floor", {{"ratio", 1.6}}}})}));
  json cpu = {{"suite", "cpu"}, {"timings", json::array()}};
  json& c = cpu["timings"];
  c.push_back(entry("chart", "svgf cpu exact it4 tap1", {{"method", "svgf"}, {"mode", "exact"}},
                    1280, 720, 90, {stage("reproject", 12), stage("atrous", 60)}));
  c.push_back(entry("jbf", "jbf-atrous cpu exact l4", {{"method", "jbf-atrous"}, {"mode", "exact"}},
                    1280, 720, 200, {stage("atrous", 190)}));
  c.push_back(entry("wavelet", "wavelet cpu exact it4 k5", {{"method", "wavelet"}, {"mode", "exact"}},
                    1280, 720, 75, {stage("atrous", 70)}));
  Results r;
  r.suites["gpu"] = gpu;
  r.suites["cpu"] = cpu;
  const std::vector<TargetResult> all = evaluate_targets(targets, r);

  const auto levels = results_of(all, "gpu-1080p-jbf-atrous-vs-svgf-iterations");
  REQUIRE(levels.size() == 8);
  CHECK(row(levels, "exact, N = 1").measured.value == Approx(0.5));
  CHECK(row(levels, "exact, N = 1").verdict == Verdict::Met);
  CHECK(row(levels, "exact, N = 3").measured.value == Approx(3.5 / 3));
  CHECK(row(levels, "exact, N = 3").verdict == Verdict::Missed);
  CHECK(row(levels, "fast, N = 4").measured.value == Approx(3.5 / 4));
  CHECK(row(levels, "fast, N = 4").verdict == Verdict::Met);

  // The a-trous stage of entries in other sections over SVGF's, not their frame times.
  const auto stages = results_of(all, "cpu-720p-atrous-stage-vs-svgf");
  REQUIRE(stages.size() == 2);
  CHECK(row(stages, "jbf-atrous, 4 levels").measured.value == Approx(190.0 / 60));
  CHECK(row(stages, "jbf-atrous, 4 levels").verdict == Verdict::Missed);
  CHECK(row(stages, "wavelet 5x5, 4 passes").measured.value == Approx(70.0 / 60));
  CHECK(row(stages, "wavelet 5x5, 4 passes").verdict == Verdict::Met);

  const auto rate = results_of(all, "gpu-1080p-jbf-full-window-float-rate");
  REQUIRE(rate.size() == 2);
  CHECK(row(rate, "exact").measured.value == 61.0);
  CHECK(row(rate, "exact").verdict == Verdict::Met);
  CHECK(row(rate, "fast").verdict == Verdict::Missed);
  REQUIRE(row(rate, "fast").context.size() == 5);
  CHECK(row(rate, "fast").context[1].value == 0.015);  // ns a tap, from the filter stage

  // Without the entries the rows are not measured, not met.
  const std::vector<TargetResult> none = evaluate_targets(targets, Results{});
  for (const TargetResult& t : results_of(none, "gpu-1080p-jbf-atrous-vs-svgf-iterations"))
    CHECK(t.verdict == Verdict::NotMeasured);
}

TEST_CASE("issue 11's targets: BMFR fast at 1080p, exact against its floor, the CPU against SVGF",
          "[bench][targets][bmfr]") {
  const json targets = load_targets(default_targets_path());
  auto on = [](json e, const std::string& scene) {
    e["input"]["scene"] = scene;
    return e;
  };
  json gpu = {{"suite", "gpu"}, {"timings", json::array()}};
  json& g = gpu["timings"];
  for (const std::string mode : {"exact", "fast"}) {
    const std::string key = "bmfr cuda " + mode + " noise";
    const json config = {{"method", "bmfr"}, {"mode", mode}};
    // At the chart size on the default scene (not the targets'), and at 1080p on camera-pan.
    g.push_back(entry("bmfr", key, config, 1280, 720, 0.3));
    json e = on(entry("bmfr", key, config, 1920, 1080, mode == "fast" ? 0.78 : 0.79), "camera-pan");
    e["frame_ms"]["filter"]["p95"] = 0.8;
    e["floor"] = {{"floor_ms", 0.3}, {"ratio", mode == "fast" ? 2.6 : 2.63}, {"bytes_ms", 0.28},
                  {"ops_ms", 0.08}};
    g.push_back(e);
  }
  g.push_back(on(entry("bmfr", "bmfr cuda exact skip", {{"method", "bmfr"}, {"mode", "exact"}},
                       1920, 1080, 0.57),
                 "camera-pan"));
  json cpu = {{"suite", "cpu"}, {"timings", json::array()}};
  json& c = cpu["timings"];
  for (int threads : {2, 16}) {
    const json config = {{"method", "bmfr"}, {"mode", "exact"}, {"threads", threads}};
    c.push_back(on(entry("bmfr", "bmfr cpu exact noise", config, 1280, 720, 300.0 / (threads / 2)),
                   "camera-pan"));
  }
  c.push_back(on(entry("bmfr", "svgf cpu exact it4 tap1",
                       {{"method", "svgf"}, {"mode", "exact"}, {"threads", 2}}, 1280, 720, 250),
                 "camera-pan"));
  // The chart size's entry on the default scene must not be taken for camera-pan's.
  c.push_back(entry("bmfr", "bmfr cpu exact noise",
                    {{"method", "bmfr"}, {"mode", "exact"}, {"threads", 2}}, 1280, 720, 1000));
  Results r;
  r.suites["gpu"] = gpu;
  r.suites["cpu"] = cpu;
  const std::vector<TargetResult> all = evaluate_targets(targets, r);

  const auto fast = results_of(all, "gpu-fast-1080p-bmfr");
  REQUIRE(fast.size() == 1);
  CHECK(fast[0].measured.value == 0.78);
  CHECK(fast[0].verdict == Verdict::Met);
  REQUIRE(fast[0].context.size() == 3);
  CHECK(fast[0].context[0].value == 0.8);  // p95
  CHECK(fast[0].context[1].value == 0.3);  // floor

  const auto exact = results_of(all, "gpu-exact-1080p-bmfr-floor");
  REQUIRE(exact.size() == 1);
  CHECK(exact[0].measured.value == 2.63);
  CHECK(exact[0].verdict == Verdict::Missed);
  REQUIRE(exact[0].context.size() == 5);
  CHECK(exact[0].context[0].value == 0.79);

  const auto ratio = results_of(all, "cpu-720p-bmfr-vs-svgf");
  REQUIRE(ratio.size() == 1);
  CHECK(ratio[0].measured.value == Approx(300.0 / 250));
  CHECK(ratio[0].verdict == Verdict::Met);

  const std::vector<TargetResult> none = evaluate_targets(targets, Results{});
  for (const char* id :
       {"gpu-fast-1080p-bmfr", "gpu-exact-1080p-bmfr-floor", "cpu-720p-bmfr-vs-svgf"})
    for (const TargetResult& t : results_of(none, id)) CHECK(t.verdict == Verdict::NotMeasured);
}

TEST_CASE("a target's row ratio and stage are checked when the file loads", "[bench][targets]") {
  const fs::path file = fs::temp_directory_path() / "svgf_bench_targets_test.json";
  auto load_with = [&](const json& extra) {
    json t = {{"id", "t"},           {"description", "d"}, {"source", "s"},
              {"select", {{"suite", "gpu"}, {"section", "jbf"}}},
              {"metric", "/ms/median"}, {"comparator", "<="}, {"threshold", 1}};
    t.update(extra);
    std::ofstream(file) << json({{"targets", {t}}}).dump();
    return load_targets(file.string());
  };
  CHECK_NOTHROW(load_with({{"stage", "atrous"}}));
  CHECK_NOTHROW(load_with(
      {{"ratio", {{"numerator", json::object()}, {"denominator", {{"section", "chart"}}}}},
       {"rows", {{{"label", "a"}, {"ratio", {{"numerator", {{"levels", 2}}}}}}}}}));
  CHECK_THROWS_WITH(load_with({{"rows", {{{"label", "a"}, {"ratio", json::object()}}}}}),
                    Catch::Contains("target \"t\": row \"a\" has a ratio but the target has none"));
  CHECK_THROWS_WITH(
      load_with({{"ratio", {{"numerator", json::object()}, {"denominator", json::object()}}},
                 {"rows", {{{"label", "a"}, {"ratio", {{"numerator", {{"colour", 1}}}}}}}}}),
      Catch::Contains("unknown filter \"colour\""));
  CHECK_THROWS_WITH(load_with({{"rows", {{{"label", "a"}, {"selct", json::object()}}}}}),
                    Catch::Contains("unknown field \"selct\""));
  CHECK_THROWS_WITH(load_with({{"stage", 3}}), Catch::Contains("stage is not a name"));
  fs::remove(file);
}

TEST_CASE("issue 6's memory-bound stages: a stage counted inside another's launch is not judged",
          "[bench][targets]") {
  // CUDA runs SVGF's sanitize stage inside the demodulation's launch (bench/stage_cost.cpp): the
  // stage is listed with no cost, and bench/runner.cpp marks its floor bound by "none".
  const json targets = load_targets(default_targets_path());
  json gpu = {{"suite", "gpu"}, {"timings", json::array()}};
  auto floor = [](const char* bound) {
    return json{{"floor", {{"bound", bound}}}, {"host_link", false}};
  };
  for (const std::string mode : {"exact", "fast"}) {
    json sanitize = floor("none"), demodulate = floor("bytes"), atrous = floor("ops");
    sanitize["pct_of_copy_bw"] = 0.0;
    demodulate["pct_of_copy_bw"] = 76.0;
    atrous["pct_of_copy_bw"] = 40.0;
    gpu["timings"].push_back(entry(
        "sizes", "svgf cuda " + mode + " it4 tap1", {{"method", "svgf"}, {"mode", mode}}, 1920,
        1080, 0.7,
        {stage("sanitize", 0.0, sanitize), stage("demodulate", 0.12, demodulate),
         stage("atrous", 0.43, atrous), stage("upload", 3.0, {{"host_link", true}})}));
  }
  Results r;
  r.suites["gpu"] = gpu;
  const std::vector<TargetResult> all = evaluate_targets(targets, r);
  for (const char* id :
       {"gpu-fast-1080p-memory-bound-stages", "gpu-exact-1080p-memory-bound-stages"}) {
    INFO(id);
    const auto rows = results_of(all, id);
    REQUIRE(rows.size() == 1);
    CHECK_THAT(rows[0].target, Catch::Contains("(demodulate)"));
    CHECK(rows[0].measured.value == 76.0);
    CHECK(rows[0].verdict == Verdict::Met);
  }
}

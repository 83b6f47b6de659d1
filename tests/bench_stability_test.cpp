// svgf-bench stability (bench/stability.h) on a tiny configuration: every scenario's code path
// on the committed fixtures and on small renders, two methods, in seconds. What the reduced
// suite finds is checked where it is known: SVGF's defaults follow the light switch (issue 12's
// test says so too), and a method without history has nothing to lag after a disocclusion (its
// run and its restarted run are the same bits), so the measure reads exactly 0 there.
#include <catch2/catch.hpp>
#include <algorithm>
#include <string>
#include <vector>

#include "bench/stability.h"
#include "bench/stability_inputs.h"

using namespace svgf;
using namespace svgf::bench;

namespace {

StabilityOptions tiny() {
  StabilityOptions o;
  o.command = "svgf-bench stability (test)";
  o.fixtures_root = std::string(SVGF_SOURCE_DIR) + "/fixtures";
  o.threads = 2;
  o.quiet = true;
  o.methods = {"svgf", "gaussian"};
  o.sizes.shadow_width = 40;  // not square, as --full's 384x216
  o.sizes.shadow_height = 24;
  o.sizes.shadow_frames = 5;
  o.sizes.shadow_reference_spp = 2;
  o.sizes.static_size = 16;
  o.sizes.static_frames = 7;
  o.sizes.static_reference_spp = 2;
  return o;
}

const ScenarioResult& scenario(const std::vector<ScenarioResult>& rs, const std::string& name) {
  const auto it = std::find_if(rs.begin(), rs.end(),
                               [&](const ScenarioResult& r) { return r.name == name; });
  REQUIRE(it != rs.end());
  return *it;
}

const StabilityRow& row(const ScenarioResult& r, const std::string& method) {
  const auto it = std::find_if(r.rows.begin(), r.rows.end(),
                               [&](const StabilityRow& w) { return w.method == method; });
  REQUIRE(it != r.rows.end());
  return *it;
}

}  // namespace

TEST_CASE("stability: every scenario runs on a tiny configuration and reads as known",
          "[bench][stability]") {
  const StabilityOptions o = tiny();
  const std::vector<ScenarioResult> rs = run_stability(o);
  REQUIRE(rs.size() == stability_scenario_names().size());
  for (const ScenarioResult& r : rs) {
    INFO(r.name);
    if (!r.skipped.empty()) {
      CHECK(!stability_can_render());  // only the rendered scenarios may be skipped
      continue;
    }
    REQUIRE(r.rows.size() == 2);
    for (const StabilityRow& w : r.rows) {
      INFO(w.method << ": " << w.value);
      CHECK(w.verdict != Outcome::NotMeasured);
    }
  }
  const StabilityRow& svgf_light = row(scenario(rs, "light-switch"), "svgf");
  CHECK(svgf_light.verdict == Outcome::Pass);
  CHECK(svgf_light.data["lag"].get<int>() <= 2);

  const StabilityRow& gauss_trail = row(scenario(rs, "disocclusion"), "gaussian");
  CHECK(gauss_trail.data["worst_lag"].get<int>() == 0);
  CHECK(gauss_trail.data["excess_at_uncovering_db"].get<double>() == 0.0);
  // A method without history is back the frame after the firefly.
  CHECK(row(scenario(rs, "fireflies"), "gaussian").data["frames"].get<int>() == 1);

  // Each failed row of the suite's own methods keeps that method's output at the frame the
  // page shows, with the input and reference of that frame; a passed row keeps nothing.
  for (const ScenarioResult& r : rs) {
    INFO(r.name);
    std::vector<std::string> failed;
    for (const StabilityRow& w : r.rows)
      if (w.verdict == Outcome::Fail) failed.push_back(w.method);
    REQUIRE(r.shown_failures.size() == failed.size());
    for (size_t i = 0; i < failed.size(); ++i) {
      CHECK(r.shown_failures[i].first == failed[i]);
      CHECK(r.shown_failures[i].second.width() == r.shown_reference.width());
    }
    if (!failed.empty()) {
      CHECK(r.shown_frame >= 0);
      CHECK(r.shown_input.width() > 0);
    }
  }
  const ScenarioResult& fireflies = scenario(rs, "fireflies");
  CHECK(fireflies.shown_frame == 6);  // the frame with the outlier
  // The Gaussian spreads the outlier over its 6 px footprint (docs/stability.md): shown.
  REQUIRE(row(fireflies, "gaussian").verdict == Outcome::Fail);
  CHECK(std::any_of(fireflies.shown_failures.begin(), fireflies.shown_failures.end(),
                    [](const auto& f) { return f.first == "gaussian"; }));

  const std::string page = stability_page(o, rs);
  for (const ScenarioResult& r : rs) {
    CHECK(page.find("(`" + r.name + "`)") != std::string::npos);
    const bool linked = page.find("(stability/" + r.name + ".png)") != std::string::npos;
    CHECK(linked == !r.shown_failures.empty());
  }
  CHECK(page.find("| svgf | ") != std::string::npos);
  CHECK(page.find(o.command) != std::string::npos);
  const nlohmann::json j = stability_json(o, rs);
  CHECK(j["scenarios"].size() == rs.size());
}

TEST_CASE("stability: unknown names and unwritable outputs are refused before a run",
          "[bench][stability]") {
  StabilityOptions o = tiny();
  o.methods = {"svgf", "nope"};
  CHECK_THROWS_WITH(check_stability_options(o), Catch::Contains("unknown method 'nope'"));
  o = tiny();
  o.scenarios = {"flicker", "wobble"};
  CHECK_THROWS_WITH(run_stability(o), Catch::Contains("unknown scenario 'wobble'"));
  o = tiny();
  o.out_md = "/nonexistent-folder/stability.md";
  CHECK_THROWS_WITH(check_stability_options(o), Catch::Contains("no folder"));
}

// `svgf-bench quality` on a tiny evaluation set rendered here, read back by chart-data's results
// model (bench/eval_quality.h, bench/results.h).
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "bench/chart_points.h"
#include "bench/eval_quality.h"
#include "bench/results.h"
#include "bench/suites.h"
#include "gbuffer/eval_set.h"

namespace fs = std::filesystem;
using namespace svgf::bench;
using nlohmann::json;

namespace {

void render_tiny(const fs::path& root, const std::string& scene) {
  svgf::gbuffer::EvalParams p;
  p.width = 24;
  p.height = 16;
  p.frames = 3;
  p.reference_spp = 32;  // cornell-moving's halves then stay under PSNR's clamp: corrected
  const svgf::gbuffer::Renderer renderer;
  const auto seq = svgf::gbuffer::eval_sequence(root.string(), scene, p);
  svgf::gbuffer::render_eval_sequence(renderer, seq, p, svgf::gbuffer::plan_eval_sequence(seq, p));
}

}  // namespace

TEST_CASE("quality on the evaluation set: every chart configuration, clean means",
          "[bench][eval]") {
  const fs::path root = fs::temp_directory_path() / "svgf_bench_eval_quality_test";
  fs::remove_all(root);
  render_tiny(root, "cornell-moving");
  render_tiny(root, "camera-pan");
  fs::create_directories(root / "unfinished");  // no manifest: skipped
  EvalQualityOptions o;
  o.set_dir = root.string();
  o.out_file = (root / "out" / "q.json").string();
  o.threads = 2;
  o.command = "test";
  REQUIRE(run_eval_quality(o) == 0);
  std::ifstream in(o.out_file);
  const json doc = json::parse(in);
  CHECK(doc["set"]["scenes"].size() == 2);
  CHECK(doc["set"]["scenes"][0]["reference_spp"] == 32);
  CHECK(doc["means"].size() == quality_configs(2).size());
  // camera-pan is a bright room: much of its reference noise estimate is at the clamp.
  REQUIRE(doc["left_out_scenes"].size() == 1);
  CHECK(doc["left_out_scenes"][0]["scene"] == "camera-pan");
  CHECK_THAT(doc["left_out_scenes"][0]["why"].get<std::string>(), Catch::Contains("clamp"));
  REQUIRE(doc["clean_scenes"].size() == 1);
  CHECK(doc["clean_scenes"][0]["reference_noise_db"].get<double>() > 0);
  for (const json& m : doc["means"]) {
    CHECK(m["all"]["scenes"] == 2);
    CHECK(m["clean"]["scenes"] == 1);
  }
  // The clean scene's PSNR has the reference noise taken out, frame by frame: the MSE against
  // the reference minus the noise in eval.json; camera-pan's has none.
  const json record = json::parse(std::ifstream(root / "cornell-moving" / "eval.json"));
  int corrected = 0;
  for (const json& e : doc["quality"]) {
    REQUIRE(e["frames"].size() == 3);
    if (e["scene"] == "camera-pan") {
      CHECK_FALSE(e["mean"].contains("psnr_corrected"));
      continue;
    }
    for (int k = 0; k < 3; ++k) {
      const json& f = e["frames"][k];
      const double noise = record["reference_noise_mse"][k].get<double>();
      const double mse = std::pow(10.0, -f["psnr"].get<double>() / 10.0);
      if (mse <= noise) continue;  // undefined: null
      CHECK(f["psnr_corrected"].get<double>() ==
            Approx(-10.0 * std::log10(mse - noise)).epsilon(1e-12));
      CHECK(f["psnr_corrected"].get<double>() > f["psnr"].get<double>());
      ++corrected;
    }
  }
  CHECK(corrected > 30);

  // chart-data reads it in place of the suites' quality; the chart leaves camera-pan out.
  Results r;
  load_eval_quality(r, o.out_file);
  CHECK(r.quality(kDefaultCpu).size() == 2);
  const json& clean = doc["means"][1];  // the first SVGF configuration
  const std::string key = clean["key"];
  // The chart takes the corrected PSNR of a clean scene (the clean mean over one scene is it).
  const json chart_entry = r.quality(key).at("cornell-moving");
  CHECK(chart_entry["mean"]["psnr"] == clean["clean"]["psnr"]);
  CHECK(chart_entry["mean"]["psnr_measured"] == clean["clean"]["psnr_measured"]);
  CHECK(chart_entry["mean"]["psnr"].get<double>() >
        chart_entry["mean"]["psnr_measured"].get<double>());
  for (const json& e : doc["quality"])  // camera-pan's is the measured one
    if (e["key"] == key && e["scene"] == "camera-pan")
      CHECK(r.quality(key).at("camera-pan")["mean"]["psnr"] == e["mean"]["psnr"]);

  // A frame that no longer matches its manifest's SHA-256 is an error naming it.
  { std::ofstream(root / "camera-pan" / "frame_0001.exr", std::ios::app) << "x"; }
  CHECK_THROWS_WITH(run_eval_quality(o), Catch::Contains("frame_0001"));
  fs::remove_all(root);
}

// svgf info and svgf compare: what a sequence holds, and how two sets of frames differ.
#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "app/compare_command.h"
#include "app/denoise_command.h"
#include "app/info_command.h"
#include "app/usage_error.h"
#include "io/exr_frame.h"
#include "io/sequence.h"
#include "app_test_support.h"
#include "synthetic_sequence.h"
#include "test_support.h"

namespace fs = std::filesystem;
using namespace svgf;

TEST_CASE("svgf info: ranges, non-finite counts per frame and channel, hash mismatches",
          "[app][info]") {
  const fs::path dir = test::scratch("info_in"), json_path = test::scratch("info") / "info.json";
  fs::create_directories(json_path.parent_path());
  const test::SyntheticScene scene;
  Frame planted = scene.frame(1);
  planted.color.at(5, 7, 1) = std::numeric_limits<float>::quiet_NaN();
  planted.motion.at(3, 2, 0) = std::numeric_limits<float>::infinity();
  {
    io::SequenceWriter w(dir.string(), io::FrameStorage{});
    w.add(scene.frame(0));
    w.add(planted);
    w.add(scene.frame(2));
    io::Manifest m;
    m.scene = "synthetic";
    m.generator = "app_info_compare_test";
    w.commit(m);
  }
  // A clean sequence: exit 0, and the ranges are the frames' own.
  REQUIRE(app::info_command({dir.string(), "--json", json_path.string()}) == 0);
  auto report = test::read_json(json_path);
  REQUIRE(report["frames"] == 3);
  REQUIRE(report["ok"] == true);
  REQUIRE(report["channels"]["color"]["non_finite"] == 1);
  REQUIRE(report["channels"]["motion"]["non_finite"] == 1);
  REQUIRE(report["channels"]["albedo"]["non_finite"] == 0);
  REQUIRE(report["per_frame"][1]["non_finite"]["color"] == 1);
  REQUIRE_FALSE(report["per_frame"][0].contains("non_finite"));
  double lo = 1e30, hi = -1e30, surface = 0;
  for (int k = 0; k < 3; ++k) {
    const Frame f = k == 1 ? planted : scene.frame(k);
    for (float v : f.depth.data()) {
      lo = std::min(lo, double(v));
      hi = std::max(hi, double(v));
      surface += v > 0.f;
    }
  }
  REQUIRE(report["channels"]["depth"]["min"].get<double>() == lo);
  REQUIRE(report["channels"]["depth"]["max"].get<double>() == hi);
  REQUIRE(report["surface_fraction"].get<double>() ==
          Approx(surface / (3.0 * planted.depth.pixel_count())));
  REQUIRE_FALSE(report["channels"].contains("emission"));  // absent channels are not listed

  // Frame 2 replaced behind the manifest's back: its SHA-256 no longer matches; exit 1 naming it.
  io::write_frame((dir / io::frame_file_name(2)).string(), scene.frame(5));
  REQUIRE(app::info_command({dir.string(), "--json", json_path.string()}) == 1);
  report = test::read_json(json_path);
  REQUIRE(report["ok"] == false);
  REQUIRE(report["per_frame"][2]["sha256_ok"] == false);
  REQUIRE(report["per_frame"][0]["sha256_ok"] == true);
  bool named = false;
  for (const auto& p : report["problems"])
    named = named || p.get<std::string>().find(io::frame_file_name(2)) != std::string::npos;
  REQUIRE(named);

  REQUIRE_THROWS_AS(app::info_command({}), app::UsageError);
  REQUIRE_THROWS(app::info_command({(dir / "missing").string()}));  // no manifest: named error
  fs::remove_all(dir);
  fs::remove_all(json_path.parent_path());
}

TEST_CASE("svgf compare: the metrics svgf denoise reports, per frame and mean; diff maps",
          "[app][compare]") {
  const fs::path in = test::write_synthetic(test::scratch("cmp_in"), 3),
                 out = test::scratch("cmp_out"), work = test::scratch("cmp_work");
  fs::create_directories(work);
  REQUIRE(app::denoise_command({in.string(), out.string(), "--backend", "cpu", "--method",
                                "gaussian", "--no-preview"}) == 0);
  const auto denoised = test::read_json(out / "report.json");
  const fs::path json_path = work / "cmp.json", diff = work / "diff";
  REQUIRE(app::compare_command({out.string(), in.string(), "--json", json_path.string(),
                                "--diff", diff.string()}) == 0);
  const auto cmp = test::read_json(json_path);
  REQUIRE(cmp["frames"].size() == 3);
  double mean = 0;
  for (int k = 0; k < 3; ++k) {
    // The sequence as B: each frame's reference, as svgf denoise measured it.
    REQUIRE(cmp["frames"][k]["file"] == io::frame_file_name(k));
    REQUIRE(cmp["frames"][k]["psnr_db"].get<double>() ==
            Approx(denoised["frames"][k]["psnr_denoised_db"].get<double>()).epsilon(1e-12));
    REQUIRE(cmp["frames"][k]["relmse"].get<double>() ==
            Approx(denoised["frames"][k]["relmse_denoised"].get<double>()).epsilon(1e-12));
    REQUIRE(cmp["frames"][k]["flip"].get<double>() > 0);
    REQUIRE(fs::file_size(diff / ("frame_000" + std::to_string(k) + "_flip.png")) > 100);
    mean += cmp["frames"][k]["psnr_db"].get<double>() / 3;
  }
  REQUIRE(cmp["mean"]["psnr_db"].get<double>() == Approx(mean));
  // Against itself: identical (no PSNR), SSIM 1, FLIP 0.
  REQUIRE(app::compare_command({out.string(), out.string(), "--json", json_path.string()}) == 0);
  const auto same = test::read_json(json_path);
  REQUIRE(same["frames"][1]["identical"] == true);
  REQUIRE(same["frames"][1]["psnr_db"].is_null());
  REQUIRE(same["frames"][1]["ssim"].get<double>() == Approx(1.0));
  REQUIRE(same["frames"][1]["flip"].get<double>() == 0.0);
  // A file against a file of another size: an error naming both.
  Image small(8, 8, 3, 0.5f);
  io::write_rgb_exr((work / "small.exr").string(), small);
  REQUIRE_THROWS_WITH(app::compare_command({(out / io::frame_file_name(0)).string(),
                                            (work / "small.exr").string()}),
                      Catch::Contains("small.exr") && Catch::Contains("8x8"));
  REQUIRE_THROWS_AS(app::compare_command({out.string()}), app::UsageError);
  fs::remove_all(in);
  fs::remove_all(work);
  test::remove_output(out);
}

TEST_CASE("silent traps are warned of: no surface, constant albedo, a moving camera without motion",
          "[app][info]") {
  const test::SyntheticScene scene;
  std::vector<Frame> frames = {scene.frame(0), scene.frame(1), scene.frame(2), scene.frame(3)};
  for (float& d : frames[1].depth.data()) d = 0.f;  // "unknown depth filled with 0"
  for (float& a : frames[2].albedo.data()) a = 1.f;  // "no albedo buffer"
  frames[3].camera.world_to_view[3] = frames[2].camera.world_to_view[3] + 0.5f;
  for (float& m : frames[3].motion.data()) m = 0.f;
  const fs::path dir = test::scratch("traps"), out = test::scratch("traps_out"),
                 json_path = test::scratch("traps_json") / "info.json";
  fs::create_directories(json_path.parent_path());
  {
    io::SequenceWriter w(dir.string(), io::FrameStorage{});
    for (const Frame& f : frames) w.add(f);
    io::Manifest m;
    m.scene = "synthetic";
    w.commit(m);
  }
  const std::vector<std::vector<std::string>> expected = {{}, {"no-surface"}, {"constant-albedo"},
                                                          {"zero-motion"}};
  REQUIRE(app::info_command({dir.string(), "--json", json_path.string()}) == 0);  // warnings only
  const auto info = test::read_json(json_path);
  for (int k = 0; k < 4; ++k) {
    INFO("frame " << k);
    std::vector<std::string> kinds;
    if (info["per_frame"][k].contains("warnings"))
      for (const auto& w : info["per_frame"][k]["warnings"]) kinds.push_back(w);
    REQUIRE(kinds == expected[static_cast<size_t>(k)]);
  }
  REQUIRE(app::denoise_command({dir.string(), out.string(), "--backend", "cpu", "--method",
                                "gaussian", "--no-preview"}) == 0);
  const auto report = test::read_json(out / "report.json");
  REQUIRE(report["input_warnings"].size() == 3);
  for (const auto& w : report["input_warnings"]) {
    const int k = w["frame"];
    REQUIRE(w["kind"] == expected[static_cast<size_t>(k)].at(0));
    REQUIRE(w["text"].get<std::string>().size() > 40);  // a sentence saying what to do
  }
  fs::remove_all(dir);
  fs::remove_all(json_path.parent_path());
  test::remove_output(out);
}

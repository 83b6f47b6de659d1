// The svgf denoise command end to end on a generated sequence: outputs, report, bad input.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include <unistd.h>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "app/denoise_command.h"
#include "cli/command_line.h"
#include "app/method_options.h"
#include "app/frame_order.h"
#include "io/exr_frame.h"
#include "io/sequence.h"
#include "app_test_support.h"
#include "test_support.h"

namespace fs = std::filesystem;
using namespace svgf;

using test::file_bytes;
using test::file_names;
using test::read_json;
using test::scratch;
using test::write_numbered;
using test::write_synthetic;

TEST_CASE("svgf denoise writes frames, previews and a report", "[app]") {
  const fs::path in = write_synthetic(scratch("in"), 4), out = scratch("out");
  REQUIRE(app::denoise_command({in.string(), out.string(), "--backend", "cpu", "--threads", "2"}) == 0);
  for (int k = 0; k < 4; ++k) {
    const std::string name = io::frame_file_name(k);
    const Image img = io::read_rgb_exr((out / name).string());
    REQUIRE(img.width() == 64);
    REQUIRE(fs::file_size(out / "preview" / (name.substr(0, name.size() - 4) + ".png")) > 100);
  }
  std::ifstream f(out / "report.json");
  const auto report = nlohmann::json::parse(f);
  REQUIRE(report["frames"].size() == 4);
  REQUIRE(report["mean_psnr_denoised_db"].get<double>() > report["mean_psnr_noisy_db"].get<double>() + 5);
  REQUIRE(report["denoiser"].get<std::string>().find("cpu") != std::string::npos);
  // Nothing half-written is left behind.
  for (const auto& e : fs::recursive_directory_iterator(out))
    REQUIRE(e.path().filename().string().find(".tmp") == std::string::npos);
  fs::remove_all(in);
  test::remove_output(out);
}

TEST_CASE("svgf denoise: bad input is an error naming the file", "[app]") {
  const fs::path out = scratch("bad_out");
  REQUIRE_THROWS_WITH(app::denoise_command({"/nonexistent/seq", out.string()}),
                      Catch::Contains("/nonexistent/seq"));
  // A frame that lost a channel.
  const fs::path in = write_synthetic(scratch("bad_in"), 2);
  Frame broken = test::SyntheticScene().frame(1);
  broken.albedo = Image();
  REQUIRE_THROWS(io::write_frame((in / io::frame_file_name(1)).string(), broken));
  {
    std::ofstream junk(in / io::frame_file_name(1));
    junk << "not an exr";
  }
  REQUIRE_THROWS_WITH(app::denoise_command({in.string(), out.string(), "--backend", "cpu"}),
                      Catch::Contains(io::frame_file_name(1)));
  REQUIRE_THROWS_WITH(app::denoise_command({in.string(), out.string(), "--backend", "gpu"}),
                      Catch::Contains("gpu"));
  REQUIRE_THROWS_WITH(app::denoise_command({in.string(), out.string(), "--iterations", "x"}),
                      Catch::Contains("--iterations"));
  fs::remove_all(in);
  test::remove_output(out);

  // SVGF's split (issue 12, item 2) needs direct and indirect together, and in every frame with
  // --svgf-split on: found from the headers, before any output exists.
  const fs::path plain = write_synthetic(scratch("split_in"), 2);
  REQUIRE_THROWS_WITH(
      app::denoise_command({plain.string(), out.string(), "--svgf-split", "on"}),
      Catch::Contains(io::frame_file_name(0)) && Catch::Contains("--svgf-split on"));
  CHECK_FALSE(fs::exists(out));
  Frame half = test::SyntheticScene().frame(1);
  half.direct = half.color;
  io::write_frame((plain / io::frame_file_name(1)).string(), half);
  REQUIRE_THROWS_WITH(app::denoise_command({plain.string(), out.string(), "--no-verify"}),
                      Catch::Contains(io::frame_file_name(1)) &&
                          Catch::Contains("'direct' without 'indirect'"));
  CHECK_FALSE(fs::exists(out));
  // Off does not read them; other methods never do.
  REQUIRE(app::denoise_command({plain.string(), out.string(), "--no-verify", "--svgf-split", "off",
                                "--no-preview"}) == 0);
  REQUIRE(app::denoise_command({plain.string(), out.string(), "--no-verify", "--method",
                                "gaussian", "--no-preview"}) == 0);
  fs::remove_all(plain);
  test::remove_output(out);
}

// Issue 15: `svgf denoise X X` overwrote every input frame. An output folder that is the input
// folder, or lies inside it, or holds it, is refused before anything is written, and the input
// is left byte for byte as it was; a sibling whose name merely starts the same is fine.
TEST_CASE("svgf denoise refuses an output folder that overlaps the input folder", "[app]") {
  const fs::path in = write_synthetic(scratch("overlap_in"), 2);
  std::vector<std::pair<fs::path, std::string>> before;
  for (const auto& e : fs::directory_iterator(in)) before.push_back({e.path(), file_bytes(e.path())});
  const std::vector<std::pair<std::string, std::string>> refused = {
      {in.string(), "OUT_DIR"},
      {(in / "").string(), "OUT_DIR"},
      {(in / "out").string(), "OUT_DIR"},
      {(in / "out" / ".." / "..").string(), "IN_DIR"},
      {in.parent_path().string(), "IN_DIR"},
  };
  for (const auto& [out, names] : refused) {
    INFO("OUT_DIR " << out);
    try {
      app::denoise_command({in.string(), out, "--backend", "cpu"});
      FAIL("accepted");
    } catch (const app::UsageError& e) {
      REQUIRE_THAT(e.what(), Catch::Contains(names));
    }
  }
  for (const auto& [path, bytes] : before) REQUIRE(file_bytes(path) == bytes);
  REQUIRE(!fs::exists(in / "preview"));
  REQUIRE(!fs::exists(in / "out"));
  const fs::path sibling = fs::path(in.string() + "_out");
  REQUIRE(app::denoise_command({in.string(), sibling.string(), "--backend", "cpu", "--no-preview"}) == 0);
  REQUIRE(fs::exists(sibling / "report.json"));
  fs::remove_all(in);
  fs::remove_all(sibling);
}

// Issue 15, item 5: a bad argument or an impossible combination is a usage error (exit 2 from
// main) naming the flag, found before the output folder is made.
TEST_CASE("svgf denoise: bad arguments are usage errors found before any output", "[app]") {
  const fs::path in = write_synthetic(scratch("args_in"), 1), out = scratch("args_out");
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--backend", "gpu"}, "gpu"},
      {{"--mode", "fast", "--backend", "cpu"}, "fast mode"},
      {{"--mode", "slow"}, "slow"},
      {{"--exposure", "-1"}, "--exposure"},
      {{"--exposure", "0"}, "--exposure"},
      {{"--exposure", "inf"}, "--exposure"},
      // Each parameter with its range (issue 15, item 5: these were accepted, some gave NaN).
      {{"--phi-color", "-1"}, "--phi-color must be finite and > 0, got -1"},
      {{"--phi-normal", "inf"}, "--phi-normal must be finite and >= 0"},
      {{"--phi-normal", "-128"}, "--phi-normal must be finite and >= 0"},
      {{"--phi-depth", "-1"}, "--phi-depth must be finite and >= 0"},
      {{"--alpha", "0"}, "--alpha must be in (0, 1]"},
      {{"--method", "gaussian", "--sigma", "0"}, "--sigma must be in [0.001, 256]"},
  };
  for (const auto& [flags, names] : cases) {
    std::vector<std::string> args = {in.string(), out.string()};
    args.insert(args.end(), flags.begin(), flags.end());
    INFO(flags.front() << " " << flags[1]);
    try {
      app::denoise_command(args);
      FAIL("accepted");
    } catch (const app::UsageError& e) {
      REQUIRE_THAT(e.what(), Catch::Contains(names));
    }
    REQUIRE(!fs::exists(out));
  }
  fs::remove_all(in);
}

// Issue 15, item 2: the manifest's SHA-256 was never checked. Every frame is now verified before
// the output folder is made; --no-verify skips it.
TEST_CASE("svgf denoise verifies the frames' SHA-256 before writing anything", "[app]") {
  const fs::path in = write_synthetic(scratch("sha_in"), 3), out = scratch("sha_out");
  {  // a byte appended to frame 2: the EXR still reads, the checksum no longer matches
    std::ofstream f(in / io::frame_file_name(2), std::ios::binary | std::ios::app);
    f << '!';
  }
  REQUIRE_THROWS_WITH(app::denoise_command({in.string(), out.string(), "--backend", "cpu"}),
                      Catch::Contains(io::frame_file_name(2)) && Catch::Contains("SHA-256"));
  REQUIRE(!fs::exists(out));
  REQUIRE(app::denoise_command({in.string(), out.string(), "--backend", "cpu", "--no-preview",
                                "--no-verify"}) == 0);
  REQUIRE(fs::exists(out / io::frame_file_name(2)));
  fs::remove_all(in);
  test::remove_output(out);
}

TEST_CASE("svgf denoise --method wavelet: its flags reach the filter, bad values name the flag",
          "[app][wavelet]") {
  const fs::path in = write_synthetic(scratch("wavelet_in"), 2), out = scratch("wavelet_out");
  REQUIRE(app::denoise_command({in.string(), out.string(), "--backend", "cpu", "--method",
                                "wavelet", "--kernel-size", "7", "--iterations", "3",
                                "--sigma-luma", "2", "--no-preview"}) == 0);
  std::ifstream f(out / "report.json");
  const auto report = nlohmann::json::parse(f);
  REQUIRE(report["denoiser"].get<std::string>().rfind("wavelet 7x7 cpu", 0) == 0);
  REQUIRE(report["mean_psnr_denoised_db"].get<double>() >
          report["mean_psnr_noisy_db"].get<double>() + 5);
  // Every block of the synthetic scene has samples: nothing fell back, in each frame and in all.
  REQUIRE(report["fallback_pixels"] == 0);
  for (const auto& frame : report["frames"]) REQUIRE(frame["fallback_pixels"] == 0);
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"--kernel-size", "4"}, {"--sigma-depth", "-1"}, {"--sigma-normal", "-2"},
      {"--sigma-luma", "0"}};
  for (const auto& [flag, value] : bad)
    REQUIRE_THROWS_WITH(app::denoise_command({in.string(), out.string(), "--backend", "cpu",
                                              "--method", "wavelet", flag, value}),
                        Catch::Contains(flag));
  // A flag of another method is an error naming it, not silently ignored.
  REQUIRE_THROWS_WITH(app::denoise_command({in.string(), out.string(), "--backend", "cpu",
                                            "--method", "wavelet", "--phi-color", "5"}),
                      Catch::Contains("--phi-color applies to svgf, not to wavelet"));
  fs::remove_all(in);
  test::remove_output(out);
}

TEST_CASE("svgf denoise --method bmfr: its flags reach the filter, bad values name the flag",
          "[app][bmfr]") {
  const fs::path in = write_synthetic(scratch("bmfr_in"), 3), out = scratch("bmfr_out");
  REQUIRE(app::denoise_command({in.string(), out.string(), "--backend", "cpu", "--method",
                                "bmfr", "--bmfr-rank", "skip", "--bmfr-post-alpha", "0.2",
                                "--bmfr-taa", "on", "--no-preview"}) == 0);
  std::ifstream f(out / "report.json");
  const auto report = nlohmann::json::parse(f);
  REQUIRE(report["denoiser"].get<std::string>().rfind("bmfr (skip, taa) cpu", 0) == 0);
  REQUIRE(report["frames"][1]["stage_ms"].contains("taa"));
  REQUIRE(report["mean_psnr_denoised_db"].get<double>() >
          report["mean_psnr_noisy_db"].get<double>() + 5);
  // Every block of the synthetic scene has samples: nothing fell back, in each frame and in all.
  REQUIRE(report["fallback_pixels"] == 0);
  for (const auto& frame : report["frames"]) REQUIRE(frame["fallback_pixels"] == 0);
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"--bmfr-rank", "qr"},          {"--bmfr-noise", "-1"},
      {"--bmfr-skip-threshold", "1"}, {"--bmfr-pre-alpha", "0"},
      {"--bmfr-post-alpha", "1.5"},   {"--bmfr-position-limit", "0"},
      {"--bmfr-normal-limit", "nan"}, {"--bmfr-taa", "yes"},
      {"--bmfr-taa-alpha", "0"}};
  for (const auto& [flag, value] : bad)
    REQUIRE_THROWS_WITH(app::denoise_command({in.string(), out.string(), "--backend", "cpu",
                                              "--method", "bmfr", flag, value}),
                        Catch::Contains(flag));
  REQUIRE_THROWS_WITH(app::denoise_command({in.string(), out.string(), "--backend", "cpu",
                                            "--method", "svgf", "--bmfr-rank", "skip"}),
                      Catch::Contains("--bmfr-rank applies to bmfr, not to svgf"));
  fs::remove_all(in);
  test::remove_output(out);
}

// Issue 12, item 5: a named SVGF configuration first, the single flags on top of it.
TEST_CASE("svgf flags: --svgf-preset picks the paper's or Falcor's values, flags change them",
          "[app]") {
  const auto params = [](std::vector<std::string> args) {
    CLI::App command_line;
    app::MethodParamFlags flags;
    flags.add_to(command_line);
    cli::parse(command_line, args);
    DenoiserConfig c;
    flags.read(c);
    return c.svgf;
  };
  const SvgfParams falcor = params({"--svgf-preset", "falcor"});
  CHECK(falcor.feedback_tap == 1);
  CHECK(falcor.phi_color == 10.f);
  CHECK_FALSE(falcor.variance_of_mean);
  // Flag order does not matter: the preset is applied first.
  const SvgfParams changed =
      params({"--phi-color", "5", "--svgf-preset", "paper", "--variance-of-mean", "on"});
  CHECK(changed.iterations == 5);
  CHECK(changed.feedback_tap == 0);
  CHECK(changed.phi_color == 5.f);
  CHECK(changed.variance_of_mean);
  CHECK(params({"--history-cap", "16"}).history_cap == 16);
  const SvgfParams converge = params({"--svgf-preset", "converge", "--iterations", "3"});
  CHECK(converge.feedback_tap == -1);
  CHECK(converge.variance_of_mean);
  CHECK(converge.iterations == 3);
  REQUIRE_THROWS_WITH(params({"--svgf-preset", "nvidia"}), Catch::Contains("--svgf-preset") &&
                                                               Catch::Contains("nvidia"));
  REQUIRE_THROWS_WITH(params({"--variance-of-mean", "yes"}),
                      Catch::Contains("--variance-of-mean: must be on or off, got 'yes'"));
  // A range is a CLI11 validator: the message names the flag and the range.
  REQUIRE_THROWS_WITH(params({"--history-cap", "0"}),
                      Catch::Contains("--history-cap: Value 0 not in range 1 to 4096"));
  REQUIRE_THROWS_WITH(params({"--alpha", "nan"}), Catch::Contains("--alpha: must be a number"));
  REQUIRE_THROWS_WITH(params({"--phi-color", "x"}), Catch::Contains("--phi-color"));
  CHECK(params({"--feedback-tap", "-1"}).feedback_tap == -1);  // a negative value, not a flag
  CHECK(params({"--antilag=on", "--antilag-low", "2"}).antilag_low == 2.f);
  CHECK(params({"--antilag=on"}).antilag == Antilag::Statistics);  // today's 'on'
  CHECK(params({"--antilag", "statistics"}).antilag == Antilag::Statistics);
  const SvgfParams asvgf = params({"--antilag", "gradient", "--gradient-iterations", "5"});
  CHECK(asvgf.antilag == Antilag::Gradient);
  CHECK(asvgf.gradient_iterations == 5);
  CHECK(params({}).antilag == Antilag::Gradient);  // the default (docs/svgf.md: Defaults)
  CHECK(params({"--antilag", "off"}).antilag == Antilag::Off);
  CHECK(params({"--gradient-lambda-radius", "2"}).gradient_lambda_radius == 2);
  REQUIRE_THROWS_WITH(params({"--gradient-lambda-radius", "4"}),
                      Catch::Contains("--gradient-lambda-radius"));
  REQUIRE_THROWS_WITH(params({"--antilag", "yes"}),
                      Catch::Contains("--antilag") && Catch::Contains("off, statistics (or on) or gradient"));
  REQUIRE_THROWS_WITH(params({"--gradient-iterations", "9"}), Catch::Contains("--gradient-iterations"));
  const SvgfParams taa = params({"--svgf-taa", "on", "--svgf-taa-alpha", "0.25"});
  CHECK(taa.taa);
  CHECK(taa.taa_alpha == 0.25f);
  CHECK_FALSE(params({}).taa);
  CHECK(params({}).reproject_camera_depth);  // docs/svgf.md, Reprojection under camera motion
  CHECK_FALSE(params({"--camera-depth", "off"}).reproject_camera_depth);
  REQUIRE_THROWS_WITH(params({"--camera-depth", "no"}), Catch::Contains("--camera-depth"));
  REQUIRE_THROWS_WITH(params({"--svgf-taa", "yes"}), Catch::Contains("--svgf-taa"));
  // Direct and indirect apart (issue 12, item 2).
  CHECK(params({}).split == SplitMode::Auto);
  const SvgfParams split =
      params({"--svgf-split", "on", "--indirect-iterations", "5", "--indirect-phi-color", "20"});
  CHECK(split.split == SplitMode::On);
  CHECK(split.indirect().iterations == 5);
  CHECK(split.indirect().phi_color == 20.f);
  CHECK(params({"--svgf-split", "off"}).split == SplitMode::Off);
  REQUIRE_THROWS_WITH(params({"--svgf-split", "yes"}),
                      Catch::Contains("--svgf-split") && Catch::Contains("auto, off or on"));
  REQUIRE_THROWS_WITH(params({"--indirect-iterations", "13"}),
                      Catch::Contains("--indirect-iterations: Value 13 not in range -1 to 12"));
  REQUIRE_THROWS_WITH(params({"--indirect-phi-color", "0"}),
                      Catch::Contains("--indirect-phi-color"));
}

TEST_CASE("svgf denoise --svgf-taa: TAA is timed as its own stage, a bad alpha names the flag",
          "[app]") {
  const fs::path in = write_synthetic(scratch("svgf_taa_in"), 3), out = scratch("svgf_taa_out");
  REQUIRE(app::denoise_command({in.string(), out.string(), "--backend", "cpu", "--svgf-taa", "on",
                                "--no-preview"}) == 0);
  std::ifstream f(out / "report.json");
  const auto report = nlohmann::json::parse(f);
  REQUIRE(report["frames"][1]["stage_ms"].contains("taa"));
  REQUIRE(report["mean_psnr_denoised_db"].get<double>() >
          report["mean_psnr_noisy_db"].get<double>() + 5);
  REQUIRE_THROWS_WITH(app::denoise_command({in.string(), out.string(), "--backend", "cpu",
                                            "--svgf-taa-alpha", "0"}),
                      Catch::Contains("--svgf-taa-alpha"));
  fs::remove_all(in);
  test::remove_output(out);
}

// Issue 15, item 2: frames were read in the manifest's order and outputs numbered by position.
// They are now read by frame number (svgf.frame) and each output keeps its input's number, so a
// shuffled manifest gives the same bytes as the ordered one.
TEST_CASE("svgf denoise reads frames by frame number, not by manifest order", "[app]") {
  const fs::path ordered = write_numbered(scratch("order_in"), {0, 1, 2});
  const fs::path shuffled = write_numbered(scratch("shuffled_in"), {2, 0, 1});
  const fs::path out_a = scratch("order_out"), out_b = scratch("shuffled_out");
  for (const auto& [in, out] : {std::pair{ordered, out_a}, std::pair{shuffled, out_b}})
    REQUIRE(app::denoise_command({in.string(), out.string(), "--backend", "cpu", "--threads", "2",
                                  "--no-preview"}) == 0);
  for (int k = 0; k < 3; ++k) {
    const std::string name = io::frame_file_name(k);
    INFO(name);
    REQUIRE(file_bytes(out_b / name) == file_bytes(out_a / name));
  }
  const auto report = read_json(out_b / "report.json");
  REQUIRE(report["frames"].size() == 3);
  for (int k = 0; k < 3; ++k) {
    REQUIRE(report["frames"][k]["frame"] == k);
    REQUIRE(report["frames"][k]["input"] == io::frame_file_name((k + 1) % 3));  // 2, 0, 1
  }
  for (const auto& p : {ordered, shuffled, out_a, out_b}) fs::remove_all(p);
}

// A gap in the numbering (a dropped frame) restarts the history, as a camera cut does: frame 5
// must not be reprojected from frame 2. Outputs keep their numbers across the gap.
TEST_CASE("svgf denoise restarts the history at a gap and keeps the frame numbers", "[app]") {
  const fs::path gapped = write_numbered(scratch("gap_in"), {0, 1, 2, 5, 6});
  const fs::path tail = write_numbered(scratch("gap_tail_in"), {5, 6});
  const fs::path out = scratch("gap_out"), tail_out = scratch("gap_tail_out");
  for (const auto& [in, o] : {std::pair{gapped, out}, std::pair{tail, tail_out}})
    REQUIRE(app::denoise_command({in.string(), o.string(), "--backend", "cpu", "--threads", "2",
                                  "--no-preview"}) == 0);
  REQUIRE(file_names(out) == std::vector<std::string>{"frame_0000.exr", "frame_0001.exr",
                                                      "frame_0002.exr", "frame_0005.exr",
                                                      "frame_0006.exr", "report.csv",
                                                      "report.html", "report.json"});
  // Frames 5 and 6 come out as if the sequence started at 5.
  for (const char* name : {"frame_0005.exr", "frame_0006.exr"}) {
    INFO(name);
    REQUIRE(file_bytes(out / name) == file_bytes(tail_out / name));
  }
  const auto report = read_json(out / "report.json");
  REQUIRE(report["frames"][3]["frame"] == 5);
  REQUIRE(report["frames"][3]["history_reset"] == "gap: frames 3 to 4 missing");
  REQUIRE(!report["frames"][4].contains("history_reset"));
  for (const auto& p : {gapped, tail, out, tail_out}) fs::remove_all(p);
}

TEST_CASE("svgf denoise refuses two files with one frame number, naming both", "[app]") {
  const fs::path in = write_numbered(scratch("dup_in"), {0, 1, 1}), out = scratch("dup_out");
  REQUIRE_THROWS_WITH(app::denoise_command({in.string(), out.string(), "--backend", "cpu"}),
                      Catch::Contains((in / "frame_0001.exr").string()) &&
                          Catch::Contains((in / "frame_0002.exr").string()) &&
                          Catch::Contains("both frame 1"));
  REQUIRE(!fs::exists(out));
  REQUIRE_THAT(read_json(out.string() + ".failed-report.json")["error"].get<std::string>(),
               Catch::Contains("both frame 1"));
  fs::remove_all(in);
  test::remove_output(out);
}

// Every frame's header is checked before anything is written, even with --no-verify: a later
// frame that lacks its channels stops the run with no output folder.
TEST_CASE("svgf denoise checks every frame's header before writing anything", "[app]") {
  const fs::path in = write_synthetic(scratch("header_in"), 3), out = scratch("header_out");
  io::write_rgb_exr((in / io::frame_file_name(2)).string(), Image(64, 48, 3));
  REQUIRE_THROWS_WITH(app::denoise_command({in.string(), out.string(), "--backend", "cpu",
                                            "--no-verify"}),
                      Catch::Contains(io::frame_file_name(2)) && Catch::Contains("color.R"));
  REQUIRE(!fs::exists(out));
  fs::remove_all(in);
  test::remove_output(out);
}

TEST_CASE("plan_frames: order, restarts and refusals", "[app]") {
  using app::plan_frames;
  const auto plan = plan_frames({{"a", 4}, {"b", 0}, {"c", 1}, {"d", 3}, {"e", 7}}, {3}, "m");
  std::vector<std::pair<int, std::string>> got;
  for (const auto& p : plan) got.push_back({p.number, p.reset});
  REQUIRE(got == std::vector<std::pair<int, std::string>>{{0, "first frame"},
                                                          {1, ""},
                                                          {3, "gap: frame 2 missing"},
                                                          {4, ""},
                                                          {7, "gap: frames 5 to 6 missing"}});
  REQUIRE(plan[0].position == 1);
  REQUIRE(plan_frames({{"a", 0}, {"b", 1}}, {1}, "m")[1].reset == "camera cut");
  REQUIRE_THROWS_WITH(plan_frames({{"a", 0}, {"b", -1}}, {}, "m"),
                      Catch::Contains("b") && Catch::Contains("negative"));
  REQUIRE_THROWS_WITH(plan_frames({{"a", 0}, {"b", 1}}, {2}, "m"),
                      Catch::Contains("m: camera cut at frame 2"));
}

// Issue 15, item 3: outputs were written straight into OUT_DIR, so a run that failed half-way
// left new frames mixed with the old output and its old report. A run now writes into a staging
// folder and swaps it in at the end: a failed run leaves the previous output byte for byte, no
// staging folder, and a failure report beside OUT_DIR.
TEST_CASE("svgf denoise failing half-way leaves the previous output as it was", "[app]") {
  const fs::path in = write_synthetic(scratch("halfway_in"), 4), out = scratch("halfway_out");
  REQUIRE(app::denoise_command({in.string(), out.string(), "--backend", "cpu", "--threads", "2"}) == 0);
  const auto before = test::snapshot(out);
  REQUIRE(before.count("report.json"));
  // Frame 3's header is fine, its pixel data cut short: only reading its pixels fails.
  const fs::path frame3 = in / io::frame_file_name(3);
  const std::string good_frame3 = file_bytes(frame3);
  fs::resize_file(frame3, fs::file_size(frame3) - 64);
  REQUIRE_THROWS_WITH(app::denoise_command({in.string(), out.string(), "--backend", "cpu",
                                            "--threads", "2", "--iterations", "2", "--no-verify"}),
                      Catch::Contains(frame3.string()));
  REQUIRE(test::snapshot(out) == before);
  REQUIRE(test::leftovers(out).empty());
  const fs::path failure = out.string() + ".failed-report.json";
  const auto report = read_json(failure);
  REQUIRE(report["status"] == "failed");
  REQUIRE(report["stage"] == "denoising");
  REQUIRE(report["frame"] == 3);
  REQUIRE(report["file"] == frame3.string());
  REQUIRE(report["frames_written"] == 3);
  REQUIRE_THAT(report["error"].get<std::string>(), Catch::Contains(frame3.string()));
  // The next good run replaces the output and removes the failure report, which would lie.
  { std::ofstream(frame3, std::ios::binary) << good_frame3; }
  REQUIRE(app::denoise_command({in.string(), out.string(), "--backend", "cpu", "--threads", "2",
                                "--iterations", "2", "--no-preview"}) == 0);
  REQUIRE(!fs::exists(failure));
  REQUIRE(!fs::exists(out / "preview"));  // replaced as a whole, not merged
  REQUIRE(file_bytes(out / "report.json") != before.at("report.json"));
  REQUIRE(test::leftovers(out).empty());
  fs::remove_all(in);
  test::remove_output(out);
}

// OUT_DIR is replaced as a whole, so it must be absent, empty or an earlier output (report.json):
// a wrong path holding other files is a usage error before anything is read.
TEST_CASE("svgf denoise refuses to replace a folder that is not an earlier output", "[app]") {
  const fs::path in = write_synthetic(scratch("replace_in"), 1), out = scratch("replace_out");
  fs::create_directories(out);
  { std::ofstream(out / "notes.txt") << "keep"; }
  REQUIRE_THROWS_AS(app::denoise_command({in.string(), out.string(), "--backend", "cpu"}),
                    app::UsageError);
  REQUIRE(file_names(out) == std::vector<std::string>{"notes.txt"});
  // Nor may the input be a leftover that a run into OUT_DIR would clear.
  const fs::path leftover = out.string() + ".old-1";
  fs::rename(in, leftover);
  test::remove_output(out);
  REQUIRE_THROWS_WITH(app::denoise_command({leftover.string(), out.string(), "--backend", "cpu"}),
                      Catch::Contains("leftover"));
  REQUIRE(fs::exists(leftover / "manifest.json"));
  fs::remove_all(leftover);
}

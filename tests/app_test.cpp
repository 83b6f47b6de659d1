// The svgf denoise command end to end on a generated sequence: outputs, report, bad input.
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
#include "app/options.h"
#include "io/exr_frame.h"
#include "io/sequence.h"
#include "synthetic_sequence.h"
#include "test_support.h"

namespace fs = std::filesystem;
using namespace svgf;

namespace {

fs::path scratch(const std::string& name) {
  const fs::path p = fs::temp_directory_path() / ("svgf_app_test_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(p);
  return p;
}

fs::path write_synthetic(const fs::path& dir, int frames) {
  test::SyntheticScene scene;
  io::SequenceWriter writer(dir.string(), io::FrameStorage{});
  for (int k = 0; k < frames; ++k) writer.add(scene.frame(k));
  io::Manifest m;
  m.scene = "synthetic";
  m.generator = "app_test";
  writer.commit(m);
  return dir;
}

}  // namespace

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
  fs::remove_all(out);
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
  fs::remove_all(out);
}

namespace {

std::string file_bytes(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

}  // namespace

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
  fs::remove_all(out);
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
  fs::remove_all(out);
}

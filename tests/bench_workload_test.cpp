// The benchmark's rendered frames carry A-SVGF's gradient samples, its cache renders again a
// frame stored without them, and a --antilag gradient run on them times and costs the gradient
// stages.
#include <catch2/catch.hpp>
#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "bench/runner.h"
#include "bench/workload.h"
#include "io/exr_frame.h"
#include "methods/svgf/stages.h"

using namespace svgf;
using namespace svgf::bench;
using json = nlohmann::json;
namespace fs = std::filesystem;

namespace {

// A folder of its own under the system's temporary folder, removed afterwards.
struct TempDir {
  fs::path path;
  explicit TempDir(const std::string& name) : path(fs::temp_directory_path() / name) {
    fs::remove_all(path);
  }
  ~TempDir() { fs::remove_all(path); }
};

std::vector<std::string> stage_names(const json& e) {
  std::vector<std::string> names;
  for (const json& s : e["stages"]) names.push_back(s["stage"].get<std::string>());
  return names;
}

bool has(const std::vector<std::string>& v, const std::string& name) {
  return std::find(v.begin(), v.end(), name) != v.end();
}

}  // namespace

TEST_CASE("rendered benchmark frames carry gradient samples, older caches are rendered again",
          "[bench][workload]") {
  if (!renderer_available()) {
    WARN("this build has no renderer: the synthetic frames carry no gradient samples");
    CHECK_FALSE(generate_frames("cornell-moving", 24, 15, 2, "").gradient_samples());
    return;
  }
  TempDir cache("svgf_bench_workload_test");
  const FrameSet rendered = generate_frames("cornell-moving", 24, 15, 3, cache.path.string());
  REQUIRE(rendered.frames.size() == 3);
  CHECK(rendered.gradient_samples());
  CHECK(rendered.description.find("with gradient samples") != std::string::npos);
  // Frame 0 has no earlier frame (the group is there, all zeros); the next ones hold samples.
  const Image& g = rendered.frames[1].gradient;
  REQUIRE(g.channels() == 3);
  CHECK(std::count(g.plane(2), g.plane(2) + g.pixel_count(), 1.f) > 0);

  // A cache written before the renders carried gradient samples: each frame is rendered again.
  int stripped = 0;
  for (const auto& e : fs::directory_iterator(cache.path)) {
    Frame f = io::read_frame(e.path().string());
    f.gradient = Image();
    io::write_frame(e.path().string(), f);
    ++stripped;
  }
  REQUIRE(stripped == 3);
  const FrameSet again = generate_frames("cornell-moving", 24, 15, 3, cache.path.string());
  REQUIRE(again.gradient_samples());
  CHECK(again.frames[1].gradient.data() == g.data());
  for (const auto& e : fs::directory_iterator(cache.path))
    CHECK_FALSE(io::read_frame(e.path().string()).gradient.empty());
}

TEST_CASE("a --antilag gradient run times the three gradient stages and says the frames carry "
          "samples",
          "[bench][workload]") {
  if (!renderer_available()) {
    WARN("this build has no renderer: no gradient samples to time");
    return;
  }
  const FrameSet frames = generate_frames("cornell-moving", 24, 15, 3, "");
  RunConfig c = run_config("svgf");
  c.denoiser.threads = 1;
  TimingOptions t;
  t.warmup = 1;
  t.frames = 3;
  for (Antilag antilag : {Antilag::Gradient, Antilag::Statistics}) {
    CAPTURE(to_string(antilag));
    c.denoiser.svgf.antilag = antilag;
    const json e = time_run(c, frames, t, Ceilings{10.0, 1e10, "test"});
    CHECK(e["input"]["gradient_samples"] == true);
    const std::vector<std::string> names = stage_names(e);
    const bool gradient = antilag == Antilag::Gradient;
    for (const char* stage : {svgf_stage::kGradient, svgf_stage::kGradientAtrous,
                              svgf_stage::kGradientLambda})
      CHECK(has(names, stage) == gradient);
    // Every stage is counted (bench/stage_cost.h), so the frame has a floor.
    for (const json& s : e["stages"]) CHECK(s.contains("bytes_read_per_px"));
    CHECK(e["cost_model"] == "bench/stage_cost.cpp");
  }
  // Direct and indirect filtered apart: the stages run once a frame are counted, the others
  // (run once per signal) are not, and the frame has no floor.
  {
    RunConfig split = c;
    split.denoiser.svgf.antilag = Antilag::Gradient;
    split.denoiser.svgf.split = SplitMode::On;
    split.denoiser.svgf.taa = true;
    const json e = time_run(split, generate_frames("cornell-moving", 24, 15, 3, "", true), t,
                            Ceilings{10.0, 1e10, "test"});
    for (const json& s : e["stages"]) {
      const std::string name = s["stage"].get<std::string>();
      INFO(name);
      const bool once = name == svgf_stage::kGradient || name == svgf_stage::kGradientAtrous ||
                        name == svgf_stage::kGradientLambda || name == svgf_stage::kSplitSum ||
                        name == svgf_stage::kTaa;
      CHECK(s.contains("bytes_read_per_px") == once);
    }
    CHECK(has(stage_names(e), svgf_stage::kSplitSum));
    CHECK_FALSE(e.contains("floor"));
  }
  // Frames without the group: the benchmark says so.
  FrameSet stripped = frames;
  for (Frame& f : stripped.frames) f.gradient = Image();
  c.denoiser.svgf.antilag = Antilag::Gradient;
  const json e = time_run(c, stripped, t, Ceilings{10.0, 1e10, "test"});
  CHECK(e["input"]["gradient_samples"] == false);
  CHECK_FALSE(has(stage_names(e), svgf_stage::kGradient));
}

TEST_CASE("an SVGF run counts the young histories the variance estimates and costs them",
          "[bench][workload]") {
  // Three frames played cyclically: the first timed frame of a run without warm-up has no
  // history (every surface pixel young); after warm-up frames most histories are old.
  const FrameSet frames = generate_frames("cornell-moving", 24, 15, 3, "");
  RunConfig c = run_config("svgf");
  c.denoiser.threads = 1;
  const auto variance = [](const json& e) {
    for (const json& s : e["stages"])
      if (s["stage"] == svgf_stage::kVariance) return s;
    FAIL("no variance stage");
    return json();
  };
  TimingOptions first;
  first.warmup = 0;
  first.frames = 1;
  const json e1 = time_run(c, frames, first, Ceilings{10.0, 1e10, "test"});
  REQUIRE(e1["input"].contains("young_fraction"));
  CHECK(e1["input"]["young_fraction"]["median"].get<double>() == 1.0);
  CHECK(variance(e1)["taps_per_px"].get<double>() ==
        Approx(49.0 * e1["input"]["surface_fraction"].get<double>()));

  TimingOptions later;
  later.warmup = 8;
  later.frames = 3;
  const json e2 = time_run(c, frames, later, Ceilings{10.0, 1e10, "test"});
  // The timed frames only: the warm-up frames' histories are younger still.
  CHECK(e2["input"]["young_fraction"]["frames"] == e2["frames"]);
  const double young = e2["input"]["young_fraction"]["median"].get<double>();
  CHECK(young < 0.5);
  CHECK(e2["input"]["young_fraction"]["min"].get<double>() <= young);
  CHECK(e2["input"]["young_fraction"]["max"].get<double>() >= young);
  // The variance's floor counts its taps: more operations with more young pixels.
  CHECK(variance(e1)["ops_per_px"].get<double>() > variance(e2)["ops_per_px"].get<double>());

  // Another method has no history to count.
  const json other = time_run(run_config("gaussian"), frames, first, Ceilings{10.0, 1e10, "test"});
  CHECK_FALSE(other["input"].contains("young_fraction"));
}

// svgf-bench runs any project method through make_denoiser: a run's stage timings carry the
// method's own stage names, costs only where the cost model counts the stage (SVGF's stages, the
// other methods' filter stage), and its JSON reads back through the results model into the
// chart points, the summary and the targets.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iterator>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include "bench/chart_points.h"
#include "bench/chart_tables.h"
#include "bench/results.h"
#include "bench/runner.h"
#include "bench/stage_cost.h"
#include "bench/suites.h"
#include "bench/summary.h"

using namespace svgf;
using namespace svgf::bench;
namespace fs = std::filesystem;

namespace {

FrameSet fixture() {
  return load_fixture(std::string(SVGF_SOURCE_DIR) + "/fixtures/cornell-moving", 3);
}

TimingOptions quick() {
  TimingOptions t;
  t.warmup = 1;
  t.frames = 2;
  return t;
}

// Only `costed` has bytes, operations, a floor and a per-tap cost; no stage has a made-up count,
// and without every stage counted there is no frame floor.
void require_costed_stage_only(const json& e, const RunConfig& c, const std::string& costed) {
  std::vector<std::string> names;
  for (const json& s : e["stages"]) {
    const std::string name = s["stage"].get<std::string>();
    names.push_back(name);
    CHECK(s["ms"]["median"].get<double>() > 0);
    CHECK(s.contains("bytes_read_per_px") == (name == costed));
    CHECK(s.contains("floor") == (name == costed));
    CHECK(s.contains("per_tap") == (name == costed));
  }
  CHECK(names == make_denoiser(c.denoiser)->stages());
  CHECK_FALSE(e.contains("floor"));
  CHECK(e["cost_model"] == "bench/stage_cost.cpp, stage " + costed + " only");
}

// The stage named `name` of a timing entry.
const json& stage_of(const json& e, const std::string& name) {
  for (const json& s : e["stages"])
    if (s["stage"] == name) return s;
  FAIL("no stage " << name);
  static const json none;
  return none;
}

}  // namespace

TEST_CASE("a wavelet run is timed by the method's own stages, its a-trous passes costed",
          "[bench][wavelet]") {
  const RunConfig c = wavelet_config(Backend::Cpu, Mode::Exact, 3, 2);
  const json e = time_run(c, fixture(), quick(), Ceilings{10.0, 1e10, "test"});
  require_costed_stage_only(e, c, "atrous");
  CHECK(e["frames"] == 2);
  CHECK(e["config"]["kernel_size"] == 3);
  CHECK(e["key"] == "wavelet cpu exact it4 k3");
  const double surface = e["input"]["surface_fraction"].get<double>();
  CHECK(stage_of(e, "atrous")["taps_per_px"].get<double>() == Approx(4 * 8 * surface));
}

TEST_CASE("a JBF run costs its filter stage a tap", "[bench][jbf]") {
  for (int levels : {0, 2}) {
    RunConfig c = jbf_config(Backend::Cpu, Mode::Exact, levels, 2);
    c.denoiser.jbf.radius = 2;  // a quick full window
    CAPTURE(c.key());
    const json e = time_run(c, fixture(), quick(), Ceilings{10.0, 1e10, "test"});
    const std::string stage = levels ? "atrous" : "filter";
    require_costed_stage_only(e, c, stage);
    const json& s = stage_of(e, stage);
    const double pixels = e["input"]["pixels"].get<double>();
    const double taps = s["taps_per_px"].get<double>();
    CHECK(taps == Approx(24 * std::max(levels, 1) * e["input"]["surface_fraction"].get<double>()));
    // A tap's time is the stage's over the frame's taps; the float-rate share is the counted
    // operations' rate over the ceiling.
    const double ms = s["ms"]["median"].get<double>();
    CHECK(s["per_tap"]["ns"].get<double>() == Approx(ms * 1e6 / (taps * pixels)));
    CHECK(s["per_tap"]["ops"].get<double>() * taps == Approx(s["ops_per_px"].get<double>()));
    CHECK(s["pct_of_ops"].get<double>() ==
          Approx(100 * s["ops_per_px"].get<double>() * pixels / (ms * 1e-3) / 1e10));
  }
}

TEST_CASE("SVGF keeps its cost model and floor", "[bench][svgf]") {
  const json e = time_run(svgf_config(Backend::Cpu, Mode::Exact, 2, 1, 2), fixture(), quick(),
                          Ceilings{10.0, 1e10, "test"});
  CHECK(e["cost_model"] == "bench/stage_cost.cpp");
  REQUIRE(e.contains("floor"));
  for (const json& s : e["stages"]) CHECK(s.contains("bytes_read_per_px"));
}

TEST_CASE("a BMFR run is costed in every stage and has a frame floor", "[bench][bmfr]") {
  RunConfig c = run_config("bmfr");
  c.denoiser.threads = 2;
  const json e = time_run(c, fixture(), quick(), Ceilings{10.0, 1e10, "test"});
  CHECK(e["cost_model"] == "bench/stage_cost.cpp");
  REQUIRE(e.contains("floor"));
  double floor_ms = 0;
  for (const json& s : e["stages"]) {
    INFO(s["stage"]);
    REQUIRE(s.contains("floor"));
    floor_ms += s["floor"]["floor_ms"].get<double>();
  }
  CHECK(e["floor"]["floor_ms"].get<double>() == Approx(floor_ms));
  // The regression's rows: 25 blocks of 1024 rows over 128x128 pixels (about 1.56 a pixel),
  // 10 planes a row.
  const double rows = bmfr_blocks_per_px(128, 128) * 1024;
  CHECK(rows > 1.4);
  CHECK(stage_of(e, "regression")["bytes_read_per_px"].get<double>() == Approx(rows * 40));
}

TEST_CASE("keys are unique per configuration and name the kernel size", "[bench]") {
  std::set<std::string> keys;
  for (int k : {3, 5, 7, 9}) keys.insert(wavelet_config(Backend::Cpu, Mode::Exact, k, 2).key());
  RunConfig moved = wavelet_config(Backend::Cpu, Mode::Exact, 5, 2);
  moved.denoiser.wavelet.sigma_luma = 8.f;
  keys.insert(moved.key());
  keys.insert(run_config("gaussian").key());
  keys.insert(run_config("cv-gaussian").key());
  keys.insert(svgf_config(Backend::Cpu, Mode::Exact, 4, 1, 2).key());
  CHECK(keys.size() == 8);
  CHECK(wavelet_config(Backend::Cpu, Mode::Exact, 5, 0).key() == kWaveletCpu);
  CHECK(wavelet_config(Backend::Cuda, Mode::Fast, 5, 0).key() == kWaveletFast);
  const SvgfParams defaults;
  const int it = defaults.iterations, tap = defaults.feedback_tap;
  CHECK(svgf_config(Backend::Cpu, Mode::Exact, it, tap, 0).key() == kDefaultCpu);
  CHECK(svgf_config(Backend::Cuda, Mode::Exact, it, tap, 0).key() == kDefaultExact);
  CHECK(svgf_config(Backend::Cuda, Mode::Fast, it, tap, 0).key() == kDefaultFast);
  CHECK_THROWS_WITH(run_config("bilateral"), Catch::Contains("cv-bilateral"));
}

TEST_CASE("a wavelet suite entry reads back through the results model", "[bench][wavelet]") {
  const FrameSet f = fixture();
  const RunConfig c = wavelet_config(Backend::Cpu, Mode::Exact, 5, 2);
  json timing = time_run(c, f, quick(), Ceilings{});
  timing["group"] = "wavelet";
  json quality = quality_run(c, f);
  quality["group"] = "quality";
  REQUIRE(quality["frames"].size() == 3);
  const json doc = {{"suite", "cpu"},
                    {"host", {{"cpu_model", "test"}, {"hardware_threads", 2}}},
                    {"ceilings", json::object()},
                    {"sections", json::object()},
                    {"timings", {timing}},
                    {"quality", {quality}}};
  const fs::path dir = fs::temp_directory_path() / "svgf_bench_methods_test";
  fs::create_directories(dir);
  std::ofstream(dir / "cpu.json") << doc.dump();
  const Results r = load_results(dir.string());
  fs::remove_all(dir);

  REQUIRE(r.timings("cpu", "wavelet").size() == 1);
  CHECK(r.quality(kWaveletCpu).count("cornell-moving") == 1);
  const std::vector<Point> pts = chart_points(r);
  REQUIRE(pts.size() == 1);
  CHECK(pts[0].series == "cpu_wavelet");
  CHECK(pts[0].key == kWaveletCpu);
  CHECK(std::isfinite(pts[0].q.psnr));
  CHECK(pts[0].pareto_psnr);
  const std::string md = summary_markdown(r, pts, {});
  CHECK_THAT(md, Catch::Contains("Wavelet kernel sizes"));
  CHECK_THAT(md, Catch::Contains("| 5x5 wavelet, 4 passes |"));
  CHECK_THAT(md, Catch::Contains("**wavelet cpu exact it4 k5 t2**"));
  CHECK_THAT(md, Catch::Contains("| atrous |"));
  CHECK_THAT(md, Catch::Contains("n/a"));
}

TEST_CASE("a BMFR quality run reports its blocks: rank deficiency and condition", "[bench][bmfr]") {
  const FrameSet f = fixture();
  for (const char* strategy : {"noise", "skip"}) {
    RunConfig c = run_config("bmfr");
    c.denoiser.threads = 2;
    c.denoiser.bmfr.rank_strategy = parse_bmfr_rank_strategy(strategy);
    const json q = quality_run(c, f);
    INFO(strategy << ": " << q["blocks"].dump());
    REQUIRE(q.contains("blocks"));
    const json& b = q["blocks"];
    CHECK(b["blocks"] == 3 * 25);  // 128x128 on a moving grid: 5 x 5 blocks a frame
    CHECK(b["empty"] == 0);
    // The fixture's walls are axis-aligned: skip drops columns in most blocks, noise in none.
    if (std::string(strategy) == "noise") CHECK(b["rank_deficient"] == 0);
    else CHECK(b["rank_deficient"].get<int>() > 3 * 25 / 2);
    CHECK(b["condition_median"].get<double>() >= 1.0);
    CHECK(b["condition_max"].get<double>() < 1e4);
  }
  // Methods without blocks report none.
  CHECK_FALSE(quality_run(run_config("svgf"), f).contains("blocks"));
}

TEST_CASE("every method and variant has its chart series", "[bench]") {
  auto series = [](const std::string& method, const std::string& backend, const std::string& mode) {
    return series_of({{"config", {{"method", method}, {"backend", backend}, {"mode", mode}}}});
  };
  CHECK(series("svgf", "cpu", "exact") == "cpu_exact");
  CHECK(series("svgf", "cuda", "fast") == "cuda_fast");
  CHECK(series("wavelet", "cuda", "exact") == "cuda_exact_wavelet");
  CHECK(series("gaussian", "cpu", "exact") == "cpu_gaussian");
  CHECK(series("jbf", "cuda", "fast") == "cuda_fast_jbf");
  CHECK(series("jbf-atrous", "cpu", "exact") == "cpu_jbf");
  CHECK(series("cv-nlmeans", "cpu", "opencv") == "baselines");
  for (const std::string& s :
       {series("gaussian", "cuda", "fast"), series("jbf-atrous", "cuda", "exact")})
    CHECK(std::find(std::begin(kSeries), std::end(kSeries), s) != std::end(kSeries));
  CHECK(jbf_config(Backend::Cpu, Mode::Exact, 0, 0).key() == kJbfCpu);
  CHECK(jbf_config(Backend::Cpu, Mode::Exact, 4, 0).key() == kJbfAtrousCpu);
  CHECK(series("bmfr", "cpu", "exact") == "cpu_bmfr");
  for (const std::string& s : {series("bmfr", "cuda", "exact"), series("bmfr", "cuda", "fast")})
    CHECK(std::find(std::begin(kSeries), std::end(kSeries), s) != std::end(kSeries));
  CHECK(bmfr_config(Backend::Cpu, Mode::Exact, BmfrRankStrategy::Noise, 0).key() == kBmfrCpu);
  CHECK(bmfr_config(Backend::Cpu, Mode::Exact, BmfrRankStrategy::Skip, 0).key() == kBmfrSkipCpu);
  CHECK(bmfr_config(Backend::Cuda, Mode::Fast, BmfrRankStrategy::Noise, 0).key() == kBmfrFast);
  for (const char* suite : {"cpu", "gpu"}) {
    const std::vector<std::string> sections = suite_sections(suite);
    CHECK(std::find(sections.begin(), sections.end(), "bmfr") != sections.end());
  }
}

TEST_CASE("BMFR entries read back into the chart, the BMFR and block tables of the summary",
          "[bench][bmfr]") {
  const FrameSet f = fixture();
  const RunConfig c = bmfr_config(Backend::Cpu, Mode::Exact, BmfrRankStrategy::Skip, 2);
  json chart = time_run(c, f, quick(), Ceilings{10.0, 1e10, "test"});
  chart["group"] = "bmfr";
  // The same configuration on the full-coverage scene, and SVGF's reference there: entries of
  // the section, not chart points.
  json room = chart;
  room["input"]["scene"] = "camera-pan";
  json svgf = time_run(svgf_config(Backend::Cpu, Mode::Exact, 4, 1, 2), f, quick(), Ceilings{});
  svgf["group"] = "bmfr";
  svgf["input"]["scene"] = "camera-pan";
  json quality = quality_run(c, f);
  quality["group"] = "quality";
  const json doc = {{"suite", "cpu"},
                    {"chart_size", size_of(chart)},
                    {"chart_scene", "cornell-moving"},
                    {"host", {{"cpu_model", "test"}, {"hardware_threads", 2}}},
                    {"ceilings", json::object()},
                    {"sections", json::object()},
                    {"timings", {chart, room, svgf}},
                    {"quality", {quality}}};
  const fs::path dir = fs::temp_directory_path() / "svgf_bench_bmfr_test";
  fs::create_directories(dir);
  std::ofstream(dir / "cpu.json") << doc.dump();
  const Results r = load_results(dir.string());
  fs::remove_all(dir);

  const std::vector<Point> pts = chart_points(r);
  REQUIRE(pts.size() == 1);
  CHECK(pts[0].series == "cpu_bmfr");
  CHECK(pts[0].key == kBmfrSkipCpu);
  CHECK(std::isfinite(pts[0].q.psnr));

  const std::string md = summary_markdown(r, pts, {});
  CHECK_THAT(md, Catch::Contains("## BMFR (bmfr sections)"));
  CHECK_THAT(md,
             Catch::Contains("| bmfr cpu exact skip t2 | " + size_of(chart) + " | camera-pan |"));
  CHECK_THAT(md, Catch::Contains("| svgf cpu exact it4 tap1 t2 | " + size_of(chart) +
                                 " | camera-pan |"));
  // The block diagnostics of the fixture: 3 frames of 25 blocks.
  CHECK_THAT(md, Catch::Contains("## Blocks of the block-fitting methods"));
  CHECK_THAT(md, Catch::Contains("| bmfr cpu exact skip | cornell-moving | 75 |"));
  CHECK_THAT(md, Catch::Contains("| exact | bmfr regression (1920x1080) |"));
  CHECK_THAT(md, Catch::Contains("**bmfr cpu exact skip t2**"));
}

TEST_CASE("JBF and kernel-size study entries read back into the charts, the study and the summary",
          "[bench][jbf]") {
  const FrameSet f = fixture();
  // (section, configuration): the JBF's a-trous form; the study's wavelet, Gaussian and dense
  // JBF (small radii, so the test stays quick).
  RunConfig dense = jbf_config(Backend::Cpu, Mode::Exact, 0, 2);
  dense.denoiser.jbf.radius = 2;
  dense.denoiser.jbf.alpha = 1.f;
  const std::pair<std::string, RunConfig> runs[] = {
      {"jbf", jbf_config(Backend::Cpu, Mode::Exact, 2, 2)},
      {"wavelet", wavelet_config(Backend::Cpu, Mode::Exact, 3, 2)},
      {"wavelet", gaussian_config(Backend::Cpu, Mode::Exact, 4.f / 3.f, 4, 2)},
      {"wavelet", dense}};
  json timings = json::array(), quality = json::array();
  for (const auto& [section, c] : runs) {
    json t = time_run(c, f, quick(), Ceilings{10.0, 1e10, "test"});
    t["group"] = section;
    timings.push_back(t);
    json q = quality_run(c, f);
    q["group"] = "quality";
    quality.push_back(q);
  }
  json elsewhere = timings[0];  // the same configuration at another size: not a chart point
  elsewhere["input"]["width"] = 256;
  timings.push_back(elsewhere);
  const json doc = {{"suite", "cpu"},
                    {"chart_size", size_of(timings[0])},
                    {"host", {{"cpu_model", "test"}, {"hardware_threads", 2}}},
                    {"ceilings", json::object()},
                    {"sections", json::object()},
                    {"timings", timings},
                    {"quality", quality}};
  const fs::path dir = fs::temp_directory_path() / "svgf_bench_jbf_test";
  fs::create_directories(dir);
  std::ofstream(dir / "cpu.json") << doc.dump();
  const Results r = load_results(dir.string());

  const std::vector<Point> pts = chart_points(r);
  std::vector<std::string> series;
  for (const Point& p : pts) series.push_back(p.series);
  // Grouped in kSeries order; the JBF's a-trous form and the dense JBF are one series.
  CHECK(series ==
        std::vector<std::string>{"cpu_wavelet", "cpu_gaussian", "cpu_jbf", "cpu_jbf"});
  for (const Point& p : pts) CHECK(std::isfinite(p.q.psnr));

  const KernelStudy study = kernel_study(r);
  REQUIRE(study.rows.size() == 3);
  CHECK(study.rows[0].name == "3x3 wavelet, 4 passes");
  REQUIRE(study.find(StudyRow::Gaussian));
  CHECK(study.find(StudyRow::Gaussian)->name == "9x9 Gaussian, sigma 1.33 (separable)");
  REQUIRE(study.find(StudyRow::Dense));
  CHECK(study.find(StudyRow::Dense)->name == "5x5 JBF (dense, no history)");
  CHECK(study.rows[0].ms[0] == median_ms(timings[1]));
  CHECK(std::isnan(study.rows[0].ms[2]));  // no GPU results

  const std::string md = summary_markdown(r, pts, {});
  CHECK_THAT(md, Catch::Contains("× Gaussian | Δ dB | × dense JBF | Δ dB |"));
  CHECK_THAT(md, Catch::Contains("## Cost a tap"));
  CHECK_THAT(md, Catch::Contains("| jbf-atrous cpu exact l2 t2 | " + size_of(timings[0]) +
                                 " | atrous |"));
  CHECK_THAT(md, Catch::Contains("**jbf-atrous cpu exact l2 t2**"));

  write_points(dir, pts);
  write_kernel_study(dir, r);
  auto data_lines = [&](const std::string& name) {
    std::ifstream in(dir / name);
    REQUIRE(in);
    int n = 0;
    for (std::string line; std::getline(in, line);) n += !line.empty() && line[0] != '#';
    return n;
  };
  CHECK(data_lines("points_cpu_jbf.dat") == 2);
  CHECK(data_lines("points_cpu_gaussian.dat") == 1);
  CHECK(data_lines("kernel_study_cpu_wavelet.dat") == 1);
  CHECK(data_lines("kernel_study_cpu_gaussian.dat") == 1);
  CHECK(data_lines("kernel_study_cpu_dense.dat") == 1);
  CHECK(data_lines("kernel_study_cuda_fast_wavelet.dat") == 0);
  fs::remove_all(dir);
}

TEST_CASE("OpenCV baseline entries from before the cv- names read under them", "[bench]") {
  const json old_entry = {{"group", "quality"},
                          {"key", "gaussian s1"},
                          {"label", "gaussian s1 t2"},
                          {"scene", "cut"},
                          {"mean", {{"psnr", 20.0}}},
                          {"frames", json::array()},
                          {"config", {{"method", "gaussian"}, {"mode", "opencv"}}}};
  const fs::path dir = fs::temp_directory_path() / "svgf_bench_legacy_test";
  fs::create_directories(dir);
  std::ofstream(dir / "cpu.json") << json({{"suite", "cpu"}, {"quality", {old_entry}}}).dump();
  const Results r = load_results(dir.string());
  fs::remove_all(dir);
  CHECK(r.quality("cv-gaussian s1").count("cut") == 1);
  CHECK(r.quality("gaussian s1").empty());
}

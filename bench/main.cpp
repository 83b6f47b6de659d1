// svgf-bench: the benchmark binary (not a test). docs/benchmarks.md shows how its numbers are
// made and what they mean.
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "app/method_options.h"
#include "app/options.h"
#include "bench/baselines.h"
#include "bench/chart_data.h"
#include "bench/gpu_probe.h"
#include "bench/host_probe.h"
#include "bench/runner.h"
#include "bench/suites.h"
#include "bench/workload.h"
#include "io/atomic_file.h"
#include "io/printable.h"

namespace fs = std::filesystem;
using svgf::app::kMethodParamUsage;
using svgf::app::Options;
using svgf::app::UsageError;
using json = nlohmann::json;

namespace {

// The options before and after the method parameters (app/method_options.h).
const char* const kUsageHead =
    "usage: svgf-bench [run] [options]          one configuration, timed (and measured)\n"
    "       svgf-bench suite cpu|gpu [options]   the suites behind docs/benchmarks.md\n"
    "       svgf-bench chart-data RESULTS_DIR [--out DIR] [--targets FILE]\n"
    "                                            tables for bench/chart.sh and summary.md, with\n"
    "                                            each target's verdict (default: the source\n"
    "                                            tree's bench/targets.json)\n"
    "       svgf-bench --help\n"
    "\n"
    "run: times every stage of the method, by its own stage names (CUDA events on the GPU, a\n"
    "steady clock on the CPU) over --frames frames after --warmup frames, and prints per stage\n"
    "and per frame the median and p95, megapixels per second and the peak device memory; for\n"
    "the stages the cost model counts (bench/stage_cost.cpp: every svgf and bmfr stage, the\n"
    "filter stage of jbf, jbf-atrous and wavelet) also the bytes and operations the stage must\n"
    "move and do, the achieved bandwidth against the measured copy bandwidth, the share of the\n"
    "measured float rate, the floor and, for a filter's taps, the time a tap (other stages:\n"
    "n/a).\n"
    "  --method M            a project method, as `svgf denoise`: svgf (default), wavelet,\n"
    "                        gaussian, jbf, jbf-atrous, bmfr; or an OpenCV baseline:\n"
    "                        (CPU) cv-gaussian, cv-bilateral, cv-joint-bilateral, cv-nlmeans\n"
    "  --backend cpu|cuda    (default cpu)\n"
    "  --mode exact|fast     fast exists on cuda only (default exact)\n"
    "  --threads N           CPU threads, 0 = all cores (default 0)\n"
    "  --size S              generated frames: 720p, 1080p, 4k, N (square) or WxH (default 720p)\n"
    "  --fixture DIR         a fixture sequence instead of generated frames\n"
    "  --scene NAME          scene rendered for --size (default cornell-moving)\n"
    "  --distinct-frames K   frames rendered for --size, played cyclically (default 8)\n"
    "  --cache DIR           where rendered frames are kept between runs ('' = none)\n"
    "  --frames N            timed frames (default 100)\n"
    "  --warmup N            untimed frames first (default 10)\n"
    "  --budget-s S          stop timing after S seconds once 10 frames are timed (default none)\n"
    "  --block WxH           CUDA block shape (default 32x8)\n"
    "  --quality             with --fixture: per-frame PSNR, SSIM, relMSE, FLIP and temporal\n"
    "                        stability against the reference\n"
    "  --json PATH           write the results as JSON\n"
    "  --no-ceilings         skip measuring the copy bandwidth and float rate (for profilers)\n"
    "method parameters (as `svgf denoise`; a flag the method does not read is an error):\n";
const char* const kUsageTail =
    "\n"
    "suite: cpu (sections sizes, chart, coverage, baselines, wavelet, jbf, bmfr, quality) or\n"
    "gpu (sizes, iterations, coverage, blocks, chart, wavelet, jbf, bmfr, quality); results go to\n"
    "OUT/<suite>.json, where a rerun replaces the entries it measures again (same section,\n"
    "configuration and input) and keeps the rest. wavelet: the CIS 565 kernel sizes 3, 5, 7, 9\n"
    "(4 passes) beside a 9x9 Gaussian (radius 4, sigma 4/3) and a dense 9x9 edge-stopping\n"
    "filter (jbf radius 4, same sigma, no history). jbf: jbf (radius 16) and jbf-atrous (4\n"
    "levels) at the chart size; on gpu also at the iterations size, with 1 to 4 levels (for the\n"
    "target against svgf's iterations section) and the full window's cost a tap. bmfr: exact\n"
    "mode with --bmfr-rank noise and skip (gpu: fast noise too) at the chart size and on\n"
    "camera-pan (full coverage; cpu: at the chart size on 2 threads and all, beside svgf on 2\n"
    "threads; gpu: at the iterations size). The quality section measures all of them; gpu\n"
    "checks cpu exact == cuda exact for svgf, wavelet 5x5, jbf, jbf-atrous and bmfr (both\n"
    "strategies).\n"
    "  --out DIR             (default docs/bench)\n"
    "  --sections A,B        only these sections\n"
    "  --sizes A,B           sizes of the sizes section (default 256,720p,1080p,4k)\n"
    "  --chart-size S        size of the chart and baseline timings (default 720p)\n"
    "  --iterations-size S   size of the gpu iterations, coverage and blocks sections, of\n"
    "                        the jbf section's level study and bmfr's camera-pan (default\n"
    "                        1080p)\n"
    "  --fixtures DIR        fixture folders for the quality section (default fixtures)\n"
    "  --frames, --warmup, --scene, --distinct-frames, --cache as for run\n"
    "  --baseline-budget-s S time budget per baseline, CPU wavelet and CPU jbf timing, which\n"
    "                        also warm up 2 frames only (default 120)\n";

std::string usage() { return std::string(kUsageHead) + kMethodParamUsage + kUsageTail; }

std::vector<std::string> split_commas(const std::string& s) {
  std::vector<std::string> v;
  std::stringstream in(s);
  std::string item;
  while (std::getline(in, item, ','))
    if (!item.empty()) v.push_back(item);
  return v;
}

std::string default_fixtures() {
  if (fs::is_directory("fixtures")) return "fixtures";
  return std::string(SVGF_SOURCE_DIR) + "/fixtures";
}

std::string joined(int argc, char** argv) {
  std::string s = "svgf-bench";
  for (int i = 1; i < argc; ++i) s += std::string(" ") + argv[i];
  return s;
}

void parse_block(const std::string& s, int& x, int& y) {
  char extra = 0;
  if (std::sscanf(s.c_str(), "%dx%d%c", &x, &y, &extra) != 2 || x < 1 || y < 1)
    throw UsageError("--block must be WxH, got '" + s + "'");
}

svgf::bench::TimingOptions timing_from(const Options& o) {
  svgf::bench::TimingOptions t;
  t.frames = o.get_int("frames", t.frames, 1, 1 << 20);
  t.warmup = o.get_int("warmup", t.warmup, 0, 1 << 20);
  t.budget_s = o.get_float("budget-s", 0.f);
  return t;
}

int run_command(const std::vector<std::string>& args, const std::string& command) {
  using namespace svgf;
  using namespace svgf::app;
  using namespace svgf::bench;
  std::set<std::string> valued = {
      "method",          "backend", "mode",   "threads", "size",     "fixture", "scene",
      "distinct-frames", "cache",   "frames", "warmup",  "budget-s", "block",   "json"};
  valued.insert(method_param_flags().begin(), method_param_flags().end());
  const Options o(args, valued, {"quality", "no-ceilings", "help"});
  if (!o.positional().empty()) throw UsageError("unexpected argument '" + o.positional()[0] + "'");
  RunConfig c;
  try {
    c = run_config(o.get("method", "svgf"));
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  check_params_apply(o, c.method);
  read_method_params(o, c.denoiser);
  c.denoiser.backend = parse_backend(o.get("backend", "cpu"));
  c.denoiser.mode = parse_mode(o.get("mode", "exact"));
  c.denoiser.threads = o.get_int("threads", 0, 0, 1024);
  if (o.has("block")) parse_block(o.get("block", ""), c.denoiser.block_x, c.denoiser.block_y);
  if (!c.project() && c.denoiser.backend != Backend::Cpu)
    throw UsageError("the OpenCV baselines run on the CPU only");

  FrameSet frames;
  if (o.has("fixture")) {
    frames = load_fixture(o.get("fixture", ""));
  } else {
    int w = 0, h = 0;
    parse_size(o.get("size", "720p"), w, h);
    frames = generate_frames(o.get("scene", "cornell-moving"), w, h,
                             o.get_int("distinct-frames", 8, 1, 1000),
                             o.get("cache", SVGF_BENCH_CACHE_DIR));
  }

  json doc;
  doc["suite"] = "run";
  doc["command"] = command;
  const HostInfo host = query_host();
  doc["host"] = {{"cpu_model", host.cpu_model},
                 {"hardware_threads", host.hardware_threads},
                 {"load", host.load}};
  Ceilings ceilings;
  if (o.has("no-ceilings")) {
    // No measurement (e.g. under a profiler): bandwidth shares and floors print as 0.
  } else if (c.cuda()) {
    DeviceInfo d = query_device();
    measure_ceilings(d);
    ceilings.copy_gbs = d.memcpy_gbs;
    ceilings.ops_per_s = d.fp32_ops_per_s;
    ceilings.copy_what = "cudaMemcpyAsync device to device, 1 GiB";
    doc["device"] = {{"name", d.name},
                     {"sms", d.sms},
                     {"driver_version", d.driver_version},
                     {"memcpy_d2d_gbs", d.memcpy_gbs},
                     {"fp32_ops_per_s", d.fp32_ops_per_s}};
  } else {
    const int t = c.resolved_threads();
    ceilings.copy_gbs = host_copy_gbs(t);
    ceilings.ops_per_s = host_float_ops_per_s(t);
    ceilings.copy_what = "memcpy of 256 MiB on " + std::to_string(t) + " thread(s)";
  }
  json entry = time_run(c, frames, timing_from(o), ceilings);
  print_timing(entry, stdout);
  doc["timings"] = json::array({entry});
  doc["quality"] = json::array();
  if (o.has("quality")) {
    if (!frames.has_reference()) throw UsageError("--quality needs a --fixture with a reference");
    json q = quality_run(c, frames);
    print_quality(q, stdout);
    doc["quality"].push_back(q);
  }
  if (o.has("json")) {
    const std::string path = o.get("json", ""), text = doc.dump(1) + "\n";
    io::write_atomically(path, [&](const std::string& tmp) { std::ofstream(tmp) << text; });
    std::printf("wrote %s\n", path.c_str());
  }
  return 0;
}

int suite_command(const std::vector<std::string>& args, const std::string& command) {
  using namespace svgf::bench;
  const Options o(args,
                  {"out", "sections", "sizes", "chart-size", "iterations-size", "fixtures",
                   "frames", "warmup", "scene", "distinct-frames", "cache", "baseline-budget-s"},
                  {"help"});
  if (o.positional().size() != 1) throw UsageError("suite needs a name: cpu or gpu");
  SuiteOptions s;
  s.name = o.positional()[0];
  s.out_dir = o.get("out", "docs/bench");
  s.sections = split_commas(o.get("sections", ""));
  s.sizes = split_commas(o.get("sizes", ""));
  s.chart_size = o.get("chart-size", s.chart_size);
  s.iterations_size = o.get("iterations-size", "");
  s.fixtures_root = o.get("fixtures", default_fixtures());
  s.cache_dir = o.get("cache", SVGF_BENCH_CACHE_DIR);
  s.scene = o.get("scene", s.scene);
  s.distinct_frames = o.get_int("distinct-frames", s.distinct_frames, 1, 1000);
  s.timing = timing_from(o);
  s.baseline_budget_s = o.get_float("baseline-budget-s", static_cast<float>(s.baseline_budget_s));
  s.command = command;
  return run_suite(s);
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  const std::string command = joined(argc, argv);
  try {
    for (const std::string& a : args)
      if (a == "--help" || a == "-h") {
        std::fputs(usage().c_str(), stdout);
        return 0;
      }
    if (!args.empty() && args[0] == "suite")
      return suite_command({args.begin() + 1, args.end()}, command);
    if (!args.empty() && args[0] == "chart-data") {
      const Options o({args.begin() + 1, args.end()}, {"out", "targets"}, {});
      if (o.positional().size() != 1) throw UsageError("chart-data needs RESULTS_DIR");
      return svgf::bench::write_chart_data(o.positional()[0],
                                           o.get("out", o.positional()[0] + "/data"),
                                           o.get("targets", svgf::bench::default_targets_path()));
    }
    if (!args.empty() && args[0] == "run") args.erase(args.begin());
    return run_command(args, command);
  } catch (const UsageError& e) {
    std::fprintf(stderr, "svgf-bench: %s\n(svgf-bench --help lists the options)\n",
                 svgf::io::printable(e.what()).c_str());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "svgf-bench: %s\n", svgf::io::printable(e.what()).c_str());
    return 1;
  }
}

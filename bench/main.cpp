// svgf-bench: the benchmark binary (not a test). docs/benchmarks.md shows how its numbers are
// made and what they mean.
#include <array>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#ifdef __GLIBC__
#include <malloc.h>
#endif

#include "app/method_options.h"
#include "cli/command_line.h"
#include "bench/baselines.h"
#include "bench/chart_data.h"
#include "bench/eval_quality.h"
#include "bench/gpu_probe.h"
#include "bench/atrous_probe.h"
#include "bench/host_probe.h"
#include "bench/runner.h"
#include "bench/stability.h"
#include "bench/suites.h"
#include "bench/workload.h"
#include "io/atomic_file.h"
#include "io/printable.h"

namespace fs = std::filesystem;
using svgf::cli::UsageError;
using json = nlohmann::json;

namespace {

const char* const kRunFooter =
    "Times every stage of the method, by its own stage names (CUDA events on the GPU, a steady\n"
    "clock on the CPU) over --frames frames after --warmup frames, and prints per stage and per\n"
    "frame the median and p95, megapixels per second and the peak device memory; for the stages\n"
    "the cost model counts (bench/stage_cost.cpp: every svgf and bmfr stage, of a split svgf frame\n"
    "those it runs once, the filter stage of jbf, jbf-atrous and wavelet) also the bytes and\n"
    "operations the stage must move and do, the achieved bandwidth against the measured copy\n"
    "bandwidth, the share of the measured float rate, the floor and, for a filter's taps, the time\n"
    "a tap (other stages: n/a). The input line says whether the frames carry A-SVGF's gradient\n"
    "samples (rendered frames do). An svgf run then plays its frames once more from a reset\n"
    "history, untimed, to count the young histories (the variance's 7x7 estimate, in its floor).\n"
    "`svgf-bench [options]` without a subcommand is `svgf-bench run [options]`.";
const char* const kSuiteFooter =
    "cpu (sections sizes, chart, coverage, baselines, wavelet, jbf, bmfr, quality) or gpu\n"
    "(sizes, iterations, coverage, blocks, chart, wavelet, jbf, bmfr, quality); results go to\n"
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
    "strategies).";

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

// --frames, --warmup, --budget-s: run's and suite's.
void add_timing(CLI::App& app, svgf::bench::TimingOptions& t) {
  app.add_option("--frames", t.frames, "timed frames (default 100)")
      ->type_name("N")->check(CLI::Range(1, 1 << 20));
  app.add_option("--warmup", t.warmup, "untimed frames first (default 10)")
      ->type_name("N")->check(CLI::Range(0, 1 << 20));
  app.add_option("--budget-s", t.budget_s,
                 "stop timing after S seconds once 10 frames are timed (default none)")
      ->type_name("S")->check(CLI::Range(0.0, 1e9));
}

struct RunArgs {
  std::string method = "svgf", backend = "cpu", mode = "exact", size = "720p", fixture,
              scene = "cornell-moving", cache = SVGF_BENCH_CACHE_DIR, block, json;
  int threads = 0, distinct_frames = 8;
  bool quality = false, no_ceilings = false;
  svgf::bench::TimingOptions timing;
  svgf::app::MethodParamFlags params;
  std::string command;
};

int run_command(const RunArgs& a) {
  using namespace svgf;
  using namespace svgf::app;
  using namespace svgf::bench;
  RunConfig c;
  try {
    c = run_config(a.method);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  a.params.check_apply(c.method);
  a.params.read(c.denoiser);
  c.denoiser.backend = parse_backend(a.backend);
  c.denoiser.mode = parse_mode(a.mode);
  c.denoiser.threads = a.threads;
  if (!a.block.empty()) parse_block(a.block, c.denoiser.block_x, c.denoiser.block_y);
  if (!c.project() && c.denoiser.backend != Backend::Cpu)
    throw UsageError("the OpenCV baselines run on the CPU only");

  // Direct and indirect only for the run that asks to filter them apart.
  const bool split = c.project() && c.denoiser.method == Method::Svgf &&
                     c.denoiser.svgf.split == SplitMode::On;
  FrameSet frames;
  if (!a.fixture.empty()) {
    frames = load_fixture(a.fixture, 0, split);
  } else {
    int w = 0, h = 0;
    parse_size(a.size, w, h);
    frames = generate_frames(a.scene, w, h, a.distinct_frames, a.cache, split);
  }

  if (c.project() && c.denoiser.method == Method::Svgf &&
      c.denoiser.svgf.antilag == Antilag::Gradient && !frames.gradient_samples())
    std::fprintf(stderr,
                 "svgf-bench: the frames carry no gradient samples: --antilag gradient runs the "
                 "statistics rule\n");

  json doc;
  doc["suite"] = "run";
  doc["command"] = a.command;
  const HostInfo host = query_host();
  doc["host"] = {{"cpu_model", host.cpu_model},
                 {"hardware_threads", host.hardware_threads},
                 {"cpu_kernels", host.cpu_kernels},
                 {"load", host.load}};
  Ceilings ceilings;
  if (a.no_ceilings) {
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
    if (c.method == "svgf") {
      ceilings.resident_atrous_ns_per_tap = resident_atrous_ns_per_tap(t);
      ceilings.chain_ops_per_s = host_chain_ops_per_s(t);
    }
    ceilings.copy_what = "memcpy of 256 MiB on " + std::to_string(t) + " thread(s)";
  }
  json entry = time_run(c, frames, a.timing, ceilings);
  print_timing(entry, stdout);
  doc["timings"] = json::array({entry});
  doc["quality"] = json::array();
  if (a.quality) {
    if (!frames.has_reference()) throw UsageError("--quality needs a --fixture with a reference");
    json q = quality_run(c, frames);
    print_quality(q, stdout);
    doc["quality"].push_back(q);
  }
  if (!a.json.empty()) {
    const std::string text = doc.dump(1) + "\n";
    io::write_atomically(a.json, [&](const std::string& tmp) { std::ofstream(tmp) << text; });
    std::printf("wrote %s\n", a.json.c_str());
  }
  return 0;
}

void add_run(CLI::App& bench, const std::string& command, int& status) {
  auto a = std::make_shared<RunArgs>();
  a->command = command;
  CLI::App* run = bench.add_subcommand("run", "one configuration, timed (and measured); the default");
  run->footer(kRunFooter);
  run->add_option("--method", a->method,
                  "a project method, as `svgf denoise`: svgf (default), wavelet, gaussian, jbf, "
                  "jbf-atrous, bmfr; or an OpenCV baseline: (CPU) cv-gaussian, cv-bilateral, "
                  "cv-joint-bilateral, cv-nlmeans")
      ->type_name("M")
      ->check(svgf::cli::accepted_by(svgf::bench::run_config));
  run->add_option("--backend", a->backend, "(default cpu)")
      ->type_name("cpu|cuda")
      ->check(svgf::cli::accepted_by(svgf::parse_backend));
  run->add_option("--mode", a->mode, "fast exists on cuda only (default exact)")
      ->type_name("exact|fast")
      ->check(svgf::cli::accepted_by(svgf::parse_mode));
  run->add_option("--threads", a->threads, "CPU threads, 0 = all cores (default 0)")
      ->type_name("N")->check(CLI::Range(0, 1024));
  run->add_option("--size", a->size,
                  "generated frames: 720p, 1080p, 4k, N (square) or WxH (default 720p)")
      ->type_name("S");
  run->add_option("--fixture", a->fixture, "a fixture sequence instead of generated frames")
      ->type_name("DIR");
  run->add_option("--scene", a->scene, "scene rendered for --size (default cornell-moving)")
      ->type_name("NAME");
  run->add_option("--distinct-frames", a->distinct_frames,
                  "frames rendered for --size, played cyclically (default 8)")
      ->type_name("K")->check(CLI::Range(1, 1000));
  run->add_option("--cache", a->cache, "where rendered frames are kept between runs ('' = none)")
      ->type_name("DIR");
  add_timing(*run, a->timing);
  run->add_option("--block", a->block, "CUDA block shape (default 32x8)")->type_name("WxH");
  run->add_flag("--quality", a->quality,
                "with --fixture: per-frame PSNR, SSIM, relMSE, FLIP and temporal stability "
                "against the reference");
  run->add_option("--json", a->json, "write the results as JSON")->type_name("PATH");
  run->add_flag("--no-ceilings", a->no_ceilings,
                "skip measuring the copy bandwidth and float rate (for profilers)");
  a->params.add_to(*run);
  run->callback([a, &status] { status = run_command(*a); });
}

void add_suite(CLI::App& bench, const std::string& command, int& status) {
  auto s = std::make_shared<svgf::bench::SuiteOptions>();
  s->command = command;
  s->out_dir = "docs/bench";
  s->fixtures_root = default_fixtures();
  s->cache_dir = SVGF_BENCH_CACHE_DIR;
  auto lists = std::make_shared<std::pair<std::string, std::string>>();  // sections, sizes
  CLI::App* suite = bench.add_subcommand("suite", "the suites behind docs/benchmarks.md");
  suite->footer(kSuiteFooter);
  suite->add_option("NAME", s->name, "cpu or gpu")->required()->check(CLI::IsMember({"cpu", "gpu"}));
  suite->add_option("--out", s->out_dir, "(default docs/bench)")->type_name("DIR");
  suite->add_option("--sections", lists->first, "only these sections")->type_name("A,B");
  suite->add_option("--sizes", lists->second,
                    "sizes of the sizes section (default 256,720p,1080p,4k)")
      ->type_name("A,B");
  suite->add_option("--chart-size", s->chart_size,
                    "size of the chart and baseline timings (default 720p)")
      ->type_name("S");
  suite->add_option("--iterations-size", s->iterations_size,
                    "size of the gpu iterations, coverage and blocks sections, of the jbf "
                    "section's level study and bmfr's camera-pan (default 1080p)")
      ->type_name("S");
  suite->add_option("--fixtures", s->fixtures_root,
                    "fixture folders for the quality section (default fixtures)")
      ->type_name("DIR");
  add_timing(*suite, s->timing);
  suite->add_option("--scene", s->scene, "as for run")->type_name("NAME");
  suite->add_option("--distinct-frames", s->distinct_frames, "as for run")
      ->type_name("K")->check(CLI::Range(1, 1000));
  suite->add_option("--cache", s->cache_dir, "as for run")->type_name("DIR");
  suite->add_option("--baseline-budget-s", s->baseline_budget_s,
                    "time budget per baseline, CPU wavelet and CPU jbf timing, which also warm "
                    "up 2 frames only (default 120)")
      ->type_name("S")->check(CLI::Range(0.0, 1e9));
  suite->callback([s, lists, &status] {
    s->sections = split_commas(lists->first);
    s->sizes = split_commas(lists->second);
    status = svgf::bench::run_suite(*s);
  });
}

void add_eval_quality(CLI::App& bench, const std::string& command, int& status) {
  auto o = std::make_shared<svgf::bench::EvalQualityOptions>();
  o->command = command;
  o->out_file = "docs/bench/eval_quality.json";
  CLI::App* q = bench.add_subcommand(
      "quality", "every chart configuration's quality on the evaluation set (svgf-fixtures eval)");
  q->add_option("--set", o->set_dir, "the set's folder (one sequence folder per scene)")
      ->required()->type_name("DIR");
  q->add_option("--out", o->out_file, "(default docs/bench/eval_quality.json)")->type_name("FILE");
  q->add_option("--threads", o->threads, "CPU threads (default all)")->type_name("N")
      ->check(CLI::Range(0, 4096));
  q->callback([o, &status] { status = svgf::bench::run_eval_quality(*o); });
}

void add_chart_data(CLI::App& bench, int& status) {
  struct Args {
    std::string results, out, targets = svgf::bench::default_targets_path(), quality;
  };
  auto a = std::make_shared<Args>();
  CLI::App* chart = bench.add_subcommand(
      "chart-data", "tables for bench/chart.sh and summary.md, with each target's verdict");
  chart->add_option("RESULTS_DIR", a->results, "the suites' results")->required();
  chart->add_option("--out", a->out, "(default RESULTS_DIR/data)")->type_name("DIR");
  chart->add_option("--targets", a->targets,
                    "the targets (default: the source tree's bench/targets.json)")
      ->type_name("FILE");
  chart->add_option("--quality", a->quality,
                    "quality from `svgf-bench quality` (the evaluation set) in place of the suites'")
      ->type_name("FILE");
  chart->callback([a, &status] {
    status = svgf::bench::write_chart_data(a->results, a->out.empty() ? a->results + "/data" : a->out,
                                           a->targets, a->quality);
  });
}

void add_stability(CLI::App& bench, const std::string& command, int& status) {
  auto o = std::make_shared<svgf::bench::StabilityOptions>();
  auto a = std::make_shared<std::array<std::string, 3>>();  // backend, methods, scenarios
  (*a)[0] = "cpu";
  o->command = command;
  o->out_md = "docs/stability.md";
  o->fixtures_root = default_fixtures();
  o->cache_dir = SVGF_BENCH_CACHE_DIR;
  CLI::App* st = bench.add_subcommand(
      "stability", "issue 13's scenario suite: every method, thresholds, pass/fail (docs/stability.md)");
  st->footer(
      "Scenarios: moving-shadow, light-switch, static-convergence, camera-cut, disocclusion,\n"
      "flicker, fireflies, thin-edges, texture-detail. The reduced suite (the default) reads the\n"
      "committed fixtures and renders moving-shadow at 192x192 (8 frames, 64-sample references)\n"
      "and cornell-static at 64x64 (64 frames); --full renders them at 384x216 (16 frames, 256)\n"
      "and 128x128. Failed thresholds are findings: the exit status is 0 when the suite ran.");
  st->add_option("--out", o->out_md, "the page (default docs/stability.md; '' = none)")
      ->type_name("FILE");
  st->add_option("--json", o->out_json, "also the numbers as JSON")->type_name("FILE");
  st->add_flag("--full", o->full, "render the larger sequences (slow on a few cores)");
  st->add_option("--backend", (*a)[0], "(default cpu)")
      ->type_name("cpu|cuda")
      ->check(svgf::cli::accepted_by(svgf::parse_backend));
  st->add_option("--threads", o->threads, "CPU threads, 0 = all cores (default 0)")
      ->type_name("N")->check(CLI::Range(0, 1024));
  st->add_option("--cache", o->cache_dir, "where rendered sequences are kept ('' = none)")
      ->type_name("DIR");
  st->add_option("--fixtures", o->fixtures_root, "the committed fixtures (default fixtures)")
      ->type_name("DIR");
  st->add_option("--methods", (*a)[1], "only these methods (names as in the tables)")
      ->type_name("A,B");
  st->add_option("--scenarios", (*a)[2], "only these scenarios")->type_name("A,B");
  st->callback([o, a, &status] {
    o->backend = svgf::parse_backend((*a)[0]);
    o->methods = split_commas((*a)[1]);
    o->scenarios = split_commas((*a)[2]);
    if (o->full) o->sizes = svgf::bench::full_sizes();
    try {
      svgf::bench::check_stability_options(*o);
    } catch (const std::invalid_argument& e) {
      throw UsageError(e.what());
    }
    status = svgf::bench::stability_command(*o);
  });
}

}  // namespace

int main(int argc, char** argv) {
#ifdef __GLIBC__
  // Per-frame planes (~1 MB each at 640x360) would otherwise be mmap'ed and page-faulted anew
  // every frame; keep them on the heap and keep freed memory.
  mallopt(M_MMAP_THRESHOLD, 256 << 20);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
#endif
  CLI::App bench("svgf-bench: the benchmark binary (docs/benchmarks.md). Without a subcommand the "
                 "options are run's: svgf-bench --size 64x64 is svgf-bench run --size 64x64.",
                 "svgf-bench");
  svgf::cli::style(bench);
  bench.require_subcommand(1);
  int status = 0;
  const std::string command = joined(argc, argv);
  add_run(bench, command, status);
  add_suite(bench, command, status);
  add_chart_data(bench, status);
  add_eval_quality(bench, command, status);
  add_stability(bench, command, status);
  // Without a subcommand (`svgf-bench --size 64x64 ...`) the options are run's.
  std::vector<char*> args(argv, argv + argc);
  std::string run = "run";
  if (argc == 1 || (argv[1][0] == '-' && std::string(argv[1]) != "--help" &&
                    std::string(argv[1]) != "-h"))
    args.insert(args.begin() + 1, run.data());
  return svgf::cli::run_main(bench, static_cast<int>(args.size()), args.data(),
                             [&] { return status; });
}

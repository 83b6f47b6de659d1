#include "bench/suites.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>
#include <thread>

#include "bench/gpu_probe.h"
#include "bench/atrous_probe.h"
#include "bench/host_probe.h"
#include "io/atomic_file.h"

namespace fs = std::filesystem;

namespace svgf::bench {
namespace {

using json = nlohmann::json;


// A scene whose every pixel has a surface, to check the default scene's timings (whose frames are
// 44% background at 16:9) against full coverage.
const char* const kFullCoverageScene = "camera-pan";
// The coverage sections time SVGF's defaults there (the targets' configuration, issues 14 and
// 17) over 20 distinct frames: with the default 8, the loop's wrap jumps the camera back seven
// frames and leaves many pixels young in three frames of the eight, so the median is not a
// steady frame (docs/benchmarks.md, "The young pixels' variance").
constexpr int kCoverageDistinctFrames = 20;

// The chart's SVGF configurations: iterations 1..6 with the default feedback tap (the first
// iteration when there is only one), then every other tap at the default 4 iterations.
std::vector<std::pair<int, int>> chart_params() {
  std::vector<std::pair<int, int>> v;
  for (int it = 1; it <= 6; ++it) v.push_back({it, it == 1 ? 0 : 1});
  for (int tap : {-1, 0, 2, 3}) v.push_back({4, tap});
  return v;
}

// The CIS 565 kernel-size study: the wavelet filter at its defaults (4 passes) with each size.
constexpr int kWaveletKernelSizes[] = {3, 5, 7, 9};
// Its 9x9 comparisons: the Gaussian blur at radius 4 = 3 sigma (the project's radius rule; the
// blur is separable, two passes of 9 taps), and a dense single-pass 9x9 Gaussian that stops at
// edges, the JBF's full window of radius 4 with that sigma and no history (alpha 1), a single-
// frame filter like the wavelet.
constexpr float kStudySigma = 4.f / 3.f;
constexpr int kStudyRadius = 4;

std::vector<RunConfig> study_configs(Backend backend, Mode mode, int threads) {
  std::vector<RunConfig> v;
  for (int k : kWaveletKernelSizes) v.push_back(wavelet_config(backend, mode, k, threads));
  v.push_back(gaussian_config(backend, mode, kStudySigma, kStudyRadius, threads));
  RunConfig dense = jbf_config(backend, mode, 0, threads);
  dense.denoiser.jbf.radius = kStudyRadius;
  dense.denoiser.jbf.sigma_coord = kStudySigma;
  dense.denoiser.jbf.alpha = 1.f;
  v.push_back(dense);
  return v;
}

// The JBF's two forms at their defaults: the full window (radius 16) and 4 a-trous levels; the
// GPU target compares the a-trous form at 1 to 4 levels with SVGF at as many iterations.
constexpr int kJbfLevels[] = {1, 2, 3, 4};
constexpr int kJbfDefaultLevels = 4;
std::vector<RunConfig> jbf_configs(Backend backend, Mode mode, int threads) {
  return {jbf_config(backend, mode, 0, threads),
          jbf_config(backend, mode, kJbfDefaultLevels, threads)};
}

// BMFR (issue 11): exact mode with each rank-deficiency strategy (noise, the paper's, and skip),
// on the GPU also fast mode with noise.
std::vector<RunConfig> bmfr_configs(Backend backend, int threads) {
  std::vector<RunConfig> v = {bmfr_config(backend, Mode::Exact, BmfrRankStrategy::Noise, threads),
                              bmfr_config(backend, Mode::Exact, BmfrRankStrategy::Skip, threads)};
  if (backend == Backend::Cuda)
    v.push_back(bmfr_config(backend, Mode::Fast, BmfrRankStrategy::Noise, threads));
  return v;
}
// The CPU target: BMFR at most 1.5x SVGF's frame time on 2 cores.
constexpr int kBmfrTargetThreads = 2;

bool same_size(const std::string& a, const std::string& b) {
  int aw = 0, ah = 0, bw = 0, bh = 0;
  parse_size(a, aw, ah);
  parse_size(b, bw, bh);
  return aw == bw && ah == bh;
}

// A single-frame filter's timing on a slow machine: the baselines' time budget, and a short
// warm-up (there is no history to fill, only caches and allocations).
TimingOptions budgeted(const SuiteOptions& o) {
  TimingOptions t = o.timing;
  t.budget_s = o.baseline_budget_s;
  t.warmup = std::min(t.warmup, 2);
  return t;
}

bool wanted(const SuiteOptions& o, const std::string& section) {
  return o.sections.empty() ||
         std::find(o.sections.begin(), o.sections.end(), section) != o.sections.end();
}

class SuiteWriter {
 public:
  SuiteWriter(const SuiteOptions& o, const std::vector<std::string>& sections) {
    fs::create_directories(o.out_dir);
    path_ = (fs::path(o.out_dir) / (o.name + ".json")).string();
    if (fs::exists(path_)) {  // a rerun replaces the entries it measures again, keeps the rest
      std::ifstream in(path_);
      doc_ = json::parse(in, nullptr, false);
      if (doc_.is_discarded() || doc_.value("suite", "") != o.name) doc_ = json::object();
    }
    for (const char* list : {"timings", "quality", "checks"})
      if (!doc_.contains(list)) doc_[list] = json::array();
    doc_["suite"] = o.name;
    doc_["command"] = o.command;
    if (!doc_.contains("sections")) doc_["sections"] = json::object();
    for (const std::string& s : sections)
      doc_["sections"][s] = {{"started", now_iso()}, {"command", o.command}};
  }
  json& doc() { return doc_; }
  void add(const char* list, const std::string& group, json entry) {
    entry["group"] = group;
    json& v = doc_[list];
    for (size_t i = 0; i < v.size(); ++i)
      if (same_measurement(v[i], entry)) {
        v.erase(i);
        break;
      }
    v.push_back(std::move(entry));
    save();
  }
  void finish_section(const std::string& s) {
    doc_["sections"][s]["finished"] = now_iso();
    save();
  }
  void save() {
    const std::string text = doc_.dump(1) + "\n";
    io::write_atomically(path_, [&](const std::string& tmp) { std::ofstream(tmp) << text; });
  }
  const std::string& path() const { return path_; }

 private:
  // The same group and configuration on the same input (size, or fixture scene), or the same
  // check.
  static bool same_measurement(const json& a, const json& b) {
    if (a.value("group", "") != b.value("group", "") ||
        a.value("label", "") != b.value("label", "") || a.value("name", "") != b.value("name", ""))
      return false;
    if (a.contains("scene") || b.contains("scene"))
      return a.value("scene", "") == b.value("scene", "");
    if (a.contains("input") && b.contains("input"))
      return a["input"]["width"] == b["input"]["width"] &&
             a["input"]["height"] == b["input"]["height"] &&
             a["input"]["scene"] == b["input"]["scene"];
    return true;
  }
  std::string path_;
  json doc_;
};

json device_json(const DeviceInfo& d) {
  if (!d.present) return {{"present", false}, {"why_absent", d.why_absent}};
  return {{"present", true},
          {"name", d.name},
          {"driver_version", d.driver_version},
          {"runtime_version", d.runtime_version},
          {"compute_capability",
           std::to_string(d.compute_major) + "." + std::to_string(d.compute_minor)},
          {"sms", d.sms},
          {"clock_mhz", d.clock_khz / 1000.0},
          {"memory_clock_mhz", d.memory_clock_khz / 1000.0},
          {"memory_bus_bits", d.memory_bus_bits},
          {"l2_bytes", d.l2_bytes},
          {"memory_bytes", d.memory_bytes},
          {"memcpy_d2d_gbs", d.memcpy_gbs},
          {"copy_kernel_gbs", d.copy_kernel_gbs},
          {"fp32_ops_per_s", d.fp32_ops_per_s}};
}


std::vector<std::string> sizes_of(const SuiteOptions& o) {
  return o.sizes.empty() ? std::vector<std::string>{"256", "720p", "1080p", "4k"} : o.sizes;
}

// Frame sets by size, rendered (or read from the cache) once per suite.
class FrameCache {
 public:
  explicit FrameCache(const SuiteOptions& o) : o_(o) {}
  const FrameSet& get(const std::string& size) {
    auto it = sets_.find(size);
    if (it != sets_.end()) return it->second;
    int w = 0, h = 0;
    parse_size(size, w, h);
    std::fprintf(stderr, "svgf-bench: frames for %s (%dx%d)\n", size.c_str(), w, h);
    return sets_[size] = generate_frames(o_.scene, w, h, o_.distinct_frames, o_.cache_dir);
  }
  void drop(const std::string& size) { sets_.erase(size); }

 private:
  const SuiteOptions& o_;
  std::map<std::string, FrameSet> sets_;
};

// A failing configuration is recorded and the suite goes on: one run on a lent GPU has to
// bring back everything that did work.
json failure(const RunConfig& c, const std::string& what, const std::exception& e) {
  std::fprintf(stderr, "svgf-bench: %s %s failed: %s\n", c.label().c_str(), what.c_str(), e.what());
  return {{"label", c.label()}, {"key", c.key()}, {"config", config_json(c)}, {"error", e.what()}};
}

void timed(SuiteWriter& w, const std::string& group, const RunConfig& c, const FrameSet& fs,
           const TimingOptions& t, const Ceilings& ceilings) {
  json e;
  try {
    e = time_run(c, fs, t, ceilings);
    print_timing(e, stdout);
  } catch (const std::exception& ex) {
    e = failure(c, "timing at " + std::to_string(fs.width) + "x" + std::to_string(fs.height), ex);
    e["input"] = {{"width", fs.width}, {"height", fs.height}, {"scene", fs.scene}};
  }
  w.add("timings", group, std::move(e));
}

void quality_all(SuiteWriter& w, const std::vector<RunConfig>& configs,
                 const std::vector<FrameSet>& fixtures) {
  for (const RunConfig& c : configs)
    for (const FrameSet& f : fixtures) {
      json e;
      try {
        e = quality_run(c, f);
        print_quality(e, stdout);
      } catch (const std::exception& ex) {
        e = failure(c, "quality on " + f.scene, ex);
        e["scene"] = f.scene;
      }
      w.add("quality", "quality", std::move(e));
    }
}

std::vector<FrameSet> load_fixtures(const SuiteOptions& o) {
  std::vector<FrameSet> sets;
  for (const std::string& dir : fixture_dirs(o.fixtures_root)) {
    FrameSet f = load_fixture(dir);
    if (f.has_reference()) sets.push_back(std::move(f));
  }
  if (sets.empty())
    std::fprintf(stderr, "svgf-bench: no fixtures with a reference under %s: quality skipped\n",
                 o.fixtures_root.c_str());
  return sets;
}

// Exact mode's promise, checked on the fixtures: the CUDA output of `cpu` (a CPU exact
// configuration) on the GPU has the CPU's bits. `what` names the configuration in the check.
json bitwise_check(const std::vector<FrameSet>& fixtures, const RunConfig& cpu_config,
                   const std::string& what) {
  json j = {{"name", "cpu exact == cuda exact (" + what + ", every fixture frame)"}};
  size_t values = 0, differing = 0;
  DenoiserConfig cuda_config = cpu_config.denoiser;
  cuda_config.backend = Backend::Cuda;
  for (const FrameSet& f : fixtures) {
    auto cpu = make_denoiser(cpu_config.denoiser);
    auto gpu = make_denoiser(cuda_config);
    Image a, b;
    for (int k = 0; k < static_cast<int>(f.frames.size()); ++k) {
      if (f.is_cut(k)) {
        cpu->reset();
        gpu->reset();
      }
      cpu->denoise(f.frames[static_cast<size_t>(k)], a);
      gpu->denoise(f.frames[static_cast<size_t>(k)], b);
      for (size_t i = 0; i < a.data().size(); ++i) {
        uint32_t x, y;
        std::memcpy(&x, &a.data()[i], 4);
        std::memcpy(&y, &b.data()[i], 4);
        differing += x != y;
      }
      values += a.data().size();
    }
  }
  j["values"] = values;
  j["differing"] = differing;
  j["equal"] = differing == 0;
  std::printf("\ncheck: %s: %zu of %zu values differ\n", j["name"].get<std::string>().c_str(),
              differing, values);
  return j;
}

int run_cpu_suite(const SuiteOptions& o, SuiteWriter& w) {
  const HostInfo host = query_host();
  w.doc()["host"] = host_json(host);
  const int all = std::max(1, host.hardware_threads);
  std::vector<int> threads = {1};
  if (all > 1) threads.push_back(all);
  std::map<int, Ceilings> ceilings;
  w.doc()["ceilings"] = json::object();
  // The ceilings of t threads, measured the first time they are needed.
  const auto ceilings_of = [&](int t) -> const Ceilings& {
    if (ceilings.count(t)) return ceilings[t];
    Ceilings c;
    c.copy_gbs = host_copy_gbs(t);
    c.ops_per_s = host_float_ops_per_s(t);
    c.resident_atrous_ns_per_tap = resident_atrous_ns_per_tap(t);
    c.chain_ops_per_s = host_chain_ops_per_s(t);
    c.copy_what = "memcpy of 256 MiB on " + std::to_string(t) + " thread(s)";
    w.doc()["ceilings"][std::to_string(t)] = {
        {"copy_gbs", c.copy_gbs},
        {"ops_per_s", c.ops_per_s},
        {"resident_atrous_ns_per_tap", c.resident_atrous_ns_per_tap},
        {"chain_ops_per_s", chain_json(c.chain_ops_per_s)}};
    w.save();
    std::printf("host ceilings, %d thread(s): copy %.1f GB/s, float ops %.2f G/s\n", t, c.copy_gbs,
                c.ops_per_s / 1e9);
    return ceilings[t] = c;
  };
  for (int t : threads) ceilings_of(t);
  FrameCache frames(o);

  if (wanted(o, "sizes")) {
    for (const std::string& size : sizes_of(o)) {
      for (int t : threads)
        timed(w, "sizes", svgf_config(Backend::Cpu, Mode::Exact, 4, 1, t), frames.get(size),
              o.timing, ceilings[t]);
      if (size != o.chart_size) frames.drop(size);  // 4K frame sets are large
    }
    w.finish_section("sizes");
  }
  if (wanted(o, "chart")) {
    for (auto [it, tap] : chart_params())
      timed(w, "chart", svgf_config(Backend::Cpu, Mode::Exact, it, tap, all),
            frames.get(o.chart_size), o.timing, ceilings[all]);
    for (const RunConfig& c : svgf_preset_configs(Backend::Cpu, Mode::Exact, all))
      timed(w, "chart", c, frames.get(o.chart_size), o.timing, ceilings[all]);
    w.finish_section("chart");
  }
  if (wanted(o, "coverage")) {  // every pixel a surface: camera-pan's closed room
    const FrameSet room =
        generate_frames(kFullCoverageScene, frames.get(o.chart_size).width,
                        frames.get(o.chart_size).height, kCoverageDistinctFrames, o.cache_dir);
    for (int t : threads)
      timed(w, "coverage", project_config("svgf", Backend::Cpu, Mode::Exact, t), room, o.timing,
            ceilings[t]);
    w.finish_section("coverage");
  }
  if (wanted(o, "baselines") && baselines_available()) {
    for (const Baseline& b : default_baselines())
      timed(w, "baselines", baseline_config(b, all), frames.get(o.chart_size), budgeted(o),
            ceilings[all]);
    w.finish_section("baselines");
  }
  if (wanted(o, "wavelet")) {
    for (const RunConfig& c : study_configs(Backend::Cpu, Mode::Exact, all))
      timed(w, "wavelet", c, frames.get(o.chart_size), budgeted(o), ceilings[all]);
    w.finish_section("wavelet");
  }
  if (wanted(o, "jbf")) {
    for (const RunConfig& c : jbf_configs(Backend::Cpu, Mode::Exact, all))
      timed(w, "jbf", c, frames.get(o.chart_size), budgeted(o), ceilings[all]);
    w.finish_section("jbf");
  }
  if (wanted(o, "bmfr")) {
    for (const RunConfig& c : bmfr_configs(Backend::Cpu, all))
      timed(w, "bmfr", c, frames.get(o.chart_size), o.timing, ceilings[all]);
    // The CPU target at full coverage: BMFR on 2 threads and on all, beside SVGF (4 iterations,
    // feedback tap 1: the key bench/targets.json divides by; the defaults before issue 12) on 2
    // threads timed in the same sitting (the ratio's two times from one load situation).
    const FrameSet room =
        generate_frames(kFullCoverageScene, frames.get(o.chart_size).width,
                        frames.get(o.chart_size).height, o.distinct_frames, o.cache_dir);
    std::vector<int> room_threads = {kBmfrTargetThreads};
    if (all != kBmfrTargetThreads) room_threads.push_back(all);
    for (int t : room_threads)
      timed(w, "bmfr", bmfr_config(Backend::Cpu, Mode::Exact, BmfrRankStrategy::Noise, t), room,
            o.timing, ceilings_of(t));
    timed(w, "bmfr", svgf_config(Backend::Cpu, Mode::Exact, 4, 1, kBmfrTargetThreads), room,
          o.timing, ceilings_of(kBmfrTargetThreads));
    w.finish_section("bmfr");
  }
  if (wanted(o, "quality")) {
    const std::vector<FrameSet> fixtures = load_fixtures(o);
    quality_all(w, quality_configs(all), fixtures);
    w.finish_section("quality");
  }
  return 0;
}

int run_gpu_suite(const SuiteOptions& o, SuiteWriter& w) {
  w.doc()["host"] = host_json(query_host());
  DeviceInfo dev = query_device();
  if (!dev.present) throw std::runtime_error("suite gpu: no CUDA device (" + dev.why_absent + ")");
  std::string why;
  if (!cuda_available(&why)) throw std::runtime_error("suite gpu: " + why);
  measure_ceilings(dev);
  w.doc()["device"] = device_json(dev);
  w.save();
  std::printf(
      "device %s, %d SMs, driver %d: memcpy D2D %.0f GB/s, copy kernel %.0f GB/s, FP32 "
      "%.1f Tops/s\n",
      dev.name.c_str(), dev.sms, dev.driver_version, dev.memcpy_gbs, dev.copy_kernel_gbs,
      dev.fp32_ops_per_s / 1e12);
  Ceilings ceilings;
  ceilings.copy_gbs = dev.memcpy_gbs;
  ceilings.ops_per_s = dev.fp32_ops_per_s;
  ceilings.copy_what = "cudaMemcpyAsync device to device, 1 GiB";
  FrameCache frames(o);
  const std::string it_size = o.iterations_size.empty() ? "1080p" : o.iterations_size;

  if (wanted(o, "sizes")) {
    for (const std::string& size : sizes_of(o)) {
      for (Mode m : {Mode::Exact, Mode::Fast})
        timed(w, "sizes", svgf_config(Backend::Cuda, m, 4, 1, 0), frames.get(size), o.timing,
              ceilings);
      if (size != o.chart_size && size != it_size) frames.drop(size);
    }
    w.finish_section("sizes");
  }
  if (wanted(o, "iterations")) {
    for (Mode m : {Mode::Exact, Mode::Fast})
      for (int it = 1; it <= 6; ++it)
        timed(w, "iterations", svgf_config(Backend::Cuda, m, it, it == 1 ? 0 : 1, 0),
              frames.get(it_size), o.timing, ceilings);
    w.finish_section("iterations");
  }
  if (wanted(o, "coverage")) {  // every pixel a surface: camera-pan's closed room
    int cw = 0, ch = 0;
    parse_size(it_size, cw, ch);
    const FrameSet room =
        generate_frames(kFullCoverageScene, cw, ch, kCoverageDistinctFrames, o.cache_dir);
    for (Mode m : {Mode::Exact, Mode::Fast})
      timed(w, "coverage", project_config("svgf", Backend::Cuda, m, 0), room, o.timing, ceilings);
    w.finish_section("coverage");
  }
  if (wanted(o, "blocks")) {  // launch shapes other than the default 32x8, at the same size
    for (Mode m : {Mode::Exact, Mode::Fast})
      for (const auto& [bx, by] :
           std::vector<std::pair<int, int>>{{16, 8}, {32, 4}, {16, 16}, {64, 2}, {128, 1}}) {
        RunConfig c = svgf_config(Backend::Cuda, m, 4, 1, 0);
        c.denoiser.block_x = bx;
        c.denoiser.block_y = by;
        timed(w, "blocks", c, frames.get(it_size), o.timing, ceilings);
      }
    w.finish_section("blocks");
  }
  if (wanted(o, "chart")) {
    for (Mode m : {Mode::Exact, Mode::Fast}) {
      for (auto [it, tap] : chart_params())
        timed(w, "chart", svgf_config(Backend::Cuda, m, it, tap, 0), frames.get(o.chart_size),
              o.timing, ceilings);
      for (const RunConfig& c : svgf_preset_configs(Backend::Cuda, m, 0))
        timed(w, "chart", c, frames.get(o.chart_size), o.timing, ceilings);
    }
    w.finish_section("chart");
  }
  if (wanted(o, "wavelet")) {
    for (Mode m : {Mode::Exact, Mode::Fast})
      for (const RunConfig& c : study_configs(Backend::Cuda, m, 0))
        timed(w, "wavelet", c, frames.get(o.chart_size), o.timing, ceilings);
    w.finish_section("wavelet");
  }
  if (wanted(o, "jbf")) {
    for (Mode m : {Mode::Exact, Mode::Fast}) {
      for (const RunConfig& c : jbf_configs(Backend::Cuda, m, 0))
        timed(w, "jbf", c, frames.get(o.chart_size), o.timing, ceilings);
      // At the iterations section's size: the full window's per-tap cost, and the a-trous
      // levels beside SVGF's iterations there (the default levels again only at another size).
      const bool other_size = !same_size(it_size, o.chart_size);
      if (other_size)
        timed(w, "jbf", jbf_config(Backend::Cuda, m, 0, 0), frames.get(it_size), o.timing,
              ceilings);
      for (int levels : kJbfLevels)
        if (other_size || levels != kJbfDefaultLevels)
          timed(w, "jbf", jbf_config(Backend::Cuda, m, levels, 0), frames.get(it_size), o.timing,
                ceilings);
    }
    w.finish_section("jbf");
  }
  if (wanted(o, "bmfr")) {
    // At the chart size, and at the iterations size at full coverage (the targets:
    // fast mode at 1080p, exact mode against its floor).
    int cw = 0, ch = 0;
    parse_size(it_size, cw, ch);
    const FrameSet room =
        generate_frames(kFullCoverageScene, cw, ch, o.distinct_frames, o.cache_dir);
    for (const RunConfig& c : bmfr_configs(Backend::Cuda, 0)) {
      timed(w, "bmfr", c, frames.get(o.chart_size), o.timing, ceilings);
      timed(w, "bmfr", c, room, o.timing, ceilings);
    }
    w.finish_section("bmfr");
  }
  if (wanted(o, "quality")) {
    const std::vector<FrameSet> fixtures = load_fixtures(o);
    if (!fixtures.empty()) {
      const std::pair<RunConfig, const char*> checks[] = {
          {svgf_config(Backend::Cpu, Mode::Exact, 4, 1, 0), "it4 tap1"},
          {wavelet_config(Backend::Cpu, Mode::Exact, 5, 0), "wavelet it4 k5"},
          {jbf_config(Backend::Cpu, Mode::Exact, 0, 0), "jbf r16"},
          {jbf_config(Backend::Cpu, Mode::Exact, kJbfDefaultLevels, 0), "jbf-atrous l4"},
          {bmfr_config(Backend::Cpu, Mode::Exact, BmfrRankStrategy::Noise, 0), "bmfr noise"},
          {bmfr_config(Backend::Cpu, Mode::Exact, BmfrRankStrategy::Skip, 0), "bmfr skip"}};
      for (const auto& [config, what] : checks) try {
          w.add("checks", "quality", bitwise_check(fixtures, config, what));
        } catch (const std::exception& e) {
          std::fprintf(stderr, "svgf-bench: bitwise check (%s) failed: %s\n", what, e.what());
        }
      std::vector<RunConfig> configs;
      for (Mode m : {Mode::Exact, Mode::Fast}) {
        for (auto [it, tap] : chart_params())
          configs.push_back(svgf_config(Backend::Cuda, m, it, tap, 0));
        for (const RunConfig& c : svgf_preset_configs(Backend::Cuda, m, 0)) configs.push_back(c);
        for (const RunConfig& c : study_configs(Backend::Cuda, m, 0)) configs.push_back(c);
        for (const RunConfig& c : jbf_configs(Backend::Cuda, m, 0)) configs.push_back(c);
      }
      for (const RunConfig& c : bmfr_configs(Backend::Cuda, 0)) configs.push_back(c);
      quality_all(w, configs, fixtures);
    }
    w.finish_section("quality");
  }
  return 0;
}

}  // namespace

std::vector<RunConfig> quality_configs(int threads) {
  std::vector<RunConfig> configs;
  RunConfig noisy;
  noisy.method = "noisy";
  configs.push_back(noisy);
  for (auto [it, tap] : chart_params())
    configs.push_back(svgf_config(Backend::Cpu, Mode::Exact, it, tap, threads));
  for (const RunConfig& c : svgf_preset_configs(Backend::Cpu, Mode::Exact, threads))
    configs.push_back(c);
  for (const RunConfig& c : study_configs(Backend::Cpu, Mode::Exact, threads)) configs.push_back(c);
  for (const RunConfig& c : jbf_configs(Backend::Cpu, Mode::Exact, threads)) configs.push_back(c);
  for (const RunConfig& c : bmfr_configs(Backend::Cpu, threads)) configs.push_back(c);
  if (baselines_available())
    for (const Baseline& b : default_baselines()) configs.push_back(baseline_config(b, threads));
  return configs;
}

std::string now_iso() {
  const std::time_t t = std::time(nullptr);
  char buf[64];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

json host_json(const HostInfo& h) {
  return {{"cpu_model", h.cpu_model},
          {"hardware_threads", h.hardware_threads},
          {"hostname", h.hostname},
          {"cpu_kernels", h.cpu_kernels},
          {"load", h.load}};
}

std::vector<std::string> suite_sections(const std::string& name) {
  if (name == "cpu")
    return {"sizes", "chart", "coverage", "baselines", "wavelet", "jbf", "bmfr", "quality"};
  if (name == "gpu")
    return {"sizes", "iterations", "coverage", "blocks", "chart",
            "wavelet", "jbf", "bmfr", "quality"};
  throw std::invalid_argument("unknown suite '" + name + "' (known: cpu, gpu)");
}

int run_suite(const SuiteOptions& o) {
  const std::vector<std::string> all = suite_sections(o.name);
  for (const std::string& s : o.sections)
    if (std::find(all.begin(), all.end(), s) == all.end())
      throw std::invalid_argument("suite " + o.name + " has no section '" + s + "'");
  SuiteWriter w(o, o.sections.empty() ? all : o.sections);
  int cw = 0, ch = 0;
  parse_size(o.chart_size, cw, ch);
  // The chart reads its points at this size and scene (other sections time some methods at
  // more sizes, and BMFR's on the full-coverage scene too).
  w.doc()["chart_size"] = std::to_string(cw) + "x" + std::to_string(ch);
  w.doc()["chart_scene"] = o.scene;
  const int rc = o.name == "cpu" ? run_cpu_suite(o, w) : run_gpu_suite(o, w);
  w.doc()["finished"] = now_iso();
  w.save();
  std::printf("\nwrote %s\n", w.path().c_str());
  return rc;
}

}  // namespace svgf::bench

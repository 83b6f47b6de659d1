#include "bench/chart_data.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "bench/stage_cost.h"

namespace fs = std::filesystem;

namespace svgf::bench {
namespace {

using json = nlohmann::json;

const char* const kDefaultCpu = "svgf cpu exact it4 tap1";
const char* const kDefaultExact = "svgf cuda exact it4 tap1";
const char* const kDefaultFast = "svgf cuda fast it4 tap1";
const char* const kStaticScene = "cornell-static";

std::string fmt(double v, int digits) {
  if (!std::isfinite(v)) return "-";
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(digits);
  s << v;
  return s.str();
}

double num(const json& v) { return v.is_number() ? v.get<double>() : std::nan(""); }

std::string underscores(std::string s) {
  for (char& c : s)
    if (c == ' ') c = '_';
  return s;
}

struct Results {
  std::map<std::string, json> suites;  // by suite name
  const json* suite(const std::string& name) const {
    auto it = suites.find(name);
    return it == suites.end() ? nullptr : &it->second;
  }
  // Timing entries of a suite's group, in file order.
  std::vector<const json*> timings(const std::string& suite_name, const std::string& group) const {
    std::vector<const json*> v;
    if (const json* s = suite(suite_name))
      for (const json& e : (*s)["timings"])
        if (e.value("group", "") == group && !e.contains("error")) v.push_back(&e);
    return v;
  }
  const json* timing(const std::string& suite_name, const std::string& group,
                     const std::string& key) const {
    for (const json* e : timings(suite_name, group))
      if ((*e)["key"] == key) return e;
    return nullptr;
  }
  // Per-scene quality means of `key`, from the first suite that has it.
  std::map<std::string, json> quality(const std::string& key) const {
    std::map<std::string, json> by_scene;
    for (const char* s : {"gpu", "cpu"})
      if (const json* doc = suite(s))
        for (const json& e : (*doc)["quality"])
          if (e["key"] == key && !e.contains("error") &&
              !by_scene.count(e["scene"].get<std::string>()))
            by_scene[e["scene"].get<std::string>()] = e;
    return by_scene;
  }
};

// Mean over scenes of each scene's mean; output change on the static scene alone.
struct Quality {
  double psnr = NAN, flip = NAN, ssim = NAN, relmse = NAN, error_change = NAN,
         static_output_change = NAN;
  int scenes = 0;
};

Quality aggregate(const std::map<std::string, json>& by_scene) {
  Quality q;
  if (by_scene.empty()) return q;
  double s[5] = {0, 0, 0, 0, 0};
  int n[5] = {0, 0, 0, 0, 0};
  for (const auto& [scene, e] : by_scene) {
    const json& m = e["mean"];
    const double v[5] = {num(m["psnr"]), num(m["flip"]), num(m["ssim"]), num(m["relmse"]),
                         num(m["error_change"])};
    for (int i = 0; i < 5; ++i)
      if (std::isfinite(v[i])) {
        s[i] += v[i];
        ++n[i];
      }
    if (scene == kStaticScene) q.static_output_change = num(m["output_change"]);
  }
  auto mean = [&](int i) { return n[i] ? s[i] / n[i] : NAN; };
  q.psnr = mean(0);
  q.flip = mean(1);
  q.ssim = mean(2);
  q.relmse = mean(3);
  q.error_change = mean(4);
  q.scenes = static_cast<int>(by_scene.size());
  return q;
}

struct Point {
  std::string series, key, label;
  double time_ms = NAN, p95_ms = NAN;
  Quality q;
  std::string size;
  bool pareto_psnr = false, pareto_flip = false;
};

std::string short_label(const std::string& key) {
  if (key.rfind("svgf ", 0) == 0) {
    const size_t it = key.find(" it");
    return key.substr(it + 1);
  }
  return key;
}

std::string size_of(const json& e) {
  return std::to_string(e["input"]["width"].get<int>()) + "x" +
         std::to_string(e["input"]["height"].get<int>());
}

// "gpu" for the CUDA series, "cpu" for the CPU SVGF and the OpenCV baselines.
std::string platform(const Point& p) { return p.series.rfind("cuda", 0) == 0 ? "gpu" : "cpu"; }

std::vector<Point> chart_points(const Results& r) {
  std::vector<Point> pts;
  // `mode`: only entries of this mode (exact, fast), or any when empty.
  auto add = [&](const std::string& series, const std::string& suite, const std::string& group,
                 const std::string& mode, const std::string& quality_fallback_from,
                 const std::string& quality_fallback_to) {
    for (const json* e : r.timings(suite, group)) {
      if (!mode.empty() && (*e)["config"].value("mode", "") != mode) continue;
      Point p;
      p.series = series;
      p.key = (*e)["key"].get<std::string>();
      p.label = short_label(p.key);
      p.time_ms = (*e)["frame_ms"]["filter"]["median"].get<double>();
      p.p95_ms = (*e)["frame_ms"]["filter"]["p95"].get<double>();
      p.size = size_of(*e);
      auto by_scene = r.quality(p.key);
      if (by_scene.empty() && !quality_fallback_from.empty()) {
        // Exact mode is bitwise equal on both backends: its quality is the CPU's.
        std::string k = p.key;
        const size_t at = k.find(quality_fallback_from);
        if (at != std::string::npos)
          k.replace(at, quality_fallback_from.size(), quality_fallback_to);
        by_scene = r.quality(k);
      }
      p.q = aggregate(by_scene);
      pts.push_back(p);
    }
  };
  add("cpu_exact", "cpu", "chart", "", "", "");
  add("cuda_exact", "gpu", "chart", "exact", "cuda", "cpu");
  add("cuda_fast", "gpu", "chart", "fast", "", "");
  add("baselines", "cpu", "baselines", "", "", "");
  // Pareto fronts within each platform: what a GPU user, or a CPU user, can pick from.
  for (Point& p : pts) {
    if (!std::isfinite(p.time_ms)) continue;
    bool dominated_psnr = false, dominated_flip = false;
    for (const Point& o : pts) {
      if (&o == &p || !std::isfinite(o.time_ms) || platform(o) != platform(p)) continue;
      if (std::isfinite(p.q.psnr) && std::isfinite(o.q.psnr) && o.time_ms <= p.time_ms &&
          o.q.psnr >= p.q.psnr && (o.time_ms < p.time_ms || o.q.psnr > p.q.psnr))
        dominated_psnr = true;
      if (std::isfinite(p.q.flip) && std::isfinite(o.q.flip) && o.time_ms <= p.time_ms &&
          o.q.flip <= p.q.flip && (o.time_ms < p.time_ms || o.q.flip < p.q.flip))
        dominated_flip = true;
    }
    p.pareto_psnr = std::isfinite(p.q.psnr) && !dominated_psnr;
    p.pareto_flip = std::isfinite(p.q.flip) && !dominated_flip;
  }
  return pts;
}

void write_file(const fs::path& path, const std::string& text) {
  std::ofstream f(path);
  if (!f) throw std::runtime_error("cannot write " + path.string());
  f << text;
}

void write_points(const fs::path& out, const std::vector<Point>& pts) {
  for (const char* series : {"cpu_exact", "cuda_exact", "cuda_fast", "baselines"}) {
    std::ostringstream s;
    s << "# time_ms psnr_db flip ssim relmse label\n";
    for (const Point& p : pts)
      if (p.series == series && std::isfinite(p.q.psnr))
        s << p.time_ms << ' ' << p.q.psnr << ' ' << p.q.flip << ' ' << p.q.ssim << ' ' << p.q.relmse
          << " \"" << p.label << "\"\n";
    write_file(out / (std::string("points_") + series + ".dat"), s.str());
  }
  for (const char* plat : {"cpu", "gpu"})
    for (int which = 0; which < 2; ++which) {
      std::vector<const Point*> front;
      for (const Point& p : pts)
        if (platform(p) == plat && (which == 0 ? p.pareto_psnr : p.pareto_flip))
          front.push_back(&p);
      std::sort(front.begin(), front.end(),
                [](const Point* a, const Point* b) { return a->time_ms < b->time_ms; });
      std::ostringstream s;
      s << "# time_ms value label (Pareto front of the " << plat << " configurations)\n";
      for (const Point* p : front)
        s << p->time_ms << ' ' << (which == 0 ? p->q.psnr : p->q.flip) << " \"" << p->key << "\"\n";
      write_file(
          out / ((which == 0 ? "pareto_psnr_" : "pareto_flip_") + std::string(plat) + ".dat"),
          s.str());
    }
}

// Per-frame curves of each fixture scene: one file per scene and metric, one column per config.
std::vector<std::string> write_error_curves(const fs::path& out, const Results& r) {
  std::vector<std::string> keys = {"noisy input", kDefaultCpu, kDefaultFast};
  for (const json* e : r.timings("cpu", "baselines")) keys.push_back((*e)["key"]);
  std::map<std::string, std::map<std::string, json>> by_key;  // key -> scene -> entry
  std::vector<std::string> scenes;
  for (const std::string& k : keys) {
    by_key[k] = r.quality(k);
    for (const auto& [scene, e] : by_key[k])
      if (std::find(scenes.begin(), scenes.end(), scene) == scenes.end()) scenes.push_back(scene);
  }
  std::sort(scenes.begin(), scenes.end());
  for (const std::string& scene : scenes)
    for (const char* metric : {"psnr", "flip", "error_change"}) {
      std::vector<std::string> cols;
      std::vector<const json*> entries;
      size_t frames = 0;
      for (const std::string& k : keys) {
        auto it = by_key[k].find(scene);
        if (it == by_key[k].end()) continue;
        cols.push_back(underscores(k));
        entries.push_back(&it->second);
        frames = std::max(frames, it->second["frames"].size());
      }
      std::ostringstream s;
      s << "frame";
      for (const std::string& c : cols) s << ' ' << c;
      s << '\n';
      for (size_t f = 0; f < frames; ++f) {
        s << f;
        for (const json* e : entries) {
          const json& fr = (*e)["frames"];
          const double v = f < fr.size() ? num(fr[f][metric]) : NAN;
          s << ' ';
          if (std::isfinite(v))
            s << v;
          else
            s << "NaN";
        }
        s << '\n';
      }
      write_file(out / ("errors_" + scene + "_" + metric + ".dat"), s.str());
    }
  write_file(out / "scenes.txt", [&] {
    std::string t;
    for (const std::string& s : scenes) t += s + "\n";
    return t;
  }());
  return scenes;
}

double mpix(const json& e) { return e["input"]["pixels"].get<double>() / 1e6; }
double median_ms(const json& e) { return e["frame_ms"]["filter"]["median"].get<double>(); }

void write_scaling(const fs::path& out, const Results& r) {
  auto series = [&](const std::string& file, const std::vector<const json*>& es) {
    std::ostringstream s;
    s << "# megapixels median_ms p95_ms size\n";
    for (const json* e : es)
      s << mpix(*e) << ' ' << median_ms(*e) << ' '
        << (*e)["frame_ms"]["filter"]["p95"].get<double>() << " \"" << size_of(*e) << "\"\n";
    write_file(out / file, s.str());
  };
  std::map<int, std::vector<const json*>> cpu_by_threads;
  for (const json* e : r.timings("cpu", "sizes"))
    cpu_by_threads[(*e)["config"]["threads"].get<int>()].push_back(e);
  // One thread and all threads (the machine's count varies; the file names do not).
  series("scaling_pixels_cpu_t1.dat", cpu_by_threads[1]);
  series("scaling_pixels_cpu_tmax.dat",
         cpu_by_threads.empty() ? std::vector<const json*>() : cpu_by_threads.rbegin()->second);
  std::vector<const json*> exact, fast;
  for (const json* e : r.timings("gpu", "sizes"))
    ((*e)["config"]["mode"] == "fast" ? fast : exact).push_back(e);
  series("scaling_pixels_cuda_exact.dat", exact);
  series("scaling_pixels_cuda_fast.dat", fast);

  auto iterations = [&](const std::string& file, const std::vector<const json*>& es) {
    std::ostringstream s;
    s << "# iterations median_ms p95_ms size\n";
    for (const json* e : es) {
      const json& c = (*e)["config"];
      const int it = c["iterations"].get<int>(), tap = c["feedback_tap"].get<int>();
      if (tap != (it == 1 ? 0 : 1)) continue;  // the default tap only
      s << it << ' ' << median_ms(*e) << ' ' << (*e)["frame_ms"]["filter"]["p95"].get<double>()
        << " \"" << size_of(*e) << "\"\n";
    }
    write_file(out / file, s.str());
  };
  iterations("scaling_iterations_cpu.dat", r.timings("cpu", "chart"));
  std::vector<const json*> it_exact, it_fast;
  for (const json* e : r.timings("gpu", "iterations"))
    ((*e)["config"]["mode"] == "fast" ? it_fast : it_exact).push_back(e);
  iterations("scaling_iterations_cuda_exact.dat", it_exact);
  iterations("scaling_iterations_cuda_fast.dat", it_fast);
}

// ---- summary.md ---------------------------------------------------------------------------

void stage_table(std::ostringstream& md, const json& e) {
  md << "\n**" << e["label"].get<std::string>() << "** at " << size_of(e) << " — "
     << e["description"].get<std::string>() << "; " << e["frames"].get<int>() << " frames after "
     << e["warmup"].get<int>() << " warm-up; load " << fmt(e["load_before"][0].get<double>(), 2)
     << " → " << fmt(e["load_after"][0].get<double>(), 2) << "; other processes used "
     << fmt(100 * e.value("others_cpu_share", 0.0), 0) << "% of the CPUs while timing\n\n";
  md << "| stage | median ms | p95 ms | MP/s | B/px read | B/px written | GB/s | % of copy | "
        "ops/px | floor ms | bound | × floor |\n";
  md << "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---:|\n";
  for (const json& s : e["stages"]) {
    md << "| " << s["stage"].get<std::string>() << " | " << fmt(s["ms"]["median"].get<double>(), 4)
       << " | " << fmt(s["ms"]["p95"].get<double>(), 4) << " | "
       << fmt(s["mpix_per_s"].get<double>(), 0) << " | "
       << fmt(s["bytes_read_per_px"].get<double>(), 0) << " | "
       << fmt(s["bytes_written_per_px"].get<double>(), 0) << " | "
       << fmt(s["achieved_gbs"].get<double>(), 1) << " | ";
    if (s["host_link"].get<bool>()) {
      md << "(host link) | - | - | - | - |\n";
      continue;
    }
    md << fmt(s["pct_of_copy_bw"].get<double>(), 1) << " | "
       << fmt(s["ops_per_px"].get<double>(), 0) << " | "
       << fmt(s["floor"]["floor_ms"].get<double>(), 4) << " | "
       << s["floor"]["bound"].get<std::string>() << " | "
       << fmt(s["floor"]["ratio"].get<double>(), 2) << " |\n";
  }
  const json& f = e["frame_ms"];
  md << "| **frame (filter)** | **" << fmt(f["filter"]["median"].get<double>(), 4) << "** | "
     << fmt(f["filter"]["p95"].get<double>(), 4) << " | "
     << fmt(e["frame_mpix_per_s"].get<double>(), 0) << " | ";
  if (e.contains("floor"))
    md << fmt(e["floor"]["bytes_per_px"].get<double>(), 0) << " (R+W) | | "
       << fmt(e["floor"]["frame_achieved_gbs"].get<double>(), 1) << " | | "
       << fmt(e["floor"]["ops_per_px"].get<double>(), 0) << " | "
       << fmt(e["floor"]["floor_ms"].get<double>(), 4) << " | | "
       << fmt(e["floor"]["ratio"].get<double>(), 2) << " |\n";
  else
    md << " | | | | | | | |\n";
  md << "| frame (wall, denoise() call) | " << fmt(f["wall"]["median"].get<double>(), 4) << " | "
     << fmt(f["wall"]["p95"].get<double>(), 4) << " | | | | | | | | | |\n";
  if (e.contains("peak_device_bytes"))
    md << "\nPeak device memory of the denoiser: "
       << fmt(static_cast<double>(e["peak_device_bytes"].get<size_t>()) / (1 << 20), 1)
       << " MiB.\n";
}

std::string verdict(bool ok) { return ok ? "**met**" : "**missed**"; }

std::string summary(const Results& r, const std::vector<Point>& pts) {
  std::ostringstream md;
  md << "# Benchmark results (generated by `svgf-bench chart-data`; do not edit)\n";
  if (const json* cpu = r.suite("cpu")) {
    const json& h = (*cpu)["host"];
    md << "\n## CPU machine\n\n"
       << h.value("cpu_model", "?") << ", " << h.value("hardware_threads", 0)
       << " hardware threads (host " << h.value("hostname", "?")
       << ").\n\nMeasured ceilings:\n\n| threads | memcpy GB/s (read + write) | float ops/s "
          "(mul+add chains, AVX2, no FMA) |\n|---:|---:|---:|\n";
    for (const auto& [t, c] : (*cpu)["ceilings"].items())
      md << "| " << t << " | " << fmt(c["copy_gbs"].get<double>(), 1) << " | "
         << fmt(c["ops_per_s"].get<double>() / 1e9, 1) << " G |\n";
    md << "\nSections:\n\n";
    for (const auto& [s, m] : (*cpu)["sections"].items())
      md << "- " << s << ": " << m.value("started", "?") << " to " << m.value("finished", "?")
         << ", `" << m.value("command", "") << "`\n";
  }
  if (const json* gpu = r.suite("gpu")) {
    const json& d = (*gpu)["device"];
    md << "\n## GPU machine\n\n";
    if (d.value("present", false))
      md << "| | |\n|---|---|\n| device | " << d["name"].get<std::string>()
         << " |\n| compute capability | " << d["compute_capability"].get<std::string>()
         << " |\n| SMs | " << d["sms"].get<int>() << " |\n| SM clock (peak) | "
         << fmt(d["clock_mhz"].get<double>(), 0) << " MHz |\n| L2 | "
         << fmt(d["l2_bytes"].get<double>() / (1 << 20), 0) << " MiB |\n| memory | "
         << fmt(d["memory_bytes"].get<double>() / (1 << 30), 1) << " GiB |\n| driver / runtime | "
         << d["driver_version"].get<int>() << " / " << d["runtime_version"].get<int>()
         << " |\n| measured D2D copy (cudaMemcpy, 1 GiB, read + write) | "
         << fmt(d["memcpy_d2d_gbs"].get<double>(), 0)
         << " GB/s |\n| measured copy kernel (float4) | "
         << fmt(d["copy_kernel_gbs"].get<double>(), 0)
         << " GB/s |\n| measured FP32 rate (FMA chains) | "
         << fmt(d["fp32_ops_per_s"].get<double>() / 1e12, 1) << " T instructions/s |\n";
    md << "\nHost of the GPU: " << (*gpu)["host"].value("cpu_model", "?") << ", "
       << (*gpu)["host"].value("hardware_threads", 0) << " threads. Command: `"
       << (*gpu).value("command", "") << "`\n";
    for (const json& c : (*gpu)["checks"])
      md << "\nCheck: " << c["name"].get<std::string>() << ": " << c["differing"].get<size_t>()
         << " of " << c["values"].get<size_t>() << " values differ ("
         << (c["equal"].get<bool>() ? "bitwise equal" : "NOT equal") << ").\n";
  }

  // Targets.
  md << "\n## Targets\n\n| target | measured | verdict |\n|---|---|---|\n";
  const json* fast1080 = nullptr;
  const json* exact1080 = nullptr;
  for (const json* e : r.timings("gpu", "sizes"))
    if ((*e)["input"]["width"] == 1920)
      ((*e)["config"]["mode"] == "fast" ? fast1080 : exact1080) = e;
  if (fast1080)
    md << "| GPU fast, 1080p, ≤ 0.35 ms/frame | " << fmt(median_ms(*fast1080), 4) << " ms (p95 "
       << fmt((*fast1080)["frame_ms"]["filter"]["p95"].get<double>(), 4) << ") | "
       << verdict(median_ms(*fast1080) <= 0.35) << " |\n";
  if (exact1080)
    md << "| GPU exact, 1080p, ≤ 0.8 ms/frame | " << fmt(median_ms(*exact1080), 4) << " ms (p95 "
       << fmt((*exact1080)["frame_ms"]["filter"]["p95"].get<double>(), 4) << ") | "
       << verdict(median_ms(*exact1080) <= 0.8) << " |\n";
  for (const json* e : {fast1080, exact1080}) {
    if (!e) continue;
    for (const json& s : (*e)["stages"]) {
      if (s["host_link"].get<bool>() || s["floor"]["bound"] != "bytes") continue;
      const double pct = s["pct_of_copy_bw"].get<double>();
      md << "| GPU " << (*e)["config"]["mode"].get<std::string>() << " 1080p memory-bound stage "
         << s["stage"].get<std::string>() << ", ≥ 60% of copy bandwidth | " << fmt(pct, 1) << "% ("
         << fmt(s["achieved_gbs"].get<double>(), 0) << " GB/s) | " << verdict(pct >= 60) << " |\n";
    }
  }
  std::map<std::pair<int, int>, const json*> cpu;  // (width, threads)
  for (const json* e : r.timings("cpu", "sizes"))
    cpu[{(*e)["input"]["width"].get<int>(), (*e)["config"]["threads"].get<int>()}] = e;
  int tmax = 1;
  for (const auto& [k, e] : cpu) tmax = std::max(tmax, k.second);
  if (cpu.count({1280, tmax}))
    md << "| CPU " << tmax << " threads, 720p, ≤ 100 ms/frame | "
       << fmt(median_ms(*cpu[{1280, tmax}]), 1) << " ms | "
       << verdict(median_ms(*cpu[{1280, tmax}]) <= 100) << " |\n";
  for (int w : {1280, 1920, 3840})
    if (tmax > 1 && cpu.count({w, 1}) && cpu.count({w, tmax})) {
      const double s = median_ms(*cpu[{w, 1}]) / median_ms(*cpu[{w, tmax}]);
      md << "| CPU " << tmax << " threads ≥ 1.85× one thread (" << size_of(*cpu[{w, 1}]) << ") | "
         << fmt(s, 2) << "× | " << verdict(s >= 1.85) << " |\n";
    }
  for (int t : {1, tmax})
    if (cpu.count({3840, t}) && cpu.count({1920, t})) {
      const double q = median_ms(*cpu[{3840, t}]) / median_ms(*cpu[{1920, t}]);
      md << "| CPU time linear in pixels, 4K / 1080p in [3.6, 4.4] (" << t << " thread"
         << (t > 1 ? "s" : "") << ") | " << fmt(q, 2) << "× | " << verdict(q >= 3.6 && q <= 4.4)
         << " |\n";
    }

  // The default scene against a full-coverage one, same configuration and size.
  {
    std::vector<const json*> cov;
    for (const char* s : {"gpu", "cpu"})
      for (const json* e : r.timings(s, "coverage")) cov.push_back(e);
    if (!cov.empty()) {
      md << "\n## Coverage check (default scene against a scene with a surface at every "
            "pixel)\n\n| configuration | size | scene | surface | median ms | p95 ms | floor ms | "
            "× floor |\n|---|---|---|---:|---:|---:|---:|---:|\n";
      // Older results lack input.surface_fraction: it follows from the a-trous stage's ops per
      // pixel, which are linear in it (bench/stage_cost.h).
      auto surface_of = [&](const json& e) {
        if (e["input"].contains("surface_fraction"))
          return e["input"]["surface_fraction"].get<double>();
        SvgfParams p;
        p.iterations = e["config"]["iterations"].get<int>();
        p.feedback_tap = e["config"]["feedback_tap"].get<int>();
        const Mode mode = e["config"]["mode"] == "fast" ? Mode::Fast : Mode::Exact;
        for (const json& st : e["stages"])
          if (st["stage"] == "atrous") {
            const double ops0 = stage_cost(mode, Stage::Atrous, p, false, 0.0).ops;
            const double ops1 = stage_cost(mode, Stage::Atrous, p, false, 1.0).ops;
            const double emission_ops = stage_cost(mode, Stage::Atrous, p, true, 0.0).ops - ops0;
            double ops = st["ops_per_px"].get<double>();
            // Fast mode's last iteration adds the emission in when the frames have it.
            if (mode == Mode::Fast && e["stages"][0]["bytes_read_per_px"].get<double>() >
                                          stage_cost(mode, Stage::Demodulate, p, false, 1.0).read)
              ops -= emission_ops;
            return ops1 > ops0 ? (ops - ops0) / (ops1 - ops0) : 1.0;
          }
        return 1.0;
      };
      auto row = [&](const json& e) {
        md << "| " << e["label"].get<std::string>() << " | " << size_of(e) << " | "
           << e["input"]["scene"].get<std::string>() << " | " << fmt(100 * surface_of(e), 0)
           << "% | " << fmt(median_ms(e), 4) << " | "
           << fmt(e["frame_ms"]["filter"]["p95"].get<double>(), 4) << " | "
           << fmt(e["floor"]["floor_ms"].get<double>(), 4) << " | "
           << fmt(e["floor"]["ratio"].get<double>(), 2) << " |\n";
      };
      // The same configuration at the same size on the default scene.
      auto same_on_default = [&](const json& c) -> const json* {
        for (const char* s : {"gpu", "cpu"})
          for (const char* g : {"sizes", "chart"})
            for (const json* e : r.timings(s, g))
              if ((*e)["label"] == c["label"] && size_of(*e) == size_of(c)) return e;
        return nullptr;
      };
      for (const json* c : cov) {
        if (const json* d = same_on_default(*c)) row(*d);
        row(*c);
      }
    }
  }

  // Scaling tables.
  md << "\n## Time against pixels (filter stages, median ms per frame)\n\n| size | Mpx |";
  std::vector<std::string> cols;
  std::map<std::string, std::map<std::string, double>> grid;  // size -> column -> ms
  std::map<std::string, double> size_px;
  for (const json* e : r.timings("cpu", "sizes")) {
    const std::string c = "CPU " + std::to_string((*e)["config"]["threads"].get<int>()) + " thr";
    if (std::find(cols.begin(), cols.end(), c) == cols.end()) cols.push_back(c);
    grid[size_of(*e)][c] = median_ms(*e);
    size_px[size_of(*e)] = mpix(*e);
  }
  for (const json* e : r.timings("gpu", "sizes")) {
    const std::string c = "CUDA " + (*e)["config"]["mode"].get<std::string>();
    if (std::find(cols.begin(), cols.end(), c) == cols.end()) cols.push_back(c);
    grid[size_of(*e)][c] = median_ms(*e);
    size_px[size_of(*e)] = mpix(*e);
  }
  for (const std::string& c : cols) md << ' ' << c << " ms | " << c << " ns/px |";
  md << "\n|---|---:|";
  for (size_t i = 0; i < cols.size(); ++i) md << "---:|---:|";
  md << "\n";
  std::vector<std::pair<double, std::string>> sizes;
  for (const auto& [s, px] : size_px) sizes.push_back({px, s});
  std::sort(sizes.begin(), sizes.end());
  for (const auto& [px, s] : sizes) {
    md << "| " << s << " | " << fmt(px, 3) << " |";
    for (const std::string& c : cols) {
      auto it = grid[s].find(c);
      if (it == grid[s].end())
        md << " - | - |";
      else
        md << ' ' << fmt(it->second, it->second < 10 ? 4 : 1) << " | "
           << fmt(it->second * 1e6 / (px * 1e6), 3) << " |";
    }
    md << "\n";
  }

  md << "\n## CPU time against threads (median ms per frame)\n\n| size | 1 thread |";
  if (tmax > 1) md << ' ' << tmax << " threads | speed-up |";
  md << "\n|---|---:|" << (tmax > 1 ? "---:|---:|" : "") << "\n";
  for (const auto& [wt, one] : cpu) {
    if (wt.second != 1) continue;
    const int w = wt.first;
    md << "| " << size_of(*one) << " | " << fmt(median_ms(*one), 2) << " |";
    if (tmax > 1 && cpu.count({w, tmax}))
      md << ' ' << fmt(median_ms(*cpu[{w, tmax}]), 2) << " | "
         << fmt(median_ms(*one) / median_ms(*cpu[{w, tmax}]), 2) << "× |";
    md << "\n";
  }

  md << "\n## Time against a-trous iterations (median ms per frame, default feedback tap)\n\n"
        "| iterations | CPU (chart size, all threads) | CUDA exact | CUDA fast "
        "|\n|---:|---:|---:|---:|\n";
  std::map<int, std::array<double, 3>> its;
  auto fill = [&](const std::vector<const json*>& es, int col, const std::string& mode) {
    for (const json* e : es) {
      const json& c = (*e)["config"];
      if (!mode.empty() && c["mode"] != mode) continue;
      const int it = c["iterations"].get<int>();
      if (c["feedback_tap"].get<int>() != (it == 1 ? 0 : 1)) continue;
      if (!its.count(it)) its[it] = {NAN, NAN, NAN};
      its[it][static_cast<size_t>(col)] = median_ms(*e);
    }
  };
  fill(r.timings("cpu", "chart"), 0, "");
  fill(r.timings("gpu", "iterations"), 1, "exact");
  fill(r.timings("gpu", "iterations"), 2, "fast");
  std::string cpu_size, gpu_size;
  if (!r.timings("cpu", "chart").empty()) cpu_size = size_of(*r.timings("cpu", "chart").front());
  if (!r.timings("gpu", "iterations").empty())
    gpu_size = size_of(*r.timings("gpu", "iterations").front());
  for (const auto& [it, v] : its)
    md << "| " << it << " | " << fmt(v[0], 2) << " | " << fmt(v[1], 4) << " | " << fmt(v[2], 4)
       << " |\n";
  md << "\nCPU at " << (cpu_size.empty() ? "-" : cpu_size) << ", CUDA at "
     << (gpu_size.empty() ? "-" : gpu_size) << ".\n";

  // Launch shapes.
  {
    std::map<std::string, std::array<double, 2>> shapes;  // "16x8" -> exact, fast
    std::string size;
    auto add = [&](const json& e) {
      const json& c = e["config"];
      if (!c.contains("block") || c["iterations"] != 4 || c["feedback_tap"] != 1) return;
      const std::string b =
          std::to_string(c["block"][0].get<int>()) + "x" + std::to_string(c["block"][1].get<int>());
      if (!shapes.count(b)) shapes[b] = {NAN, NAN};
      shapes[b][c["mode"] == "fast" ? 1 : 0] = median_ms(e);
      size = size_of(e);
    };
    const std::vector<const json*> blocks = r.timings("gpu", "blocks");
    if (!blocks.empty()) {
      const int w = (*blocks.front())["input"]["width"].get<int>();
      for (const json* e : r.timings("gpu", "sizes"))
        if ((*e)["input"]["width"].get<int>() == w) add(*e);
      for (const json* e : blocks) add(*e);
      md << "\n## GPU launch shape (" << size
         << ", it4 tap1, median ms per frame)\n\n| block | exact | fast |\n|---|---:|---:|\n";
      for (const auto& [b, v] : shapes)
        md << "| " << b << " | " << fmt(v[0], 4) << " | " << fmt(v[1], 4) << " |\n";
    }
  }

  // Quality against speed.
  md << "\n## Quality against time (the chart's numbers)\n\nTime: median filter time per frame "
        "at the chart size; quality: mean over the fixture scenes of each scene's mean over its "
        "frames. Output change is on the static scene ("
     << kStaticScene
     << ").\n\n"
        "| configuration | size | time ms | p95 ms | PSNR dB | FLIP | SSIM | relMSE | error change "
        "| "
        "static output change | Pareto front of its platform (PSNR / FLIP) "
        "|\n|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---|\n";
  for (const Point& p : pts)
    md << "| " << p.key << " | " << p.size << " | " << fmt(p.time_ms, p.time_ms < 10 ? 4 : 1)
       << " | " << fmt(p.p95_ms, p.p95_ms < 10 ? 4 : 1) << " | " << fmt(p.q.psnr, 2) << " | "
       << fmt(p.q.flip, 4) << " | " << fmt(p.q.ssim, 4) << " | " << fmt(p.q.relmse, 4) << " | "
       << fmt(p.q.error_change, 5) << " | " << fmt(p.q.static_output_change, 5) << " | "
       << (p.pareto_psnr ? "PSNR" : "") << (p.pareto_psnr && p.pareto_flip ? " / " : "")
       << (p.pareto_flip ? "FLIP" : "") << " |\n";
  const Quality noisy = aggregate(r.quality("noisy input"));
  md << "| noisy input | | | | " << fmt(noisy.psnr, 2) << " | " << fmt(noisy.flip, 4) << " | "
     << fmt(noisy.ssim, 4) << " | " << fmt(noisy.relmse, 4) << " | " << fmt(noisy.error_change, 5)
     << " | " << fmt(noisy.static_output_change, 5) << " | |\n";

  // Quality per scene of the default configurations.
  md << "\n## Quality per fixture scene (mean over frames)\n\n| configuration | scene | frames | "
        "PSNR dB | SSIM | relMSE | FLIP | error change | output change "
        "|\n|---|---|---:|---:|---:|---:|---:|---:|---:|\n";
  std::vector<std::string> keys = {"noisy input", kDefaultCpu, kDefaultExact, kDefaultFast};
  for (const json* e : r.timings("cpu", "baselines")) keys.push_back((*e)["key"]);
  for (const std::string& k : keys)
    for (const auto& [scene, e] : r.quality(k)) {
      const json& m = e["mean"];
      md << "| " << k << " | " << scene << " | " << e["frames"].size() << " | "
         << fmt(num(m["psnr"]), 2) << " | " << fmt(num(m["ssim"]), 4) << " | "
         << fmt(num(m["relmse"]), 4) << " | " << fmt(num(m["flip"]), 4) << " | "
         << fmt(num(m["error_change"]), 5) << " | " << fmt(num(m["output_change"]), 5) << " |\n";
    }

  // The cost model every floor above comes from.
  md << "\n## Cost model (bench/stage_cost.cpp), per pixel, default parameters (4 iterations, "
        "feedback tap 1), frames with emission planes\n\n| mode | stage | surface pixel: bytes "
        "read | written | ops | background pixel: bytes read | written | ops | planes |\n"
        "|---|---|---:|---:|---:|---:|---:|---:|---|\n";
  const SvgfParams defaults;
  for (Mode mode : {Mode::Exact, Mode::Fast}) {
    for (int si = 0; si < kStageCount; ++si) {
      const Stage st = static_cast<Stage>(si);
      const StageCost a = stage_cost(mode, st, defaults, true, 1.0);
      const StageCost b = stage_cost(mode, st, defaults, true, 0.0);
      if (a.bytes() <= 0 && b.bytes() <= 0) continue;
      md << "| " << to_string(mode) << " | " << stage_name(st) << " | " << fmt(a.read, 0) << " | "
         << fmt(a.written, 0) << " | " << fmt(a.ops, 0) << " | " << fmt(b.read, 0) << " | "
         << fmt(b.written, 0) << " | " << fmt(b.ops, 0) << " | " << a.planes << " |\n";
    }
    const StageCost a = frame_cost(mode, defaults, true, 1.0);
    const StageCost b = frame_cost(mode, defaults, true, 0.0);
    md << "| " << to_string(mode) << " | **frame (filter stages)** | " << fmt(a.read, 0) << " | "
       << fmt(a.written, 0) << " | " << fmt(a.ops, 0) << " | " << fmt(b.read, 0) << " | "
       << fmt(b.written, 0) << " | " << fmt(b.ops, 0) << " | |\n";
  }

  // Per-stage tables.
  md << "\n## Per-stage tables\n\nBytes and operations per pixel come from bench/stage_cost.cpp "
        "(planes each kernel reads and writes once; steady-state path). The floor of a stage is "
        "max(bytes / copy bandwidth, ops / FP32 rate) with the measured ceilings; the frame's "
        "floor is the sum over its stages.\n";
  for (const char* s : {"gpu", "cpu"})
    for (const json* e : r.timings(s, "sizes")) stage_table(md, *e);
  for (const json* e : r.timings("cpu", "baselines")) {
    md << "\n**" << (*e)["label"].get<std::string>() << "** at " << size_of(*e) << ": median "
       << fmt(median_ms(*e), 1) << " ms, p95 "
       << fmt((*e)["frame_ms"]["filter"]["p95"].get<double>(), 1) << " ms over "
       << (*e)["frames"].get<int>() << " frames (" << (*e)["description"].get<std::string>()
       << ").\n";
  }
  return md.str();
}

}  // namespace

int write_chart_data(const std::string& results_dir, const std::string& out_dir) {
  Results r;
  for (const auto& e : fs::directory_iterator(results_dir)) {
    if (e.path().extension() != ".json") continue;
    std::ifstream in(e.path());
    json doc = json::parse(in, nullptr, false);
    if (doc.is_discarded() || !doc.contains("suite")) continue;
    const std::string name = doc["suite"].get<std::string>();  // before doc is moved from
    r.suites[name] = std::move(doc);
  }
  if (r.suites.empty())
    throw std::runtime_error("chart-data: no suite results (cpu.json, gpu.json) in " + results_dir);
  fs::create_directories(out_dir);
  const std::vector<Point> pts = chart_points(r);
  write_points(out_dir, pts);
  write_error_curves(out_dir, r);
  write_scaling(out_dir, r);
  write_file(fs::path(out_dir) / "summary.md", summary(r, pts));
  std::printf("chart-data: %zu suite(s), %zu chart points -> %s\n", r.suites.size(), pts.size(),
              out_dir.c_str());
  return 0;
}

}  // namespace svgf::bench

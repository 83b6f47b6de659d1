#include "bench/eval_quality.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench/host_probe.h"
#include "bench/suites.h"
#include "bench/workload.h"
#include "io/atomic_file.h"
#include "io/sequence.h"

namespace fs = std::filesystem;

namespace svgf::bench {

using json = nlohmann::json;

const std::map<std::string, double>& reference_noise_db() {
  static const std::map<std::string, double> table = {
      {"cornell-static", 40.84}, {"cornell-moving", 41.04}, {"camera-pan", 25.95},
      {"textured", 43.20},       {"thin", 27.33},           {"cut", 40.90},
      {"moving-shadow", 43.80},  {"light-switch", 38.06}};
  return table;
}

namespace {

std::string fmt_db(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f dB", v);
  return buf;
}

// The complete sequences of the set, by folder name; incomplete ones (no manifest yet, or one
// that does not read) are named and skipped.
std::vector<FrameSet> load_set(const std::string& dir, json& scenes) {
  if (!fs::is_directory(dir)) throw std::runtime_error("quality: no folder " + dir);
  std::vector<fs::path> dirs;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_directory()) dirs.push_back(e.path());
  std::sort(dirs.begin(), dirs.end());
  std::vector<FrameSet> sets;
  for (const fs::path& d : dirs) {
    if (!fs::exists(d / "manifest.json")) {
      std::fprintf(stderr, "svgf-bench quality: %s is incomplete (no manifest.json): skipped\n",
                   d.string().c_str());
      continue;
    }
    const io::Sequence seq(d.string());
    for (int k = 0; k < seq.size(); ++k) seq.verify_checksum(k);  // names the file and frame
    // Without the direct/indirect channels: SVGF runs unsplit (--svgf-split off).
    FrameSet f = load_fixture(d.string(), 0, false);
    if (!f.has_reference()) {
      std::fprintf(stderr, "svgf-bench quality: %s has no reference: skipped\n", d.string().c_str());
      continue;
    }
    const auto& m = seq.manifest();
    scenes.push_back({{"scene", f.scene}, {"folder", d.filename().string()},
                      {"width", m.width}, {"height", m.height}, {"frames", seq.size()},
                      {"spp", m.spp}, {"reference_spp", m.reference_spp}});
    sets.push_back(std::move(f));
  }
  if (sets.empty()) throw std::runtime_error("quality: no complete sequence under " + dir);
  return sets;
}

}  // namespace

int run_eval_quality(const EvalQualityOptions& o) {
  json doc;
  doc["kind"] = "eval-quality";
  doc["command"] = o.command;
  doc["started"] = now_iso();
  const HostInfo host = query_host();
  doc["host"] = host_json(host);
  json scenes = json::array();
  const std::vector<FrameSet> sets = load_set(o.set_dir, scenes);
  doc["set"] = {{"dir", o.set_dir}, {"scenes", scenes}};
  const int threads = o.threads > 0 ? o.threads : std::max(1, host.hardware_threads);
  doc["backend"] = "cpu exact (CUDA exact gives the same bits)";
  doc["svgf_split"] = "off";
  doc["clean_reference_db"] = kCleanReferenceDb;
  json clean = json::array(), noisy = json::array();
  for (const FrameSet& f : sets) {
    auto it = reference_noise_db().find(f.scene);
    json row = {{"scene", f.scene},
                {"reference_noise_db", it == reference_noise_db().end() ? json(nullptr)
                                                                        : json(it->second)}};
    const bool ok = it != reference_noise_db().end() && it->second >= kCleanReferenceDb;
    if (!ok)
      row["why"] = it == reference_noise_db().end()
                       ? "reference noise not measured"
                       : "reference noise " + fmt_db(it->second) + ", below " +
                             fmt_db(kCleanReferenceDb);
    (ok ? clean : noisy).push_back(row);
  }
  doc["clean_scenes"] = clean;
  doc["left_out_scenes"] = noisy;
  json entries = json::array(), means = json::array();
  tbb::task_arena arena(threads);
  // The frames come without direct/indirect (load_fixture, split false), so SVGF's split "auto"
  // runs unsplit: `--svgf-split off`, with the keys the charts look up.
  for (const RunConfig& c : quality_configs(threads)) {
    double sum[2][2] = {{0, 0}, {0, 0}};  // [all, clean][psnr, flip]
    int n[2] = {0, 0};
    std::string key;
    // The scenes run side by side (each denoiser has its own state and threads), their results
    // kept by scene index and printed and summed in the set's order afterwards, so the file is
    // the same as one scene after the other. The OpenCV baselines share one global thread
    // setting, so they run one scene at a time.
    std::vector<json> results(sets.size());
    std::vector<std::string> errors(sets.size());
    auto one = [&](size_t i) {
      try {
        results[i] = quality_run(c, sets[i]);
      } catch (const std::exception& ex) {
        errors[i] = ex.what();
        if (errors[i].empty()) errors[i] = "failed";
      }
    };
    if (c.project() || c.method == "noisy")
      arena.execute([&] { tbb::parallel_for(size_t(0), sets.size(), one); });
    else
      for (size_t i = 0; i < sets.size(); ++i) one(i);
    for (size_t i = 0; i < sets.size(); ++i) {
      const FrameSet& f = sets[i];
      if (!errors[i].empty()) {
        std::fprintf(stderr, "svgf-bench quality: %s on %s: %s\n", c.key().c_str(),
                     f.scene.c_str(), errors[i].c_str());
        continue;
      }
      json e = std::move(results[i]);
      print_quality(e, stdout);
      key = e["key"].get<std::string>();
      const double psnr = e["mean"]["psnr"].is_number() ? e["mean"]["psnr"].get<double>() : NAN;
      const double flip = e["mean"]["flip"].get<double>();
      const auto it = reference_noise_db().find(f.scene);
      const bool is_clean = it != reference_noise_db().end() && it->second >= kCleanReferenceDb;
      for (int w = 0; w < (is_clean ? 2 : 1); ++w) {
        sum[w][0] += psnr;
        sum[w][1] += flip;
        ++n[w];
      }
      entries.push_back(std::move(e));
    }
    if (key.empty()) continue;
    auto mean = [&](int w, int m) { return n[w] ? json(sum[w][m] / n[w]) : json(nullptr); };
    means.push_back({{"key", key},
                     {"all", {{"scenes", n[0]}, {"psnr", mean(0, 0)}, {"flip", mean(0, 1)}}},
                     {"clean", {{"scenes", n[1]}, {"psnr", mean(1, 0)}, {"flip", mean(1, 1)}}}});
  }
  doc["quality"] = entries;
  doc["means"] = means;
  doc["finished"] = now_iso();
  const std::string text = doc.dump(1) + "\n";
  if (fs::path(o.out_file).has_parent_path()) fs::create_directories(fs::path(o.out_file).parent_path());
  io::write_atomically(o.out_file, [&](const std::string& tmp) { std::ofstream(tmp) << text; });
  std::printf("quality: %zu scene(s), %zu configuration(s) -> %s\n", sets.size(), means.size(),
              o.out_file.c_str());
  return 0;
}

}  // namespace svgf::bench

#include "bench/eval_quality.h"

#include <algorithm>
#include <atomic>
#include <chrono>
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
#ifdef SVGF_BENCH_HAVE_GBUFFER
#include "gbuffer/eval_record.h"
#endif

namespace fs = std::filesystem;

namespace svgf::bench {

using json = nlohmann::json;

namespace {

std::string fmt(const char* format, double v) {
  char buf[128];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

// One scene's reference noise per frame (eval.json) and whether its PSNR can be corrected.
struct SceneNoise {
  std::vector<double> mse;  // per frame; NaN where none is recorded
  double mean_mse = NAN, clamped_share = NAN;
  bool clean = false;
  std::string why;  // why not
};

SceneNoise scene_noise(const fs::path& dir, int frames) {
  SceneNoise n;
#ifdef SVGF_BENCH_HAVE_GBUFFER
  try {
    if (const auto r = gbuffer::read_eval_record(dir.string())) {
      for (const gbuffer::ReferenceNoise& f : r->reference_noise) n.mse.push_back(f.mse);
      const gbuffer::SequenceNoise s = gbuffer::sequence_reference_noise(*r);
      n.mean_mse = s.mse;
      n.clamped_share = s.clamped_share;
    }
  } catch (const std::exception& e) {
    n.why = e.what();
    return n;
  }
#else
  (void)dir;
#endif
  if (static_cast<int>(n.mse.size()) != frames || !std::isfinite(n.mean_mse)) {
    n.why = "no reference noise in its eval.json for every frame";
  } else if (n.clamped_share > kMaxClampedShare) {
    n.why = fmt("%.0f%% of its reference noise estimate is at PSNR's clamp",
                100 * n.clamped_share) +
            fmt(", over %.0f%%, where the estimate is low", 100 * kMaxClampedShare);
  } else {
    n.clean = true;
  }
  return n;
}

// 10 log10(1 / (MSE - noise)) from a measured PSNR; null when the difference is not positive.
json corrected_psnr(const json& measured, double noise) {
  if (!measured.is_number()) return nullptr;
  const double mse = std::pow(10.0, -measured.get<double>() / 10.0) - noise;
  return mse > 0 ? json(-10.0 * std::log10(mse)) : json(nullptr);
}

// Adds psnr_corrected per frame and its mean over the frames where it is defined (the number
// of frames where it is not: `psnr_corrected_undefined`).
void add_corrected_psnr(json& e, const SceneNoise& n) {
  double sum = 0;
  int defined = 0, undefined = 0;
  json& frames = e["frames"];
  for (size_t k = 0; k < frames.size(); ++k) {
    json& f = frames[k];
    f["psnr_corrected"] = corrected_psnr(f["psnr"], n.mse[k]);
    if (f["psnr_corrected"].is_number()) {
      sum += f["psnr_corrected"].get<double>();
      ++defined;
    } else {
      ++undefined;
    }
  }
  e["mean"]["psnr_corrected"] = defined ? json(sum / defined) : json(nullptr);
  e["mean"]["psnr_corrected_undefined"] = undefined;
}

// The complete sequences of the set, by folder name; incomplete ones (no manifest yet, or one
// that does not read) are named and skipped.
std::vector<FrameSet> load_set(const std::string& dir, json& scenes,
                               std::vector<SceneNoise>& noise) {
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
    SceneNoise sn = scene_noise(d, seq.size());
    scenes.push_back({{"scene", f.scene}, {"folder", d.filename().string()},
                      {"width", m.width}, {"height", m.height}, {"frames", seq.size()},
                      {"spp", m.spp}, {"reference_spp", m.reference_spp},
                      {"reference_noise_db", sn.mean_mse > 0 ? json(-10 * std::log10(sn.mean_mse))
                                                             : json(nullptr)},
                      {"reference_noise_clamped_share",
                       std::isfinite(sn.clamped_share) ? json(sn.clamped_share) : json(nullptr)}});
    sets.push_back(std::move(f));
    noise.push_back(std::move(sn));
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
  std::vector<SceneNoise> noise;
  const std::vector<FrameSet> sets = load_set(o.set_dir, scenes, noise);
  doc["set"] = {{"dir", o.set_dir}, {"scenes", scenes}};
  const int threads = o.threads > 0 ? o.threads : std::max(1, host.hardware_threads);
  doc["backend"] = "cpu exact (CUDA exact gives the same bits)";
  doc["svgf_split"] = "off";
  doc["max_clamped_share"] = kMaxClampedShare;
  doc["psnr_corrected"] =
      "10 log10(1 / (MSE - reference noise MSE)) per frame, the reference noise estimated from "
      "the reference's two halves (eval.json); clean scenes only";
  json clean = json::array(), noisy = json::array();
  for (size_t i = 0; i < sets.size(); ++i) {
    json row = {{"scene", sets[i].scene}, {"reference_noise_db", scenes[i]["reference_noise_db"]}};
    if (!noise[i].clean) row["why"] = noise[i].why;
    (noise[i].clean ? clean : noisy).push_back(row);
  }
  doc["clean_scenes"] = clean;
  doc["left_out_scenes"] = noisy;
  json entries = json::array(), means = json::array();
  const std::vector<RunConfig> configs = quality_configs(threads);
  // Every (configuration, scene) pair of the project's methods and the noisy input runs side by
  // side, each denoiser on one thread of the arena (exact mode gives the same bits on any
  // number), so all cores work whatever the number of scenes; the results are kept by index
  // and printed and summed in the set's order afterwards, so the file is the same as one pair
  // after the other. The OpenCV baselines share one global thread setting, so they run one
  // scene at a time on all threads.
  std::vector<std::vector<json>> results(configs.size(), std::vector<json>(sets.size()));
  std::vector<std::vector<std::string>> errors(configs.size(),
                                               std::vector<std::string>(sets.size()));
  const size_t pairs = configs.size() * sets.size();
  std::atomic<size_t> done{0};
  const auto started = std::chrono::steady_clock::now();
  auto one = [&](size_t c, size_t i) {
    RunConfig config = configs[c];
    if (config.project()) config.denoiser.threads = 1;
    try {
      results[c][i] = quality_run(config, sets[i]);
    } catch (const std::exception& ex) {
      errors[c][i] = ex.what();
      if (errors[c][i].empty()) errors[c][i] = "failed";
    }
    // Progress on stderr as pairs finish (the results are printed in order at the end).
    const double s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    std::fprintf(stderr, "svgf-bench quality: [%zu/%zu] %.0f s %s on %s\n", ++done, pairs, s,
                 configs[c].key().c_str(), sets[i].scene.c_str());
  };
  std::vector<std::pair<size_t, size_t>> side_by_side;
  for (size_t c = 0; c < configs.size(); ++c)
    if (configs[c].project() || configs[c].method == "noisy")
      for (size_t i = 0; i < sets.size(); ++i) side_by_side.emplace_back(c, i);
  tbb::task_arena arena(threads);
  arena.execute([&] {
    tbb::parallel_for(size_t(0), side_by_side.size(), [&](size_t j) {
      one(side_by_side[j].first, side_by_side[j].second);
    });
  });
  for (size_t c = 0; c < configs.size(); ++c)
    if (!configs[c].project() && configs[c].method != "noisy")
      for (size_t i = 0; i < sets.size(); ++i) one(c, i);
  for (size_t c = 0; c < configs.size(); ++c) {
    double sum[2][3] = {{0, 0, 0}, {0, 0, 0}};  // [all, clean][psnr, flip, psnr_corrected]
    int n[2] = {0, 0};
    std::string key;
    for (size_t i = 0; i < sets.size(); ++i) {
      const FrameSet& f = sets[i];
      if (!errors[c][i].empty()) {
        std::fprintf(stderr, "svgf-bench quality: %s on %s: %s\n", configs[c].key().c_str(),
                     f.scene.c_str(), errors[c][i].c_str());
        continue;
      }
      json e = std::move(results[c][i]);
      if (noise[i].clean) add_corrected_psnr(e, noise[i]);
      print_quality(e, stdout);
      key = e["key"].get<std::string>();
      const json& m = e["mean"];
      const double psnr = m["psnr"].is_number() ? m["psnr"].get<double>() : NAN;
      const double corrected =
          m.contains("psnr_corrected") && m["psnr_corrected"].is_number()
              ? m["psnr_corrected"].get<double>() : NAN;
      const double flip = m["flip"].get<double>();
      for (int w = 0; w < (noise[i].clean ? 2 : 1); ++w) {
        sum[w][0] += psnr;
        sum[w][1] += flip;
        sum[w][2] += corrected;
        ++n[w];
      }
      entries.push_back(std::move(e));
    }
    if (key.empty()) continue;
    auto mean = [&](int w, int m) {
      return n[w] && std::isfinite(sum[w][m]) ? json(sum[w][m] / n[w]) : json(nullptr);
    };
    // The clean means' PSNR is the corrected one (null if a frame's is undefined); the
    // measured one beside it.
    means.push_back({{"key", key},
                     {"all", {{"scenes", n[0]}, {"psnr", mean(0, 0)}, {"flip", mean(0, 1)}}},
                     {"clean", {{"scenes", n[1]}, {"psnr", mean(1, 2)},
                                {"psnr_measured", mean(1, 0)}, {"flip", mean(1, 1)}}}});
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

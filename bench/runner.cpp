#include "bench/runner.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>
#include <stdexcept>
#include <thread>

#include "bench/gpu_probe.h"
#include "bench/host_probe.h"
#include "bench/quality.h"
#include "bench/stage_cost.h"
#include "core/order_stats.h"
#include "methods/bmfr/denoiser.h"
#include "methods/svgf/stages.h"

namespace svgf::bench {
namespace {

using json = nlohmann::json;
using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

json summary_json(const OrderStats& s) {
  return {{"median", s.median}, {"p95", s.p95}, {"mean", s.mean},
          {"min", s.min},       {"max", s.max}, {"count", s.count}};
}

// Whether the history restarts before frame m of the played sequence (distinct frame k): a
// cut, or a fixture played again from its first frame. Rendered frame sets are cycled without
// one (their loop is a small jump the reprojection handles as motion).
bool restarts(const FrameSet& fs, int m, int k) {
  return m > 0 && (fs.is_cut(k) || (k == 0 && fs.source == "fixture"));
}

// The share of each timed frame's surface pixels whose history is young (below
// spatial_variance_history), read back from SVGF's history length after the frame: the pixels
// the variance stage filters with its 7x7 estimate, which the cost model counts
// (FrameTraits::young_fraction). Inactive for other methods and split frames.
class YoungHistories {
 public:
  YoungHistories(const Denoiser& d, const RunConfig& c, bool split)
      : min_history_(static_cast<float>(c.denoiser.svgf.spatial_variance_history)) {
    const std::vector<std::string> names = d.debug_buffers();
    active_ = c.denoiser.method == Method::Svgf && !split &&
              std::find(names.begin(), names.end(), svgf_buffer::kHistoryLength) != names.end();
  }
  // After frame f: the rule of VarianceEstimate::common_path (a surface: depth > 0).
  void add(const Denoiser& d, const Frame& f) {
    if (!active_) return;
    const Image length = d.read_buffer(svgf_buffer::kHistoryLength);
    const float* depth = f.depth.plane(0);
    const float* h = length.plane(0);
    size_t surface = 0, young = 0;
    for (size_t i = 0; i < f.depth.pixel_count(); ++i) {
      if (!(depth[i] > 0.f)) continue;
      ++surface;
      young += h[i] < min_history_ ? 1 : 0;
    }
    shares_.push_back(surface ? static_cast<double>(young) / static_cast<double>(surface) : 0.0);
  }
  bool active() const { return active_; }
  bool counted() const { return !shares_.empty(); }
  // The median frame's share, as the stage times compared with the floor are medians.
  OrderStats stats() const { return order_stats(shares_); }

 private:
  float min_history_;
  bool active_ = false;
  std::vector<double> shares_;
};

// JSON has no infinities: a PSNR of identical images becomes null.
json finite_or_null(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

}  // namespace

json time_run(const RunConfig& c, const FrameSet& fs, const TimingOptions& t,
              const Ceilings& ceilings) {
  if (c.method == "noisy") throw std::invalid_argument("the noisy input has no time to measure");
  if (fs.frames.empty()) throw std::invalid_argument("time_run: no frames");
  const bool project = c.project(), cuda = c.cuda();
  // Bytes and operations are counted for every SVGF and BMFR stage and for the other methods'
  // filter stages (bench/stage_cost.h); a frame floor needs them all.
  // SVGF filtering direct and indirect apart runs most stages twice; the cost model counts one
  // signal, so such a run has its once-a-frame stages counted, and no frame floor.
  const bool split = project && c.denoiser.method == Method::Svgf &&
                     c.denoiser.svgf.split != SplitMode::Off && !fs.frames.front().direct.empty() &&
                     !fs.frames.front().indirect.empty();
  const bool costed = project;
  const bool frame_costed = costed && !split && frame_is_costed(c.denoiser.method);
  const double pixels = static_cast<double>(fs.width) * fs.height;
  const bool emission = !fs.frames.front().emission.empty();
  const double surface = fs.surface_fraction();
  FrameTraits traits;
  traits.emission = emission;
  traits.gradient_samples = fs.gradient_samples();
  traits.split = split;
  traits.surface_fraction = surface;
  traits.width = fs.width;
  traits.height = fs.height;
  traits.packed_exact = cuda;  // the CUDA engine's exact mode filters packed pixels
  traits.fused_outputs = true;  // both engines' (methods/svgf/flavors.h)

  const size_t mem_before = cuda ? device_used_bytes() : 0;
  size_t mem_peak = 0;
  std::unique_ptr<Denoiser> den;
  std::string description;
  // The method's stages in the order a frame runs them, then the CUDA engine's transfers.
  std::vector<std::string> stage_names;
  if (project) {
    den = make_denoiser(c.denoiser);
    description = den->description();
    stage_names = den->stages();
    if (cuda) stage_names.insert(stage_names.end(), {kUploadStage, kDownloadStage});
  } else {
    set_baseline_threads(c.resolved_threads());
    description =
        "opencv " + c.baseline.label() + ", " + std::to_string(c.resolved_threads()) + " threads";
  }

  std::optional<YoungHistories> young;
  if (project) young.emplace(*den, c, split);

  std::vector<std::vector<double>> stage_ms(stage_names.size());
  std::vector<double> filter_ms, wall_ms;
  const auto load_before = load_average();
  CpuUsage usage_before = cpu_usage();
  const int n = static_cast<int>(fs.frames.size());
  Image out;
  Clock::time_point timing_start = Clock::now();
  int timed = 0;
  for (int m = 0;; ++m) {
    const bool warm = m < t.warmup;
    if (m == t.warmup) {
      timing_start = Clock::now();
      usage_before = cpu_usage();  // the timed frames only
    }
    if (!warm) {
      if (timed >= t.frames) break;
      if (t.budget_s > 0 && timed >= t.min_frames && ms_since(timing_start) > 1e3 * t.budget_s)
        break;
    }
    const int k = m % n;
    const Frame& f = fs.frames[static_cast<size_t>(k)];
    if (project && restarts(fs, m, k)) den->reset();
    const auto t0 = Clock::now();
    if (project)
      den->denoise(f, out);
    else
      run_baseline(c.baseline, f, out);
    const double wall = ms_since(t0);
    if (cuda) {
      const size_t used = device_used_bytes();
      mem_peak = std::max(mem_peak, used > mem_before ? used - mem_before : size_t(0));
    }
    if (warm) continue;
    ++timed;
    wall_ms.push_back(wall);
    if (project) {
      const StageTimes& st = den->last_report().times;
      for (size_t s = 0; s < stage_names.size(); ++s) stage_ms[s].push_back(st[stage_names[s]]);
      filter_ms.push_back(st.filter_ms());
    } else {
      filter_ms.push_back(wall);
    }
  }
  // The device path after the host path, on the same denoiser (its history goes on): what a
  // renderer whose G-buffer is already on the GPU pays, from its call to the frame done.
  DevicePathTimes device_path;
  if (cuda && project)
    device_path = time_device_path(*den, fs.frames, std::min(t.warmup, 3), timed,
                                   [&](int m, int k) {
                                     if (restarts(fs, m, k)) den->reset();
                                   });
  const auto load_after = load_average();
  const double others = others_share(usage_before, cpu_usage());
  // The timed frames' young histories, counted on a replay after the timing: the history is
  // reset and the same frames run again in the same order, with the same cuts. Read back inside
  // the timed loop, the history length made the next frame's host wall about 0.3 ms longer on
  // the H200 (an 8 MB download and a count on the host), though outside the timed call.
  if (young && young->active()) {
    den->reset();
    for (int m = 0; m < t.warmup + timed; ++m) {
      const int k = m % n;
      const Frame& f = fs.frames[static_cast<size_t>(k)];
      if (restarts(fs, m, k)) den->reset();
      den->denoise(f, out);
      if (m >= t.warmup) young->add(*den, f);
    }
  }
  const bool young_counted = young && young->counted();
  const OrderStats young_stats = young_counted ? young->stats() : OrderStats{};
  if (young_counted) traits.young_fraction = young_stats.median;

  json j;
  j["config"] = config_json(c);
  j["label"] = c.label();
  j["key"] = c.key();
  j["description"] = description;
  j["input"] = {
      {"source", fs.source},  {"scene", fs.scene},           {"description", fs.description},
      {"width", fs.width},    {"height", fs.height},         {"pixels", pixels},
      {"distinct_frames", n}, {"surface_fraction", surface}, {"emission", emission},
      {"gradient_samples", fs.gradient_samples()}};
  if (young_counted)
    j["input"]["young_fraction"] = {{"median", young_stats.median},
                                    {"mean", young_stats.mean},
                                    {"min", young_stats.min},
                                    {"max", young_stats.max},
                                    {"frames", young_stats.count}};
  j["warmup"] = t.warmup;
  j["frames"] = timed;
  const OrderStats filter = order_stats(filter_ms), wall = order_stats(wall_ms);
  j["frame_ms"] = {{"filter", summary_json(filter)}, {"wall", summary_json(wall)}};
  if (!device_path.done_ms.empty()) {
    j["frame_ms"]["device_call"] = summary_json(order_stats(device_path.call_ms));
    j["frame_ms"]["device_wall"] = summary_json(order_stats(device_path.done_ms));
  }
  j["frame_mpix_per_s"] = filter.median > 0 ? pixels / (filter.median * 1e3) : 0.0;
  j["ceilings"] = {{"copy_gbs", ceilings.copy_gbs},
                   {"ops_per_s", ceilings.ops_per_s},
                   {"copy_what", ceilings.copy_what}};
  // The probe runs SVGF's CPU a-trous: beside this run's only where this run is that.
  if (c.method == "svgf" && !cuda) {
    j["ceilings"]["resident_atrous_ns_per_tap"] = ceilings.resident_atrous_ns_per_tap;
    j["ceilings"]["chain_ops_per_s"] = chain_json(ceilings.chain_ops_per_s);
  }

  json stages = json::array();
  std::vector<std::string> costed_stages;
  double floor_total = 0, bytes_total = 0, ops_total = 0;
  for (size_t si = 0; si < stage_names.size(); ++si) {
    const std::string& name = stage_names[si];
    const OrderStats st = order_stats(stage_ms[si]);
    const std::optional<StageCost> counted =
        costed ? method_stage_cost(c.denoiser, name, traits) : std::nullopt;
    const StageCost cost = counted.value_or(StageCost{});
    if (st.max <= 0 && cost.bytes() <= 0) continue;  // not run by this backend/mode
    json e;
    e["stage"] = name;
    e["ms"] = summary_json(st);
    e["mpix_per_s"] = st.median > 0 ? pixels / (st.median * 1e3) : 0.0;
    e["host_link"] = is_transfer_stage(name);
    stages.push_back(e);
    if (!counted) continue;  // no cost model: no bytes, operations or floor ("n/a")
    costed_stages.push_back(name);
    json& ec = stages.back();
    ec["bytes_read_per_px"] = cost.read;
    ec["bytes_written_per_px"] = cost.written;
    ec["ops_per_px"] = cost.ops;
    ec["planes"] = cost.planes;
    const double bytes = cost.bytes() * pixels;
    ec["bytes_per_frame"] = bytes;
    const double gbs = st.median > 0 ? bytes / (st.median * 1e-3) / 1e9 : 0.0;
    ec["achieved_gbs"] = gbs;
    if (is_transfer_stage(name)) continue;
    const double bytes_ms = ceilings.copy_gbs > 0 ? bytes / (ceilings.copy_gbs * 1e9) * 1e3 : 0;
    const double ops_ms = ceilings.ops_per_s > 0 ? cost.ops * pixels / ceilings.ops_per_s * 1e3 : 0;
    const double floor = std::max(bytes_ms, ops_ms);
    ec["pct_of_copy_bw"] = ceilings.copy_gbs > 0 ? 100.0 * gbs / ceilings.copy_gbs : 0.0;
    // The counted operations per second against the measured float rate.
    const double ops_per_s = st.median > 0 ? cost.ops * pixels / (st.median * 1e-3) : 0.0;
    ec["pct_of_ops"] = ceilings.ops_per_s > 0 ? 100.0 * ops_per_s / ceilings.ops_per_s : 0.0;
    if (cost.taps > 0) {  // a filter's neighbour taps: what one costs
      const double taps = cost.taps * pixels;
      ec["taps_per_px"] = cost.taps;
      ec["per_tap"] = {{"ns", st.median * 1e6 / taps},
                       {"taps_per_s", st.median > 0 ? taps / (st.median * 1e-3) : 0.0},
                       {"ops", cost.ops / cost.taps},
                       {"bytes", cost.bytes() / cost.taps}};
    }
    // Bound by neither where nothing is counted: the stage ran inside another stage's launch
    // and is counted there (CUDA's sanitize stage in SVGF's demodulation: stage_cost.cpp).
    const char* bound = floor <= 0 ? "none" : ops_ms > bytes_ms ? "ops" : "bytes";
    ec["floor"] = {{"bytes_ms", bytes_ms},
                   {"ops_ms", ops_ms},
                   {"floor_ms", floor},
                   {"bound", bound},
                   {"ratio", floor > 0 ? st.median / floor : 0.0}};
    floor_total += floor;
    bytes_total += bytes;
    ops_total += cost.ops * pixels;
  }
  if (costed_stages.empty()) {
    j["cost_model"] = "none";
  } else if (frame_costed) {
    j["cost_model"] = "bench/stage_cost.cpp";
  } else {
    std::string names;
    for (const std::string& n : costed_stages) names += (names.empty() ? "" : ", ") + n;
    j["cost_model"] = "bench/stage_cost.cpp, stage " + names + " only";
  }
  if (frame_costed) {
    const double bytes_ms =
        ceilings.copy_gbs > 0 ? bytes_total / (ceilings.copy_gbs * 1e9) * 1e3 : 0;
    const double ops_ms = ceilings.ops_per_s > 0 ? ops_total / ceilings.ops_per_s * 1e3 : 0;
    j["floor"] = {{"bytes_per_frame", bytes_total},
                  {"ops_per_frame", ops_total},
                  {"bytes_per_px", bytes_total / pixels},
                  {"ops_per_px", ops_total / pixels},
                  {"bytes_ms", bytes_ms},
                  {"ops_ms", ops_ms},
                  // Stages run one after another, so the frame's floor is the sum of theirs.
                  {"floor_ms", floor_total},
                  {"ratio", floor_total > 0 ? filter.median / floor_total : 0.0},
                  {"frame_achieved_gbs",
                   filter.median > 0 ? bytes_total / (filter.median * 1e-3) / 1e9 : 0.0}};
  }
  j["stages"] = stages;
  if (cuda) j["peak_device_bytes"] = mem_peak;
  j["load_before"] = load_before;
  j["load_after"] = load_after;
  j["others_cpu_share"] = others;
  j["per_frame_filter_ms"] = filter_ms;
  j["per_frame_wall_ms"] = wall_ms;
  return j;
}

namespace {

// A block-fitting method's per-block diagnostics over a sequence (BMFR's block_rank and
// block_condition debug buffers): how often a block's features were rank-deficient (the skip
// strategy dropped a column; under the noise strategy, a numerically zero column) and the
// distribution of max |R_ii| / min |R_ii| over the blocks that fitted something.
class BlockDiagnostics {
 public:
  explicit BlockDiagnostics(const Denoiser& d) {
    const std::vector<std::string> names = d.debug_buffers();
    active_ = std::find(names.begin(), names.end(), bmfr_buffer::kRank) != names.end();
  }
  void add(const Denoiser& d) {
    if (!active_) return;
    const Image rank = d.read_buffer(bmfr_buffer::kRank);
    const Image cond = d.read_buffer(bmfr_buffer::kCondition);
    for (size_t k = 0; k < rank.data().size(); ++k) {
      ++blocks_;
      const float r = rank.data()[k];
      if (r == 0.f) {
        ++empty_;
        continue;
      }
      if (r < static_cast<float>(bmfr::kFeatures)) ++deficient_;
      condition_.push_back(cond.data()[k]);
    }
  }
  std::optional<json> result() const {
    if (!active_) return std::nullopt;
    const OrderStats s = order_stats(condition_);
    return json{{"blocks", blocks_},           {"rank_deficient", deficient_},
                {"empty", empty_},             {"condition_median", s.median},
                {"condition_p95", s.p95},      {"condition_max", s.max}};
  }

 private:
  bool active_ = false;
  int64_t blocks_ = 0, deficient_ = 0, empty_ = 0;
  std::vector<double> condition_;
};

}  // namespace

json quality_run(const RunConfig& c, const FrameSet& fs) {
  if (!fs.has_reference())
    throw std::invalid_argument("quality: " + fs.description + " has no reference");
  const bool project = c.project();
  std::unique_ptr<Denoiser> den;
  if (project)
    den = make_denoiser(c.denoiser);
  else if (c.method != "noisy")
    set_baseline_threads(c.resolved_threads());
  QualityTracker tracker;
  std::optional<BlockDiagnostics> blocks;
  if (project) blocks.emplace(*den);
  json frames = json::array();
  double sums[4] = {0, 0, 0, 0}, temporal[2] = {0, 0};
  int finite_psnr = 0, n_temporal[2] = {0, 0};
  Image out;
  for (int k = 0; k < static_cast<int>(fs.frames.size()); ++k) {
    const Frame& f = fs.frames[static_cast<size_t>(k)];
    const bool cut = fs.is_cut(k);
    int64_t replaced = 0;
    if (project) {
      if (cut) den->reset();
      den->denoise(f, out);
      replaced = den->last_report().replaced_samples;
      blocks->add(*den);
    } else if (c.method == "noisy") {
      out = f.color;
    } else {
      run_baseline(c.baseline, f, out);
    }
    const FrameQuality q = tracker.add(out, f.reference, cut);
    json e = {{"frame", k},     {"psnr", finite_or_null(q.psnr)},
              {"ssim", q.ssim}, {"relmse", q.relmse},
              {"flip", q.flip}, {"cut", cut}};
    e["error_change"] = q.error_change ? json(*q.error_change) : json(nullptr);
    e["output_change"] = q.output_change ? json(*q.output_change) : json(nullptr);
    if (project) e["replaced_samples"] = replaced;
    frames.push_back(e);
    if (std::isfinite(q.psnr)) {
      sums[0] += q.psnr;
      ++finite_psnr;
    }
    sums[1] += q.ssim;
    sums[2] += q.relmse;
    sums[3] += q.flip;
    if (q.error_change) {
      temporal[0] += *q.error_change;
      ++n_temporal[0];
    }
    if (q.output_change) {
      temporal[1] += *q.output_change;
      ++n_temporal[1];
    }
  }
  const double n = static_cast<double>(fs.frames.size());
  json j;
  j["config"] = config_json(c);
  j["label"] = c.label();
  j["key"] = c.key();
  j["scene"] = fs.scene;
  j["input"] = fs.description;
  j["width"] = fs.width;
  j["height"] = fs.height;
  j["frames"] = frames;
  j["mean"] = {
      {"psnr", finite_psnr ? json(sums[0] / finite_psnr) : json(nullptr)},
      {"ssim", sums[1] / n},
      {"relmse", sums[2] / n},
      {"flip", sums[3] / n},
      {"error_change", n_temporal[0] ? json(temporal[0] / n_temporal[0]) : json(nullptr)},
      {"output_change", n_temporal[1] ? json(temporal[1] / n_temporal[1]) : json(nullptr)}};
  if (blocks)
    if (const std::optional<json> b = blocks->result()) j["blocks"] = *b;
  return j;
}

json chain_json(const std::array<double, 3>& chain_ops_per_s) {
  json j = json::object();
  for (size_t k = 0; k < kDependentChainLengths.size(); ++k)
    j[std::to_string(kDependentChainLengths[k])] = chain_ops_per_s[k];
  return j;
}

void print_timing(const json& e, std::FILE* f) {
  const json& in = e["input"];
  std::fprintf(f, "\n%s | %s\n  %s, %d timed frames after %d warm-up\n",
               e["label"].get<std::string>().c_str(), e["description"].get<std::string>().c_str(),
               in["description"].get<std::string>().c_str(), e["frames"].get<int>(),
               e["warmup"].get<int>());
  std::fprintf(f, "  %-15s %9s %9s %9s %8s %8s %6s %8s %9s %7s\n", "stage", "median ms", "p95 ms",
               "MP/s", "B/px", "GB/s", "%copy", "ops/px", "floor ms", "xfloor");
  for (const json& s : e["stages"]) {
    std::fprintf(f, "  %-15s %9.3f %9.3f %9.0f", s["stage"].get<std::string>().c_str(),
                 s["ms"]["median"].get<double>(), s["ms"]["p95"].get<double>(),
                 s["mpix_per_s"].get<double>());
    if (!s.contains("bytes_read_per_px")) {  // no cost model for this method
      std::fprintf(f, " %8s %8s %6s %8s %9s %7s\n", "n/a", "n/a", "n/a", "n/a", "n/a", "n/a");
      continue;
    }
    const double bpx =
        s["bytes_read_per_px"].get<double>() + s["bytes_written_per_px"].get<double>();
    std::fprintf(f, " %8.0f %8.1f", bpx, s["achieved_gbs"].get<double>());
    if (s["host_link"].get<bool>())
      std::fprintf(f, " %6s %8s %9s %7s\n", "link", "-", "-", "-");
    else
      std::fprintf(f, " %6.1f %8.0f %9.4f %7.2f\n", s["pct_of_copy_bw"].get<double>(),
                   s["ops_per_px"].get<double>(), s["floor"]["floor_ms"].get<double>(),
                   s["floor"]["ratio"].get<double>());
  }
  const json& fm = e["frame_ms"];
  std::fprintf(f, "  %-15s %9.3f %9.3f %9.0f", "frame", fm["filter"]["median"].get<double>(),
               fm["filter"]["p95"].get<double>(), e["frame_mpix_per_s"].get<double>());
  if (e.contains("floor"))
    std::fprintf(f, " %8.0f %8.1f %6s %8.0f %9.4f %7.2f", e["floor"]["bytes_per_px"].get<double>(),
                 e["floor"]["frame_achieved_gbs"].get<double>(), "",
                 e["floor"]["ops_per_px"].get<double>(), e["floor"]["floor_ms"].get<double>(),
                 e["floor"]["ratio"].get<double>());
  else
    std::fprintf(f, " %8s %8s %6s %8s %9s %7s", "n/a", "n/a", "", "n/a", "n/a", "n/a");
  std::fprintf(f, "\n  %-15s %9.3f %9.3f   (denoise() call, host clock)\n", "frame wall",
               fm["wall"]["median"].get<double>(), fm["wall"]["p95"].get<double>());
  if (fm.contains("device_wall"))
    std::fprintf(f,
                 "  %-15s %9.3f %9.3f   (device path: denoise_device() call to the frame done; "
                 "the call itself %.3f ms)\n",
                 "frame wall", fm["device_wall"]["median"].get<double>(),
                 fm["device_wall"]["p95"].get<double>(), fm["device_call"]["median"].get<double>());
  if (in.contains("young_fraction")) {
    const json& y = in["young_fraction"];
    std::fprintf(f,
                 "  young histories (the variance's 7x7 estimate, in its floor): %.1f%% of the "
                 "surface in the median frame (mean %.1f%%, %.1f to %.1f%%)\n",
                 100 * y["median"].get<double>(), 100 * y["mean"].get<double>(),
                 100 * y["min"].get<double>(), 100 * y["max"].get<double>());
  }
  for (const json& s : e["stages"])
    if (s.contains("per_tap"))
      std::fprintf(f,
                   "  %-15s %.0f taps/px: %.4f ns a tap, %.2f G taps/s, %.0f ops a tap, %.1f%% of "
                   "the float ceiling\n",
                   s["stage"].get<std::string>().c_str(), s["taps_per_px"].get<double>(),
                   s["per_tap"]["ns"].get<double>(), s["per_tap"]["taps_per_s"].get<double>() / 1e9,
                   s["per_tap"]["ops"].get<double>(), s["pct_of_ops"].get<double>());
  // SVGF's CPU a-trous beside the same rows on a frame in the caches: how much of a tap's time
  // the frame's memory adds (1.0: none; the rest is the cores').
  const double resident = e["ceilings"].value("resident_atrous_ns_per_tap", 0.0);
  for (const json& s : e["stages"])
    if (resident > 0 && s["stage"] == "atrous" && s.contains("per_tap"))
      std::fprintf(f,
                   "  %-15s in the caches (1280x64, steps 1 and 2): %.4f ns a tap; the frame's "
                   "take %.2f times as long\n",
                   "atrous", resident, s["per_tap"]["ns"].get<double>() / resident);
  // The same machine's float rate when every operation waits on the one before: the exact
  // a-trous tap is such a chain, of about 30 (docs/benchmarks.md, "CPU: what limits it").
  const double ceiling = e["ceilings"].value("ops_per_s", 0.0);
  if (ceiling > 0 && e["ceilings"].contains("chain_ops_per_s")) {
    const json& chains = e["ceilings"]["chain_ops_per_s"];
    std::string shares;
    for (int length : kDependentChainLengths) {
      const double rate = chains.value(std::to_string(length), 0.0);
      char part[48];
      std::snprintf(part, sizeof part, "%s%d: %.0f%%", shares.empty() ? "" : ", ", length,
                    100 * rate / ceiling);
      shares += part;
    }
    std::fprintf(f,
                 "  float chains    a loop of independent values, each through N dependent "
                 "operations (an exact a-trous tap: about 30), of the float ceiling: %s\n",
                 shares.c_str());
  }
  if (e.contains("peak_device_bytes"))
    std::fprintf(f, "  peak device memory %.1f MiB\n",
                 static_cast<double>(e["peak_device_bytes"].get<size_t>()) / (1 << 20));
  std::fprintf(f,
               "  load average %.2f before, %.2f after; other processes used %.0f%% of the CPUs "
               "while timing\n",
               e["load_before"][0].get<double>(), e["load_after"][0].get<double>(),
               100 * e.value("others_cpu_share", 0.0));
  std::fflush(f);
}

void print_quality(const json& e, std::FILE* f) {
  const json& m = e["mean"];
  auto num = [](const json& v) { return v.is_null() ? std::nan("") : v.get<double>(); };
  std::fprintf(f,
               "  %-34s %-16s PSNR %6.2f dB  SSIM %.4f  relMSE %8.4f  FLIP %.4f  "
               "err-change %.5f  out-change %.5f\n",
               e["label"].get<std::string>().c_str(), e["scene"].get<std::string>().c_str(),
               num(m["psnr"]), num(m["ssim"]), num(m["relmse"]), num(m["flip"]),
               num(m["error_change"]), num(m["output_change"]));
  if (e.contains("blocks")) {
    const json& b = e["blocks"];
    const double n = std::max(1.0, b["blocks"].get<double>());
    std::fprintf(f,
                 "  %-34s blocks %lld: rank-deficient %.1f%%, empty %.1f%%; max/min |R_ii| "
                 "median %.3g, p95 %.3g, max %.3g\n",
                 "", static_cast<long long>(b["blocks"].get<int64_t>()),
                 100 * b["rank_deficient"].get<double>() / n, 100 * b["empty"].get<double>() / n,
                 b["condition_median"].get<double>(), b["condition_p95"].get<double>(),
                 b["condition_max"].get<double>());
  }
  std::fflush(f);
}

}  // namespace svgf::bench

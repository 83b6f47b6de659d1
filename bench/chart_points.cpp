#include "bench/chart_points.h"

#include <cmath>

namespace svgf::bench {
namespace {

std::string short_label(const std::string& key) {
  if (key.rfind("svgf ", 0) == 0) {
    const size_t it = key.find(" it");
    return key.substr(it + 1);
  }
  return key;
}

}  // namespace

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
      p.time_ms = median_ms(*e);
      p.p95_ms = p95_ms(*e);
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
  add("cpu_wavelet", "cpu", "wavelet", "", "", "");
  add("cuda_exact_wavelet", "gpu", "wavelet", "exact", "cuda", "cpu");
  add("cuda_fast_wavelet", "gpu", "wavelet", "fast", "", "");
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

}  // namespace svgf::bench

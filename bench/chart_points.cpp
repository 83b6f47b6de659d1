#include "bench/chart_points.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <sstream>

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

std::string series_of(const json& e) {
  const json& c = e["config"];
  const std::string mode = c.value("mode", "");
  if (mode == "opencv") return "baselines";
  const std::string plat = c.value("backend", "") == "cuda" ? "cuda_" + mode : "cpu";
  const std::string method = c.value("method", "");
  if (method == "svgf") return plat == "cpu" ? "cpu_exact" : plat;
  return plat + "_" + (method == "jbf-atrous" ? "jbf" : method);
}

std::string platform(const Point& p) { return p.series.rfind("cuda", 0) == 0 ? "gpu" : "cpu"; }

namespace {

// Quality of configuration `key` over the scenes; a CUDA exact configuration measured only on
// the CPU has the CPU's (exact mode is bitwise equal on both backends).
Quality quality_of(const Results& r, const json& e) {
  const std::string key = e["key"].get<std::string>();
  auto by_scene = r.quality(key);
  const json& c = e["config"];
  if (by_scene.empty() && c.value("backend", "") == "cuda" && c.value("mode", "") == "exact") {
    std::string k = key;
    k.replace(k.find("cuda"), 4, "cpu");
    by_scene = r.quality(k);
  }
  // The evaluation set is measured CPU exact only: CUDA fast, which differs from exact in the
  // 8th digit of the means on the fixtures (docs/benchmarks.md), takes exact's quality there.
  if (by_scene.empty() && !r.eval_quality.is_null() && c.value("backend", "") == "cuda" &&
      key.find("cuda fast") != std::string::npos) {
    std::string k = key;
    k.replace(k.find("cuda fast"), 9, "cpu exact");
    by_scene = r.quality(k);
  }
  // On the evaluation set, the scenes whose reference is too noisy to rank methods are left out
  // (eval_quality.h): the chart's quality is the clean scenes' mean.
  if (!r.eval_quality.is_null())
    for (const json& left_out : r.eval_quality["left_out_scenes"])
      by_scene.erase(left_out["scene"].get<std::string>());
  return aggregate(by_scene);
}

// The entries of a section at its suite's chart size and scene (results from before the suites
// recorded them have every chart entry at that size and scene).
std::vector<const json*> at_chart_size(const Results& r, const std::string& suite,
                                       const std::string& section) {
  std::vector<const json*> v;
  const json* doc = r.suite(suite);
  const std::string size = doc ? doc->value("chart_size", "") : "";
  const std::string scene = doc ? doc->value("chart_scene", "") : "";
  for (const json* e : r.timings(suite, section))
    if ((size.empty() || size_of(*e) == size) &&
        (scene.empty() || (*e)["input"].value("scene", "") == scene))
      v.push_back(e);
  return v;
}

size_t series_index(const std::string& series) {
  size_t i = 0;
  while (i < std::size(kSeries) && series != kSeries[i]) ++i;
  return i;
}

}  // namespace

std::vector<Point> chart_points(const Results& r) {
  std::vector<Point> pts;
  for (const char* suite : {"cpu", "gpu"})
    for (const char* section : {"chart", "baselines", "wavelet", "jbf", "bmfr"})
      for (const json* e : at_chart_size(r, suite, section)) {
        // The bmfr section's SVGF entry is the reference of a target, not a chart point.
        if (std::string(section) == "bmfr" && (*e)["config"].value("method", "") != "bmfr")
          continue;
        Point p;
        p.series = series_of(*e);
        p.key = (*e)["key"].get<std::string>();
        p.label = short_label(p.key);
        p.time_ms = median_ms(*e);
        p.p95_ms = p95_ms(*e);
        p.size = size_of(*e);
        p.q = quality_of(r, *e);
        pts.push_back(p);
      }
  std::stable_sort(pts.begin(), pts.end(), [](const Point& a, const Point& b) {
    return series_index(a.series) < series_index(b.series);
  });
  mark_pareto_fronts(pts);
  return pts;
}

void mark_pareto_fronts(std::vector<Point>& pts) {
  // A point is dominated when another of its platform is at least as fast and as good, and
  // strictly one of the two: equal points (a tie in both) are both on the front.
  for (Point& p : pts) {
    p.pareto_psnr = p.pareto_flip = false;
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
}

const StudyRow* KernelStudy::find(StudyRow::Kind kind) const {
  for (const StudyRow& row : rows)
    if (row.kind == kind) return &row;
  return nullptr;
}

KernelStudy kernel_study(const Results& r) {
  std::map<std::pair<int, int>, StudyRow> rows;  // (kind, kernel size) -> row
  KernelStudy study;
  for (const char* suite : {"cpu", "gpu"})
    for (const json* e : at_chart_size(r, suite, "wavelet")) {
      const json& c = (*e)["config"];
      const std::string method = c.value("method", "");
      std::ostringstream name;
      StudyRow::Kind kind;
      int kernel;
      if (method == "wavelet") {
        kind = StudyRow::Wavelet;
        kernel = c["kernel_size"].get<int>();
        name << kernel << "x" << kernel << " wavelet, " << c["iterations"].get<int>() << " passes";
      } else if (method == "gaussian") {
        kind = StudyRow::Gaussian;
        kernel = 2 * c["radius"].get<int>() + 1;
        name.precision(3);
        name << kernel << "x" << kernel << " Gaussian, sigma " << c["sigma"].get<double>()
             << " (separable)";
      } else if (method == "jbf") {
        kind = StudyRow::Dense;
        kernel = 2 * c["radius"].get<int>() + 1;
        name << kernel << "x" << kernel << " JBF (dense, no history)";
      } else {
        continue;
      }
      StudyRow& row = rows[{kind, kernel}];
      row.kind = kind;
      row.name = name.str();
      const bool fast = c.value("mode", "") == "fast";
      const int col = std::string(suite) == "cpu" ? 0 : (fast ? 2 : 1);
      row.ms[col] = median_ms(*e);
      const Quality q = quality_of(r, *e);
      if (fast)
        row.fast = q;
      else if (q.scenes > 0)
        row.exact = q;
      const std::string at = std::string(suite) + " " + size_of(*e);
      if (study.sizes.find(at) == std::string::npos)
        study.sizes += (study.sizes.empty() ? "" : ", ") + at;
    }
  for (auto& [k, row] : rows) study.rows.push_back(row);
  return study;
}

}  // namespace svgf::bench

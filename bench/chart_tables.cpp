#include "bench/chart_tables.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

namespace fs = std::filesystem;

namespace svgf::bench {
namespace {

std::string underscores(std::string s) {
  for (char& c : s)
    if (c == ' ') c = '_';
  return s;
}

}  // namespace

void write_text_file(const fs::path& path, const std::string& text) {
  std::ofstream f(path);
  if (!f) throw std::runtime_error("cannot write " + path.string());
  f << text;
}

void write_points(const fs::path& out, const std::vector<Point>& pts) {
  for (const char* series : kSeries) {
    std::ostringstream s;
    s << "# time_ms psnr_db flip ssim relmse label pareto_psnr pareto_flip (1: on its platform's "
         "front)\n";
    for (const Point& p : pts)
      if (p.series == series && std::isfinite(p.q.psnr))
        s << p.time_ms << ' ' << p.q.psnr << ' ' << p.q.flip << ' ' << p.q.ssim << ' ' << p.q.relmse
          << " \"" << p.label << "\" " << p.pareto_psnr << ' ' << p.pareto_flip << "\n";
    write_text_file(out / (std::string("points_") + series + ".dat"), s.str());
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
      write_text_file(
          out / ((which == 0 ? "pareto_psnr_" : "pareto_flip_") + std::string(plat) + ".dat"),
          s.str());
    }
}

// Per-frame curves of each fixture scene: one file per scene and metric, one column per config.
void write_error_curves(const fs::path& out, const Results& r) {
  std::vector<std::string> keys = {"noisy input", kDefaultCpu,   kDefaultFast, kWaveletCpu,
                                   kJbfCpu,       kJbfAtrousCpu, kBmfrCpu};
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
      write_text_file(out / ("errors_" + scene + "_" + metric + ".dat"), s.str());
    }
  write_text_file(out / "scenes.txt", [&] {
    std::string t;
    for (const std::string& s : scenes) t += s + "\n";
    return t;
  }());
}

void write_scaling(const fs::path& out, const Results& r) {
  auto series = [&](const std::string& file, const std::vector<const json*>& es) {
    std::ostringstream s;
    s << "# megapixels median_ms p95_ms size\n";
    for (const json* e : es)
      s << mpix(*e) << ' ' << median_ms(*e) << ' ' << p95_ms(*e) << " \"" << size_of(*e) << "\"\n";
    write_text_file(out / file, s.str());
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
      s << it << ' ' << median_ms(*e) << ' ' << p95_ms(*e) << " \"" << size_of(*e) << "\"\n";
    }
    write_text_file(out / file, s.str());
  };
  iterations("scaling_iterations_cpu.dat", r.timings("cpu", "chart"));
  std::vector<const json*> it_exact, it_fast;
  for (const json* e : r.timings("gpu", "iterations"))
    ((*e)["config"]["mode"] == "fast" ? it_fast : it_exact).push_back(e);
  iterations("scaling_iterations_cuda_exact.dat", it_exact);
  iterations("scaling_iterations_cuda_fast.dat", it_fast);
}

void write_kernel_study(const fs::path& out, const Results& r) {
  const KernelStudy study = kernel_study(r);
  const char* const platforms[] = {"cpu", "cuda_exact", "cuda_fast"};
  const std::pair<StudyRow::Kind, const char*> filters[] = {
      {StudyRow::Wavelet, "wavelet"}, {StudyRow::Gaussian, "gaussian"}, {StudyRow::Dense, "dense"}};
  for (int col = 0; col < 3; ++col)
    for (const auto& [kind, filter] : filters) {
      std::ostringstream s;
      s << "# time_ms psnr_db flip label\n";
      for (const StudyRow& row : study.rows) {
        const Quality& q = col == 2 ? row.fast : row.exact;
        if (row.kind == kind && std::isfinite(row.ms[col]) && std::isfinite(q.psnr))
          s << row.ms[col] << ' ' << q.psnr << ' ' << q.flip << " \"" << row.name << "\"\n";
      }
      write_text_file(out / ("kernel_study_" + std::string(platforms[col]) + "_" + filter + ".dat"),
                      s.str());
    }
}

}  // namespace svgf::bench

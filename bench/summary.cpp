#include "bench/summary.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <sstream>

#include "bench/stage_cost.h"
#include "bench/targets.h"
#include "methods/bmfr/denoiser.h"

namespace svgf::bench {
namespace {

std::string fmt(double v, int digits) {
  if (!std::isfinite(v)) return "-";
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(digits);
  s << v;
  return s.str();
}

void stage_table(std::ostringstream& md, const json& e) {
  md << "\n**" << e["label"].get<std::string>() << "** at " << size_of(e) << " — "
     << e["description"].get<std::string>() << "; " << e["frames"].get<int>() << " frames after "
     << e["warmup"].get<int>() << " warm-up; load " << fmt(e["load_before"][0].get<double>(), 2)
     << " → " << fmt(e["load_after"][0].get<double>(), 2) << "; other processes used "
     << fmt(100 * e.value("others_cpu_share", 0.0), 0) << "% of the CPUs while timing\n\n";
  md << "| stage | median ms | p95 ms | MP/s | B/px read | B/px written | GB/s | % of copy | "
        "ops/px | % of float rate | floor ms | bound | × floor |\n";
  md << "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---:|\n";
  for (const json& s : e["stages"]) {
    md << "| " << s["stage"].get<std::string>() << " | " << fmt(s["ms"]["median"].get<double>(), 4)
       << " | " << fmt(s["ms"]["p95"].get<double>(), 4) << " | "
       << fmt(s["mpix_per_s"].get<double>(), 0) << " | ";
    if (!s.contains("bytes_read_per_px")) {  // no cost model for this method's stages
      md << "n/a | n/a | n/a | n/a | n/a | n/a | n/a | n/a | n/a |\n";
      continue;
    }
    md << fmt(s["bytes_read_per_px"].get<double>(), 0) << " | "
       << fmt(s["bytes_written_per_px"].get<double>(), 0) << " | "
       << fmt(s["achieved_gbs"].get<double>(), 1) << " | ";
    if (s["host_link"].get<bool>()) {
      md << "(host link) | - | - | - | - | - |\n";
      continue;
    }
    md << fmt(s["pct_of_copy_bw"].get<double>(), 1) << " | "
       << fmt(s["ops_per_px"].get<double>(), 0) << " | " << fmt(num(s.value("pct_of_ops", json())), 1)
       << " | " << fmt(s["floor"]["floor_ms"].get<double>(), 4) << " | "
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
       << fmt(e["floor"]["ops_per_px"].get<double>(), 0) << " | | "
       << fmt(e["floor"]["floor_ms"].get<double>(), 4) << " | | "
       << fmt(e["floor"]["ratio"].get<double>(), 2) << " |\n";
  else
    md << "n/a | | n/a | | n/a | | n/a | | n/a |\n";
  md << "| frame (wall, denoise() call) | " << fmt(f["wall"]["median"].get<double>(), 4) << " | "
     << fmt(f["wall"]["p95"].get<double>(), 4) << " | | | | | | | | | | |\n";
  if (e.contains("peak_device_bytes"))
    md << "\nPeak device memory of the denoiser: "
       << fmt(static_cast<double>(e["peak_device_bytes"].get<size_t>()) / (1 << 20), 1)
       << " MiB.\n";
}

// The CIS 565 kernel-size study: the wavelet filter's time and quality by kernel size beside its
// 9x9 comparisons, each row's time as a multiple of theirs, so that equal time can be read off.
std::string short_name(const StudyRow& ref) {
  return ref.kind == StudyRow::Gaussian ? "Gaussian" : "dense JBF";
}

void kernel_size_table(std::ostringstream& md, const Results& r) {
  const KernelStudy study = kernel_study(r);
  if (study.rows.empty()) return;
  const StudyRow* refs[] = {study.find(StudyRow::Gaussian), study.find(StudyRow::Dense)};
  md << "\n## Wavelet kernel sizes (CIS 565 study) against a 9x9 Gaussian, median ms per frame\n\n"
        "Times at "
     << study.sizes
     << "; quality: mean over the fixture scenes (exact mode is bitwise equal on both "
        "backends). For each reference filter, × is the row's time over the reference's on "
        "each platform (CPU / CUDA exact / CUDA fast; at most 1: no slower) and Δ is the row's "
        "PSNR minus the reference's: a row with × at most 1 and Δ above 0 gives more quality "
        "for the same time.";
  for (const StudyRow* ref : refs)
    if (ref)
      md << " " << ref->name << ": " << fmt(ref->ms[0], 1) << " / " << fmt(ref->ms[1], 4) << " / "
         << fmt(ref->ms[2], 4) << " ms, " << fmt(ref->exact.psnr, 2) << " dB.";
  md << "\n\n| filter | CPU ms | CUDA exact ms | CUDA fast ms | PSNR dB | FLIP | SSIM | PSNR dB "
        "(fast) |";
  for (const StudyRow* ref : refs)
    if (ref) md << " × " << short_name(*ref) << " | Δ dB |";
  md << "\n|---|---:|---:|---:|---:|---:|---:|---:|";
  for (const StudyRow* ref : refs)
    if (ref) md << "---|---:|";
  md << "\n";
  for (const StudyRow& row : study.rows) {
    md << "| " << row.name << " | " << fmt(row.ms[0], 1) << " | " << fmt(row.ms[1], 4) << " | "
       << fmt(row.ms[2], 4) << " | " << fmt(row.exact.psnr, 2) << " | " << fmt(row.exact.flip, 4)
       << " | " << fmt(row.exact.ssim, 4) << " | " << fmt(row.fast.psnr, 2) << " |";
    for (const StudyRow* ref : refs) {
      if (!ref) continue;
      md << ' ';
      for (int col = 0; col < 3; ++col)
        md << (col ? " / " : "") << fmt(row.ms[col] / ref->ms[col], 2);
      md << " | " << fmt(row.exact.psnr - ref->exact.psnr, 2) << " |";
    }
    md << "\n";
  }
}

// What a filter's tap costs (stages with a tap count: SVGF's and the JBF's a-trous, the JBF's
// full window, the wavelet's passes) against the machine's float rate and copy bandwidth. The
// SVGF rows are the sizes section's at the sizes the other filters were timed at.
void per_tap_table(std::ostringstream& md, const Results& r) {
  std::vector<const json*> entries;
  for (const char* suite : {"gpu", "cpu"}) {
    std::vector<std::string> sizes;
    for (const char* section : {"jbf", "wavelet"})
      for (const json* e : r.timings(suite, section)) {
        entries.push_back(e);
        sizes.push_back(size_of(*e));
      }
    for (const json* e : r.timings(suite, "sizes"))
      if (std::find(sizes.begin(), sizes.end(), size_of(*e)) != sizes.end()) entries.push_back(e);
  }
  std::ostringstream rows;
  for (const json* e : entries)
    for (const json& s : (*e)["stages"]) {
      if (!s.contains("per_tap")) continue;
      const json& t = s["per_tap"];
      rows << "| " << (*e)["label"].get<std::string>() << " | " << size_of(*e) << " | "
           << s["stage"].get<std::string>() << " | " << fmt(s["ms"]["median"].get<double>(), 3)
           << " | " << fmt(s["taps_per_px"].get<double>(), 0) << " | "
           << fmt(t["ns"].get<double>(), 4) << " | " << fmt(t["taps_per_s"].get<double>() / 1e9, 3)
           << " | " << fmt(t["ops"].get<double>(), 0) << " | " << fmt(t["bytes"].get<double>(), 2)
           << " | " << fmt(s["pct_of_ops"].get<double>(), 1) << " | "
           << fmt(s["pct_of_copy_bw"].get<double>(), 1) << " | "
           << s["floor"]["bound"].get<std::string>() << " | "
           << fmt(s["floor"]["ratio"].get<double>(), 2) << " |\n";
    }
  if (rows.str().empty()) return;
  md << "\n## Cost a tap (filter stages, bench/stage_cost.cpp)\n\nA tap is one neighbour of one "
        "surface pixel (taps a pixel: the model's steady-state count times the surface "
        "fraction). ns a tap: the stage's median time over the frame's taps; ops and bytes a tap: "
        "the counted operations and bytes of the stage over its taps; % of float rate: the "
        "counted operations a second against the measured ceiling (CPU: mul+add chains; GPU: "
        "FP32 FMA instructions); % of copy: the counted bytes a second against the measured "
        "copy bandwidth.\n\n| configuration | size | stage | median ms | taps/px | ns a tap | "
        "G taps/s | ops a tap | bytes a tap | % of float rate | % of copy | bound | × floor "
        "|\n|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---|---:|\n"
     << rows.str();
}

// A reading as "0.4970 ms", with its label in front when it has one.
std::string written(const Reading& r) {
  return (r.label.empty() ? "" : r.label + " ") + fmt(r.value, r.digits) + r.unit;
}

void targets_table(std::ostringstream& md, const std::vector<TargetResult>& targets) {
  md << "\n## Targets (bench/targets.json)\n\n| target | measured | verdict | source |\n"
        "|---|---|---|---|\n";
  for (const TargetResult& t : targets) {
    md << "| " << t.target << " | ";
    if (t.verdict == Verdict::NotMeasured) {
      md << "- | not measured | " << t.source << " |\n";
      continue;
    }
    md << written(t.measured);
    for (size_t i = 0; i < t.context.size(); ++i)
      md << (i == 0 ? " (" : "; ") << written(t.context[i])
         << (i + 1 == t.context.size() ? ")" : "");
    md << " | **" << to_string(t.verdict) << "** | " << t.source << " |\n";
  }
}

// How often a block-fitting method's blocks were rank-deficient, and how well conditioned the
// fits were, per fixture scene (quality entries with "blocks": BMFR's).
void block_table(std::ostringstream& md, const Results& r) {
  std::vector<std::string> keys;
  for (const char* suite : {"gpu", "cpu"})
    if (const json* doc = r.suite(suite))
      for (const json& e : doc->value("quality", json::array()))
        if (e.contains("blocks") && !e.contains("error") &&
            std::find(keys.begin(), keys.end(), e["key"]) == keys.end())
          keys.push_back(e["key"]);
  if (keys.empty()) return;
  md << "\n## Blocks of the block-fitting methods per fixture scene\n\nEvery block of every "
        "frame: rank-deficient, a column dropped (skip: under the threshold against the "
        "block's largest column; either strategy: numerically zero); empty, no sample in the "
        "block (its pixels pass through); max/min |R_ii|, over the kept columns of the blocks "
        "that fitted something (a lower bound of the condition number).\n\n| configuration | "
        "scene | blocks | rank-deficient | empty | max/min abs(R_ii) median | p95 | max "
        "|\n|---|---|---:|---:|---:|---:|---:|---:|\n";
  for (const std::string& k : keys)
    for (const auto& [scene, e] : r.quality(k)) {
      if (!e.contains("blocks")) continue;
      const json& b = e["blocks"];
      const double n = std::max(1.0, num(b["blocks"]));
      md << "| " << k << " | " << scene << " | " << fmt(num(b["blocks"]), 0) << " | "
         << fmt(100 * num(b["rank_deficient"]) / n, 1) << "% | "
         << fmt(100 * num(b["empty"]) / n, 1) << "% | " << fmt(num(b["condition_median"]), 1)
         << " | " << fmt(num(b["condition_p95"]), 1) << " | " << fmt(num(b["condition_max"]), 1)
         << " |\n";
    }
}

// The bmfr sections: each entry's stages, frame and floor at a glance (the per-stage tables
// below have the rest).
void bmfr_table(std::ostringstream& md, const Results& r) {
  const char* const stages[] = {"sanitize", "accumulate", "regression", "weighted_sum", "post"};
  std::ostringstream rows;
  for (const char* suite : {"gpu", "cpu"})
    for (const json* e : r.timings(suite, "bmfr")) {
      rows << "| " << (*e)["label"].get<std::string>() << " | " << size_of(*e) << " | "
           << (*e)["input"].value("scene", "") << " |";
      for (const char* name : stages) {
        double ms = NAN;
        for (const json& st : (*e)["stages"])
          if (st["stage"] == name) ms = st["ms"]["median"].get<double>();
        rows << ' ' << fmt(ms, ms < 10 ? 4 : 1) << " |";
      }
      const double m = median_ms(*e);
      const bool floor = e->contains("floor");
      rows << " **" << fmt(m, m < 10 ? 4 : 1) << "** | " << fmt(p95_ms(*e), m < 10 ? 4 : 1)
           << " | " << (floor ? fmt((*e)["floor"]["floor_ms"].get<double>(), 4) : "n/a") << " | "
           << (floor ? fmt((*e)["floor"]["ratio"].get<double>(), 2) : "n/a") << " |\n";
    }
  if (rows.str().empty()) return;
  md << "\n## BMFR (bmfr sections), median ms per stage and frame\n\nThe sections' SVGF entry "
        "(its own stages) is the reference of the CPU target, timed in the same sitting.\n\n"
        "| configuration | size | scene | sanitize | accumulate | regression | weighted sum | "
        "post | frame | p95 | floor ms | × floor |\n"
        "|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n"
     << rows.str();
}

}  // namespace

namespace {

// Each platform's front, fastest first, with a sentence the docs can take over.
void pareto_fronts(std::ostringstream& md, const std::vector<Point>& pts) {
  md << "\n## Pareto fronts\n\nA configuration is on its platform's front when no other of "
        "that platform is both at least as fast and at least as good (and strictly one of them).\n";
  for (const char* plat : {"gpu", "cpu"})
    for (int which = 0; which < 2; ++which) {
      std::vector<const Point*> front;
      for (const Point& p : pts)
        if (platform(p) == plat && (which == 0 ? p.pareto_psnr : p.pareto_flip)) front.push_back(&p);
      std::sort(front.begin(), front.end(),
                [](const Point* a, const Point* b) { return a->time_ms < b->time_ms; });
      md << "\n**" << (std::string(plat) == "gpu" ? "GPU" : "CPU") << ", "
         << (which == 0 ? "PSNR" : "FLIP") << "** (" << front.size() << "): ";
      for (size_t i = 0; i < front.size(); ++i)
        md << (i ? ", " : "") << "`" << front[i]->key << "` (" << fmt(front[i]->time_ms, 3)
           << " ms, " << (which == 0 ? fmt(front[i]->q.psnr, 2) + " dB" : fmt(front[i]->q.flip, 4))
           << ")";
      md << ".\n";
      if (front.size() >= 2)
        md << "Template: \"On the " << (std::string(plat) == "gpu" ? "GPU" : "CPU") << ", going from `" << front.front()->key << "` to `"
           << front.back()->key << "` buys "
           << (which == 0 ? fmt(front.back()->q.psnr - front.front()->q.psnr, 2) + " dB PSNR"
                          : fmt(front.front()->q.flip - front.back()->q.flip, 4) + " FLIP")
           << " for " << fmt(front.back()->time_ms / front.front()->time_ms, 1)
           << "x the time; every configuration off the front is beaten in both by one on it.\"\n";
    }
}

// The evaluation set's means over all scenes and over the clean-reference scenes, each scene's
// reference noise, and which scenes were left out and why (eval_quality.h).
void eval_set_means(std::ostringstream& md, const Results& r) {
  const json& q = r.eval_quality;
  const json& scenes = q["set"]["scenes"];
  md << "\n## Evaluation set means\n\nSet: " << q["set"]["dir"].get<std::string>() << ", "
     << scenes.size() << " scenes";
  if (!scenes.empty())
    md << ", " << scenes[0]["width"] << "x" << scenes[0]["height"] << ", " << scenes[0]["frames"]
       << " frames, " << scenes[0]["reference_spp"] << "-spp references";
  md << "; " << q.value("backend", "") << ", SVGF split " << q.value("svgf_split", "")
     << "; measured " << q.value("started", "") << " on " << q["host"].value("cpu_model", "")
     << " (`" << q.value("command", "") << "`).\n\nReference noise per scene (mean MSE over the "
        "frames, from each reference's two halves, as PSNR; the share of it at PSNR's clamp):";
  for (const json& s : scenes)
    md << (&s == &scenes[0] ? " " : ", ") << "`" << s["scene"].get<std::string>() << "` "
       << fmt(num(s.value("reference_noise_db", json())), 2) << " dB ("
       << fmt(100 * num(s.value("reference_noise_clamped_share", json())), 1) << "%)";
  md << ".\n\nThe clean means' PSNR has each frame's reference noise taken out (`psnr_corrected`:"
        " the PSNR against the true image); FLIP is as measured. Left out of the clean means: ";
  const json& left = q["left_out_scenes"];
  if (left.empty()) md << "none";
  for (size_t i = 0; i < left.size(); ++i)
    md << (i ? "; " : "") << "`" << left[i]["scene"].get<std::string>() << "`: "
       << left[i].value("why", "");
  md << ".\n\n| configuration | PSNR dB, all (measured) | PSNR dB, clean (measured) | "
        "PSNR dB, clean (corrected) | FLIP, all | FLIP, clean |\n|---|---:|---:|---:|---:|---:|\n";
  for (const json& m : q["means"])
    md << "| " << m["key"].get<std::string>() << " | " << fmt(num(m["all"]["psnr"]), 2) << " | "
       << fmt(num(m["clean"].value("psnr_measured", json())), 2) << " | "
       << fmt(num(m["clean"]["psnr"]), 2) << " | " << fmt(num(m["all"]["flip"]), 4) << " | "
       << fmt(num(m["clean"]["flip"]), 4) << " |\n";
}

}  // namespace

std::string summary_markdown(const Results& r, const std::vector<Point>& pts,
                             const std::vector<TargetResult>& targets) {
  std::ostringstream md;
  md << "# Benchmark results (generated by `svgf-bench chart-data`; do not edit)\n";
  if (const json* cpu = r.suite("cpu")) {
    const json& h = (*cpu)["host"];
    md << "\n## CPU machine\n\n"
       << h.value("cpu_model", "?") << ", " << h.value("hardware_threads", 0)
       << " hardware threads (host " << h.value("hostname", "?")
       << ").\n\nMeasured ceilings:\n\n| threads | memcpy GB/s (read + write) | float ops/s "
          "(mul+add chains, "
       << h.value("cpu_kernels", "AVX2") << ", no FMA) |\n|---:|---:|---:|\n";
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

  targets_table(md, targets);

  // The default scene against a full-coverage one, same configuration and size.
  {
    std::vector<const json*> cov;
    for (const char* s : {"gpu", "cpu"})
      for (const json* e : r.timings(s, "coverage")) cov.push_back(e);
    if (!cov.empty()) {
      md << "\n## Coverage check (default scene against a scene with a surface at every "
            "pixel)\n\n| configuration | size | scene | surface | median ms | p95 ms | floor ms | "
            "× floor |\n|---|---|---|---:|---:|---:|---:|---:|\n";
      // Older results lack input.surface_fraction: it follows from the a-trous stage's bytes
      // read per pixel, which are linear in it (bench/stage_cost.h) and, unlike its operation
      // counts (refined since: inferred from them, camera-pan read as 103%), have the model's
      // values of the time.
      auto surface_of = [&](const json& e) {
        if (e["input"].contains("surface_fraction"))
          return e["input"]["surface_fraction"].get<double>();
        SvgfParams p;
        p.iterations = e["config"]["iterations"].get<int>();
        p.feedback_tap = e["config"]["feedback_tap"].get<int>();
        const Mode mode = e["config"]["mode"] == "fast" ? Mode::Fast : Mode::Exact;
        for (const json& st : e["stages"])
          if (st["stage"] == "atrous") {
            // Fast mode's last iteration reads the emission too when the frames have it.
            const bool emission =
                mode == Mode::Fast && e["stages"][0]["bytes_read_per_px"].get<double>() >
                                          stage_cost(mode, Stage::Demodulate, p, false, 1.0).read;
            const double read0 = stage_cost(mode, Stage::Atrous, p, emission, 0.0).read;
            const double read1 = stage_cost(mode, Stage::Atrous, p, emission, 1.0).read;
            const double read = st["bytes_read_per_px"].get<double>();
            return read1 > read0 ? (read - read0) / (read1 - read0) : 1.0;
          }
        return 1.0;
      };
      auto row = [&](const json& e) {
        md << "| " << e["label"].get<std::string>() << " | " << size_of(e) << " | "
           << e["input"]["scene"].get<std::string>() << " | " << fmt(100 * surface_of(e), 0)
           << "% | " << fmt(median_ms(e), 4) << " | " << fmt(p95_ms(e), 4) << " | "
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

  std::map<std::pair<int, int>, const json*> cpu;  // (width, threads)
  for (const json* e : r.timings("cpu", "sizes"))
    cpu[{(*e)["input"]["width"].get<int>(), (*e)["config"]["threads"].get<int>()}] = e;
  int tmax = 1;
  for (const auto& [k, e] : cpu) tmax = std::max(tmax, k.second);
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
  const bool on_eval = !r.eval_quality.is_null();
  md << "\n## Quality against time (the chart's numbers)\n\nTime: median filter time per frame "
        "at the chart size; quality: mean over "
     << (on_eval ? "the evaluation set's clean-reference scenes (below)" : "the fixture scenes")
     << " of each scene's mean over its frames. Output change is on the static scene ("
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

  pareto_fronts(md, pts);
  if (on_eval) eval_set_means(md, r);
  kernel_size_table(md, r);
  per_tap_table(md, r);
  bmfr_table(md, r);

  // Quality per scene of the default configurations.
  md << "\n## Quality per fixture scene (mean over frames)\n\n| configuration | scene | frames | "
        "PSNR dB | SSIM | relMSE | FLIP | error change | output change "
        "|\n|---|---|---:|---:|---:|---:|---:|---:|---:|\n";
  std::vector<std::string> keys = {"noisy input", kDefaultCpu,   kDefaultExact, kDefaultFast,
                                   kWaveletCpu,   kWaveletFast,  kJbfCpu,       kJbfAtrousCpu,
                                   kBmfrCpu,      kBmfrSkipCpu,  kBmfrFast};
  for (const json* e : r.timings("cpu", "baselines")) keys.push_back((*e)["key"]);
  for (const std::string& k : keys)
    for (const auto& [scene, e] : r.quality(k)) {
      const json& m = e["mean"];
      md << "| " << k << " | " << scene << " | " << e["frames"].size() << " | "
         << fmt(num(m["psnr"]), 2) << " | " << fmt(num(m["ssim"]), 4) << " | "
         << fmt(num(m["relmse"]), 4) << " | " << fmt(num(m["flip"]), 4) << " | "
         << fmt(num(m["error_change"]), 5) << " | " << fmt(num(m["output_change"]), 5) << " |\n";
    }

  block_table(md, r);

  // The cost model every floor above comes from.
  md << "\n## Cost model (bench/stage_cost.cpp), per pixel, default parameters (SVGF: 4 "
        "iterations, feedback tap 1, frames with emission planes, then each stage off by default "
        "and the reprojection under each anti-lag, at 1920x1080 (the gradient stages: surface "
        "column a stratum with a sample, background one without); then the other methods' filter "
        "stages; then BMFR's stages at 1920x1080, its regression a row of its blocks (1024 rows, "
        "the grid sticking out of the image: "
     << fmt(bmfr_blocks_per_px(1920, 1080) * 1024, 3)
     << " rows a pixel) and each block's own work and output)\n\n| mode | stage | surface "
        "pixel: bytes read | written | ops | background pixel: bytes read | written | ops | "
        "planes |\n|---|---|---:|---:|---:|---:|---:|---:|---|\n";
  const SvgfParams defaults;
  // Exact mode as the CPU stores it (planes), as CUDA does (packed pixels: only the stages
  // that differ), and fast mode.
  const struct {
    Mode mode;
    bool packed;
    const char* name;
  } models[] = {{Mode::Exact, false, "exact"},
                {Mode::Exact, true, "exact, CUDA (packed)"},
                {Mode::Fast, false, "fast"}};
  for (const auto& model : models) {
    const Mode mode = model.mode;
    const auto traits = [](double surface, bool packed) {
      FrameTraits f;
      f.emission = true;
      f.surface_fraction = surface;
      f.packed_exact = packed;
      f.fused_outputs = true;  // as both engines run SVGF (methods/svgf/flavors.h)
      return f;
    };
    for (int si = 0; si < kStageCount; ++si) {
      const Stage st = static_cast<Stage>(si);
      const StageCost a = stage_cost(mode, st, defaults, traits(1.0, model.packed));
      const StageCost b = stage_cost(mode, st, defaults, traits(0.0, model.packed));
      if (a.bytes() <= 0 && b.bytes() <= 0) continue;
      if (model.packed && stage_cost(mode, st, defaults, traits(1.0, false)).bytes() == a.bytes() &&
          stage_cost(mode, st, defaults, traits(0.0, false)).bytes() == b.bytes())
        continue;
      md << "| " << model.name << " | " << stage_name(st) << " | " << fmt(a.read, 0) << " | "
         << fmt(a.written, 0) << " | " << fmt(a.ops, 0) << " | " << fmt(b.read, 0) << " | "
         << fmt(b.written, 0) << " | " << fmt(b.ops, 0) << " | " << a.planes << " |\n";
    }
    const StageCost a = frame_cost(mode, defaults, traits(1.0, model.packed));
    const StageCost b = frame_cost(mode, defaults, traits(0.0, model.packed));
    md << "| " << model.name << " | **frame (filter stages)** | " << fmt(a.read, 0) << " | "
       << fmt(a.written, 0) << " | " << fmt(a.ops, 0) << " | " << fmt(b.read, 0) << " | "
       << fmt(b.written, 0) << " | " << fmt(b.ops, 0) << " | |\n";
    if (model.packed) continue;  // the optional stages below: the planes' model
    // The stages off by default, at 1920x1080 (the strata a ninth of the pixels), and the
    // reprojection under each anti-lag (fast: the fused demodulate + reproject).
    const Stage reproject = mode == Mode::Fast ? Stage::Demodulate : Stage::Reproject;
    const struct {
      Stage stage;
      Antilag antilag;
      const char* what;
      bool young = false;
    } optional[] = {{Stage::Gradient, Antilag::Gradient, "--antilag gradient"},
                    {Stage::GradientAtrous, Antilag::Gradient, "--antilag gradient, 3 steps"},
                    {Stage::GradientLambda, Antilag::Gradient, "--antilag gradient"},
                    {reproject, Antilag::Gradient, "--antilag gradient"},
                    {reproject, Antilag::Statistics, "--antilag statistics, radius 2"},
                    {Stage::Variance, defaults.antilag, "a young history: the 7x7 estimate", true},
                    {Stage::SplitSum, Antilag::Off, "split frames"},
                    {Stage::Taa, Antilag::Off, "--svgf-taa on"}};
    for (const auto& o : optional) {
      SvgfParams p = defaults;
      p.antilag = o.antilag;
      p.taa = true;
      FrameTraits f;
      f.emission = true;
      f.gradient_samples = true;
      f.split = true;
      f.width = 1920;
      f.height = 1080;
      f.young_fraction = o.young ? 1.0 : 0.0;
      f.surface_fraction = 1.0;
      const StageCost a = stage_cost(mode, o.stage, p, f);
      f.surface_fraction = 0.0;
      const StageCost b = stage_cost(mode, o.stage, p, f);
      md << "| " << model.name << " | " << stage_name(o.stage) << " (" << o.what << ") | "
         << fmt(a.read, 1) << " | " << fmt(a.written, 1) << " | " << fmt(a.ops, 0) << " | "
         << fmt(b.read, 1) << " | " << fmt(b.written, 1) << " | " << fmt(b.ops, 0) << " | "
         << a.planes << " |\n";
    }
  }
  // The other methods' filter stages at their defaults (their other stages are not counted).
  JbfParams jbf_atrous;
  jbf_atrous.levels = 4;
  const struct {
    const char* what;
    std::function<StageCost(Mode, double)> cost;
  } filters[] = {
      {"jbf filter (radius 16)", [](Mode m, double s) { return jbf_filter_cost(m, JbfParams(), s); }},
      {"jbf-atrous atrous (4 levels)",
       [&](Mode m, double s) { return jbf_filter_cost(m, jbf_atrous, s); }},
      {"wavelet atrous (5x5, 4 passes)",
       [](Mode m, double s) { return wavelet_atrous_cost(m, WaveletParams(), s); }}};
  for (const auto& f : filters)
    for (Mode mode : {Mode::Exact, Mode::Fast}) {
      const StageCost a = f.cost(mode, 1.0), b = f.cost(mode, 0.0);
      md << "| " << to_string(mode) << " | " << f.what << ", " << fmt(a.taps, 0) << " taps | "
         << fmt(a.read, 0) << " | " << fmt(a.written, 0) << " | " << fmt(a.ops, 0) << " | "
         << fmt(b.read, 0) << " | " << fmt(b.written, 0) << " | " << fmt(b.ops, 0) << " | "
         << a.planes << " |\n";
    }
  // BMFR, every stage, at 1080p (the regression's rows and blocks per pixel depend on the size).
  for (Mode mode : {Mode::Exact, Mode::Fast})
    for (const char* stage : {kSanitizeStage, bmfr_stage::kAccumulate, bmfr_stage::kRegression,
                              bmfr_stage::kWeightedSum, bmfr_stage::kPost}) {
      const BmfrParams p;
      const StageCost a = *bmfr_stage_cost(mode, p, stage, true, 1.0, 1920, 1080);
      const StageCost b = *bmfr_stage_cost(mode, p, stage, true, 0.0, 1920, 1080);
      md << "| " << to_string(mode) << " | bmfr " << stage << " (1920x1080) | " << fmt(a.read, 1)
         << " | " << fmt(a.written, 1) << " | " << fmt(a.ops, 0) << " | " << fmt(b.read, 1)
         << " | " << fmt(b.written, 1) << " | " << fmt(b.ops, 0) << " | " << a.planes << " |\n";
    }

  // Per-stage tables.
  md << "\n## Per-stage tables\n\nBytes and operations per pixel come from bench/stage_cost.cpp "
        "(planes each kernel reads and writes once; steady-state path). The floor of a stage is "
        "max(bytes / copy bandwidth, ops / FP32 rate) with the measured ceilings; the frame's "
        "floor is the sum over its stages.\n";
  for (const char* s : {"gpu", "cpu"})
    for (const char* section : {"sizes", "wavelet", "jbf", "bmfr"})
      for (const json* e : r.timings(s, section)) stage_table(md, *e);
  for (const json* e : r.timings("cpu", "baselines")) {
    md << "\n**" << (*e)["label"].get<std::string>() << "** at " << size_of(*e) << ": median "
       << fmt(median_ms(*e), 1) << " ms, p95 " << fmt(p95_ms(*e), 1) << " ms over "
       << (*e)["frames"].get<int>() << " frames (" << (*e)["description"].get<std::string>()
       << ").\n";
  }
  return md.str();
}

}  // namespace svgf::bench

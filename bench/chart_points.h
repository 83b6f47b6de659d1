#pragma once
// Quality against time: one point per timed configuration of the chart sections, with its
// quality over the fixture scenes and whether it is on its platform's Pareto front. Both the
// chart tables and the summary draw from these points.
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "bench/results.h"

namespace svgf::bench {

// The scene whose output change measures flicker on a static view.
inline const char* const kStaticScene = "cornell-static";

// Mean over scenes of each scene's mean; output change on the static scene alone.
struct Quality {
  double psnr = NAN, flip = NAN, ssim = NAN, relmse = NAN, error_change = NAN,
         static_output_change = NAN;
  int scenes = 0;
};
Quality aggregate(const std::map<std::string, json>& by_scene);

struct Point {
  std::string series, key, label;
  double time_ms = NAN, p95_ms = NAN;
  Quality q;
  std::string size;
  bool pareto_psnr = false, pareto_flip = false;
};

// The series, in the order chart_points gives them: SVGF's (the chart sections), the OpenCV
// baselines, then each other method by platform and mode: the wavelet filter's kernel sizes, the
// Gaussian and the JBF (jbf and jbf-atrous), from the wavelet and jbf sections, and BMFR (both
// rank strategies) from the bmfr sections.
inline const char* const kSeries[] = {
    "cpu_exact",    "cuda_exact",          "cuda_fast",         "baselines",
    "cpu_wavelet",  "cuda_exact_wavelet",  "cuda_fast_wavelet", "cpu_gaussian",
    "cuda_exact_gaussian", "cuda_fast_gaussian", "cpu_jbf", "cuda_exact_jbf",
    "cuda_fast_jbf", "cpu_bmfr",          "cuda_exact_bmfr",   "cuda_fast_bmfr"};

// The series of a timing entry: by its method, backend and mode.
std::string series_of(const json& entry);
// "gpu" for the CUDA series, "cpu" for the CPU ones and the OpenCV baselines.
std::string platform(const Point& p);

// A point for every configuration of the chart, baselines, wavelet, jbf and bmfr sections timed
// at its suite's chart size and on its chart scene, grouped by series.
std::vector<Point> chart_points(const Results& r);

// Sets pareto_psnr / pareto_flip: on the front of its platform (platform()) when no other
// point of that platform is both at least as fast and at least as good, and strictly better in
// one (ties in both stay on the front). Points without a time or the metric are never on it.
void mark_pareto_fronts(std::vector<Point>& pts);

// The CIS 565 kernel-size study (the wavelet sections): the wavelet filter at each kernel size
// and its 9x9 comparisons, with their times per platform and quality.
struct StudyRow {
  enum Kind { Wavelet, Gaussian, Dense } kind = Wavelet;
  std::string name;                 // "5x5 wavelet", "9x9 Gaussian (separable, sigma 1.33)"
  double ms[3] = {NAN, NAN, NAN};  // CPU (all threads), CUDA exact, CUDA fast
  Quality exact, fast;
};
struct KernelStudy {
  std::vector<StudyRow> rows;  // wavelet rows by kernel size, then the Gaussian, the dense filter
  std::string sizes;           // where the times were taken: "cpu 1280x720, gpu 1280x720"
  const StudyRow* find(StudyRow::Kind kind) const;  // the first row of `kind`, or nullptr
};
KernelStudy kernel_study(const Results& r);

}  // namespace svgf::bench

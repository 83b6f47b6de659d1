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
// baselines, the wavelet filter's kernel sizes (the wavelet sections).
inline const char* const kSeries[] = {"cpu_exact",        "cuda_exact",  "cuda_fast",
                                      "baselines",        "cpu_wavelet", "cuda_exact_wavelet",
                                      "cuda_fast_wavelet"};

// "gpu" for the CUDA series, "cpu" for the CPU ones and the OpenCV baselines.
std::string platform(const Point& p);

std::vector<Point> chart_points(const Results& r);

}  // namespace svgf::bench

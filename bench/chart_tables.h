#pragma once
// The whitespace-separated tables the gnuplot scripts in bench/chart/ draw (*.dat), and
// scenes.txt, the fixture scenes that have per-frame curves.
#include <filesystem>
#include <string>
#include <vector>

#include "bench/chart_points.h"
#include "bench/results.h"

namespace svgf::bench {

void write_text_file(const std::filesystem::path& path, const std::string& text);

// points_<series>.dat and pareto_<metric>_<platform>.dat: quality against time.
void write_points(const std::filesystem::path& out, const std::vector<Point>& pts);
// errors_<scene>_<metric>.dat: per-frame curves of each fixture scene; scenes.txt.
void write_error_curves(const std::filesystem::path& out, const Results& r);
// scaling_pixels_*.dat and scaling_iterations_*.dat.
void write_scaling(const std::filesystem::path& out, const Results& r);
// kernel_study_<platform>_<filter>.dat: the CIS 565 kernel-size study's quality against time,
// platform cpu, cuda_exact or cuda_fast, filter wavelet (one row a kernel size), gaussian or
// dense (its 9x9 comparisons).
void write_kernel_study(const std::filesystem::path& out, const Results& r);

}  // namespace svgf::bench

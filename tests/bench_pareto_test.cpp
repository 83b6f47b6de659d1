// The Pareto fronts of the quality-against-time charts (bench/chart_points.h).
#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <vector>

#include "bench/chart_points.h"

using namespace svgf::bench;

namespace {

Point point(const std::string& key, const std::string& series, double ms, double psnr, double flip) {
  Point p;
  p.key = key;
  p.series = series;
  p.time_ms = ms;
  p.q.psnr = psnr;
  p.q.flip = flip;
  return p;
}

}  // namespace

TEST_CASE("pareto: a single point is on the front", "[bench][pareto]") {
  std::vector<Point> pts = {point("a", "cpu_exact", 5, 30, 0.1)};
  mark_pareto_fronts(pts);
  CHECK(pts[0].pareto_psnr);
  CHECK(pts[0].pareto_flip);
}

TEST_CASE("pareto: a slower and worse point is dominated", "[bench][pareto]") {
  std::vector<Point> pts = {point("fast good", "cpu_exact", 5, 30, 0.10),
                            point("slow worse", "cpu_exact", 8, 28, 0.12),
                            point("slow better", "cpu_exact", 9, 32, 0.08)};
  mark_pareto_fronts(pts);
  CHECK(pts[0].pareto_psnr);
  CHECK_FALSE(pts[1].pareto_psnr);
  CHECK_FALSE(pts[1].pareto_flip);
  CHECK(pts[2].pareto_psnr);
  CHECK(pts[2].pareto_flip);
  // PSNR higher is better, FLIP lower: a point better in PSNR and worse in FLIP.
  std::vector<Point> mixed = {point("a", "cpu_exact", 5, 30, 0.10),
                              point("b", "cpu_exact", 6, 31, 0.11)};
  mark_pareto_fronts(mixed);
  CHECK(mixed[1].pareto_psnr);
  CHECK_FALSE(mixed[1].pareto_flip);
}

TEST_CASE("pareto: ties", "[bench][pareto]") {
  // Equal in time and quality: neither beats the other, both stay.
  std::vector<Point> pts = {point("a", "cpu_exact", 5, 30, 0.1), point("b", "cpu_wavelet", 5, 30, 0.1)};
  mark_pareto_fronts(pts);
  CHECK(pts[0].pareto_psnr);
  CHECK(pts[1].pareto_psnr);
  // Equal time, lower quality: dominated; equal quality, slower: dominated.
  std::vector<Point> t = {point("a", "cpu_exact", 5, 30, 0.1), point("same time", "cpu_exact", 5, 29, 0.2),
                          point("same quality", "cpu_exact", 7, 30, 0.1)};
  mark_pareto_fronts(t);
  CHECK(t[0].pareto_psnr);
  CHECK_FALSE(t[1].pareto_psnr);
  CHECK_FALSE(t[2].pareto_psnr);
  CHECK_FALSE(t[2].pareto_flip);
}

TEST_CASE("pareto: fronts are per platform; no time or metric, no front", "[bench][pareto]") {
  std::vector<Point> pts = {point("gpu fast", "cuda_fast", 1, 30, 0.1),
                            point("cpu slow worse", "cpu_exact", 50, 25, 0.2),
                            point("no time", "cpu_exact", NAN, 40, 0.01),
                            point("no psnr", "cpu_exact", 60, NAN, 0.3)};
  mark_pareto_fronts(pts);
  CHECK(pts[0].pareto_psnr);
  CHECK(pts[1].pareto_psnr);  // beaten only by a GPU point
  CHECK_FALSE(pts[2].pareto_psnr);
  CHECK_FALSE(pts[3].pareto_psnr);
  CHECK_FALSE(pts[3].pareto_flip);  // slower and worse in FLIP than "cpu slow worse"
}

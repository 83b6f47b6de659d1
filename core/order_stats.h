#pragma once
// Order statistics of per-frame timings (the benchmark's and svgf denoise's timing summary).
#include <algorithm>
#include <cmath>
#include <vector>

namespace svgf {

struct OrderStats {
  double median = 0, p95 = 0, mean = 0, min = 0, max = 0;
  int count = 0;
};

// Median (mean of the middle two for an even count) and p95 by nearest rank: the smallest value
// with at least 95% of the samples at or below it.
inline OrderStats order_stats(std::vector<double> v) {
  OrderStats s;
  s.count = static_cast<int>(v.size());
  if (v.empty()) return s;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  s.median = n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
  const size_t rank = static_cast<size_t>(std::ceil(0.95 * static_cast<double>(n)));
  s.p95 = v[std::min(n, std::max<size_t>(rank, 1)) - 1];
  double sum = 0;
  for (double x : v) sum += x;
  s.mean = sum / static_cast<double>(n);
  s.min = v.front();
  s.max = v.back();
  return s;
}

}  // namespace svgf

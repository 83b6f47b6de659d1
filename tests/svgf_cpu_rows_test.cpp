// The vectorized CPU row drivers must give the per-pixel kernels' bits exactly (the per-pixel
// kernels are what the GPU runs), for every step, border, power and guide oddity.
#include <limits>

#include <catch2/catch.hpp>

#include "methods/svgf/atrous.h"
#include "methods/svgf/variance.h"
#include "kernels_cpu/svgf_rows.h"
#include "kernels_cpu/parallel_for.h"
#include "test_support.h"

using namespace svgf;

namespace {

// A frame with random guides: three depth layers, tilted normals, background holes, mesh ids.
Frame random_guides(int w, int h, uint32_t seed) {
  Frame f = test::flat_frame(w, h);
  test::fill_uniform(f.depth_gradient, -0.05f, 0.05f, seed + 1);
  Image noise(w, h, 4);
  test::fill_uniform(noise, 0.f, 1.f, seed + 2);
  for (int i = 0; i < w * h; ++i) {
    const float u = noise.plane(0)[i];
    f.depth.plane(0)[i] = u < 0.05f ? 0.f : (u < 0.5f ? 2.f + noise.plane(1)[i] * 0.01f : 5.f);
    const float tilt = noise.plane(2)[i] * 0.6f;
    const float n = std::sqrt(1.f + tilt * tilt);
    f.normal.plane(0)[i] = tilt / n;
    f.normal.plane(2)[i] = 1.f / n;
  }
  return f;
}

}  // namespace

TEST_CASE("cpu rows: a-trous rows equal the per-pixel kernel bitwise", "[cpu_rows]") {
  const int sizes[][2] = {{257, 89}, {16, 16}, {3, 2}, {1, 7}, {64, 33}};
  const float phis[] = {128.f, 1.f, 0.f, 100.f};
  uint32_t seed = 0;
  for (const auto& size : sizes) {
    const int w = size[0], h = size[1];
    Frame f = random_guides(w, h, ++seed);
    if (w * h > 100) f.normal.plane(1)[w + 1] = std::numeric_limits<float>::quiet_NaN();
    Image in(w, h, 4), a(w, h, 4, -1.f), b(w, h, 4, -2.f);
    test::fill_uniform(in, 0.f, 3.f, ++seed);
    for (float phi : phis)
      for (int step : {1, 2, 4, 8, 16}) {
        SvgfParams p;
        p.phi_normal = phi;
        const AtrousKernel k{f.guides(), {in.rgb(), in.plane(3)}, {a.rgb(), a.plane(3)}, step, p};
        AtrousKernel k2 = k;
        k2.out = {b.rgb(), b.plane(3)};
        cpu::for_each_pixel(w, h, k);
        cpu::run_atrous_rows(k2, w, h);
        test::require_identical(b, a, "a-trous " + std::to_string(w) + "x" + std::to_string(h) +
                                          " step " + std::to_string(step) + " phi_normal " +
                                          std::to_string(phi));
      }
  }
}

TEST_CASE("cpu rows: spatial variance rows equal the per-pixel kernel bitwise", "[cpu_rows]") {
  const int sizes[][2] = {{257, 89}, {5, 3}, {31, 40}};
  uint32_t seed = 100;
  for (const auto& size : sizes) {
    const int w = size[0], h = size[1];
    const Frame f = random_guides(w, h, ++seed);
    Image acc(w, h, 4), moments(w, h, 2), history(w, h, 1), a(w, h, 4), b(w, h, 4);
    test::fill_uniform(acc, 0.f, 3.f, ++seed);
    test::fill_uniform(moments, 0.f, 2.f, ++seed);
    test::fill_uniform(history, 1.f, 6.f, ++seed);
    for (float& v : history.data()) v = std::floor(v);  // a mix of young (<4) and old history
    for (float phi : {128.f, 3.f}) {
      SvgfParams p;
      p.phi_normal = phi;
      const VarianceKernel k{f.guides(), {acc.rgb(), acc.plane(3)}, moments.plane(0),
                             moments.plane(1), history.plane(0), {a.rgb(), a.plane(3)}, p};
      VarianceKernel k2 = k;
      k2.out = {b.rgb(), b.plane(3)};
      cpu::for_each_pixel(w, h, k);
      cpu::run_variance_rows(k2, w, h);
      test::require_identical(b, a, "variance " + std::to_string(w) + "x" + std::to_string(h));
    }
  }
}

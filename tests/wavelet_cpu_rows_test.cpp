// The wavelet filter's vectorized CPU rows (kernels_cpu/wavelet_rows.cpp) must give the
// per-pixel kernel's bits exactly (the per-pixel kernel is what the GPU runs), for every kernel
// size, step, border, normal power and guide oddity.
#include <limits>
#include <string>

#include <catch2/catch.hpp>

#include "kernels_cpu/parallel_for.h"
#include "kernels_cpu/wavelet_rows.h"
#include "test_support.h"

using namespace svgf;

TEST_CASE("cpu rows: wavelet a-trous rows equal the per-pixel kernel bitwise", "[cpu_rows]") {
  const int sizes[][2] = {{203, 61}, {16, 16}, {3, 2}, {1, 7}, {40, 33}};
  const float nan = std::numeric_limits<float>::quiet_NaN();
  uint32_t seed = 300;
  for (const auto& size : sizes) {
    const int w = size[0], h = size[1];
    Frame f = test::flat_frame(w, h);
    Image noise(w, h, 4), in(w, h, 3), luma(w, h, 1), dev(w, h, 1);
    test::fill_uniform(noise, 0.f, 1.f, ++seed);
    test::fill_uniform(in, 0.f, 3.f, ++seed);
    test::fill_uniform(luma, 0.f, 2.f, ++seed);
    test::fill_uniform(dev, 0.f, 1.f, ++seed);
    for (int i = 0; i < w * h; ++i) {  // background holes, two depth layers, tilted normals
      const float u = noise.plane(0)[i];
      f.depth.plane(0)[i] = u < 0.08f ? 0.f : (u < 0.5f ? 2.f + noise.plane(1)[i] * 0.5f : 5.f);
      const float tilt = noise.plane(2)[i] * 0.8f;
      f.normal.plane(0)[i] = tilt / std::sqrt(1.f + tilt * tilt);
      f.normal.plane(2)[i] = 1.f / std::sqrt(1.f + tilt * tilt);
    }
    if (w * h > 100) {  // NaN guides: each drops its term or zeroes the weight, the same way
      f.normal.plane(1)[w + 1] = nan;
      f.depth.plane(0)[2 * w + 3] = nan;
      luma.plane(0)[3 * w + 5] = nan;
    }
    for (int kernel_size : {3, 5, 7, 9})
      for (float sigma_normal : {64.f, 128.f, 1.f, 0.f, 10.f})
        for (int step : {1, 2, 8, 32}) {
          Image a(w, h, 3, -1.f), b(w, h, 3, -2.f);
          using Power = NormalPower<ExactArith>;
          const cpu::WaveletExactIteration k{f.guides(), in.rgb(),     a.rgb(), luma.plane(0),
                                             dev.plane(0), step,        kernel_size, 1.f / 1.01f,
                                             4.f,          0.01f,       Power::of(sigma_normal)};
          cpu::WaveletExactIteration k2 = k;
          k2.out = b.rgb();
          cpu::for_each_pixel(w, h, k);
          cpu::run_wavelet_rows(k2, w, h);
          test::require_identical(b, a, "wavelet " + std::to_string(w) + "x" + std::to_string(h) +
                                            " kernel " + std::to_string(kernel_size) + " step " +
                                            std::to_string(step) + " sigma_N " +
                                            std::to_string(sigma_normal));
        }
  }
}

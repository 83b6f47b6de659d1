// A-SVGF's gradient sample, a-trous and lambda row drivers (kernels_cpu/svgf_gradient_rows.cpp)
// must give the per-stratum kernels' bits exactly (the kernels are what the GPU runs), on every
// instruction-set variant this CPU runs: strata without data, taps on other meshes, NaN / Inf /
// -0 in the planes and guides, stratum images narrower or lower than the taps' reach, every
// step and radius.
#include <cmath>
#include <limits>
#include <random>

#include <catch2/catch.hpp>

#include "cpu_variant_support.h"
#include "kernels_cpu/parallel_for.h"
#include "methods/svgf/gradient.h"
#include "test_support.h"

using namespace svgf;

namespace {

using svgf::test::kNaN;
using svgf::test::kInf;

// A frame's guides in patches of two meshes (a few strays of a third), holes and a few bad
// values, and per stratum a random guide pixel inside the frame.
struct Guides {
  Frame frame;
  Image offset;  // per stratum, 0 .. 8
  Guides(int w, int h, uint32_t seed)
      : frame(test::flat_frame(w, h)), offset(strata_along(w), strata_along(h), 1) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.f, 1.f);
    test::fill_uniform(frame.depth_gradient, -0.05f, 0.05f, seed + 1);
    for (int i = 0; i < w * h; ++i) {
      const int x = i % w, y = i / w;
      const bool near = (x / 7 + y / 5) % 3 == 0;
      const float odd = u(rng);
      frame.depth.plane(0)[i] = odd < 0.02f ? 0.f : (near ? 2.f + u(rng) * 0.05f : 5.f + u(rng));
      frame.mesh_id[i] = odd > 0.97f ? 9u : (near ? 1u : 2u);
      const float tilt = u(rng) * 0.6f - 0.3f, n = std::sqrt(1.f + tilt * tilt);
      frame.normal.plane(0)[i] = tilt / n;
      frame.normal.plane(2)[i] = 1.f / n;
      if (odd > 0.02f && odd < 0.025f) frame.depth.plane(0)[i] = kNaN;
      if (odd > 0.03f && odd < 0.035f) frame.normal.plane(1)[i] = kNaN;
    }
    const int sw = offset.width();
    for (int s = 0; s < sw * offset.height(); ++s) {
      const int x0 = (s % sw) * kGradientStratum, y0 = (s / sw) * kGradientStratum;
      const int k = static_cast<int>(u(rng) * 9.f) % 9;
      const int dx = std::min(k % 3, w - 1 - x0), dy = std::min(k / 3, h - 1 - y0);
      offset.plane(0)[s] = static_cast<float>(dy * kGradientStratum + dx);
    }
  }
};

// The filtered planes (delta, normalizer, weight): a third of the strata without data, and a
// few of each odd value in delta and normalizer.
Image random_planes(int sw, int sh, uint32_t seed) {
  Image in(sw, sh, 3);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  const float odd_values[] = {kNaN, kInf, -kInf, -0.f, 0.f};
  for (int s = 0; s < sw * sh; ++s) {
    in.plane(0)[s] = u(rng) * 4.f - 2.f;
    in.plane(1)[s] = u(rng) * 3.f;
    in.plane(2)[s] = u(rng) < 0.33f ? 0.f : 1.f;
    const float odd = u(rng);
    if (odd < 0.05f) in.plane(static_cast<int>(odd * 40.f) % 2)[s] = odd_values[s % 5];
    if (odd > 0.98f) in.plane(2)[s] = kNaN;  // not > 0: no data
  }
  return in;
}

GradientAtrousKernel kernel_for(const Guides& g, const Image& in, Image& out, int step) {
  GradientAtrousKernel k;
  k.guides = g.frame.guides();
  k.at = StratumGuides{g.frame.width(), g.offset.width(), g.offset.plane(0)};
  k.strata_height = g.offset.height();
  k.in = GradientPlanes<const float>(in.plane(0), in.plane(1), in.plane(2));
  k.out = GradientPlanes<float>(out.plane(0), out.plane(1), out.plane(2));
  k.step = step;
  return k;
}

}  // namespace

TEST_CASE("cpu rows: gradient a-trous rows equal the per-stratum kernel bitwise", "[cpu_rows]") {
  // In pixels: strata images from 45 x 17 down to narrower and lower than the taps' reach.
  const int sizes[][2] = {{133, 49}, {400, 130}, {50, 50}, {7, 40}, {40, 7}, {1, 1}, {20, 14}};
  uint32_t seed = 700;
  for (const auto& size : sizes) {
    const Guides g(size[0], size[1], ++seed);
    const int sw = g.offset.width(), sh = g.offset.height();
    const Image in = random_planes(sw, sh, ++seed);
    for (int step : {1, 2, 4, 8, 16})
      for (float phi_normal : {128.f, 100.f})   // a power of two (compile-time) and not
        for (float phi_depth : {1.f, 0.f}) {    // 0: no depth term
          const std::string what = std::to_string(sw) + "x" + std::to_string(sh) +
                                   " strata, step " + std::to_string(step) + ", phi_normal " +
                                   std::to_string(phi_normal) + ", phi_depth " +
                                   std::to_string(phi_depth);
          Image expected(sw, sh, 3, -1.f);
          GradientAtrousKernel k = kernel_for(g, in, expected, step);
          k.phi_normal = phi_normal;
          k.phi_depth = phi_depth;
          cpu::for_each_pixel(sw, sh, k);
          test::for_each_runnable_variant([&](const cpu::CpuVariant& v) {
            Image got(sw, sh, 3, -2.f);
            GradientAtrousKernel r = k;
            r.out = GradientPlanes<float>(got.plane(0), got.plane(1), got.plane(2));
            v.gradient_atrous_rows(r, sw, sh);
            test::require_identical(got, expected, what + " on " + v.name);
          });
        }
  }
}

TEST_CASE("cpu rows: gradient lambda rows equal the per-stratum kernel bitwise", "[cpu_rows]") {
  // The neighbourhood's maximum of lambdas with NaN among them (max_f keeps the order's NaN
  // rule), strata without data, every radius, images narrower and lower than its reach.
  const int sizes[][2] = {{45, 17}, {133, 43}, {3, 20}, {20, 3}, {1, 1}, {7, 7}};
  uint32_t seed = 800;
  for (const auto& size : sizes) {
    const int sw = size[0], sh = size[1];
    const Image in = random_planes(sw, sh, ++seed);
    for (int radius = 0; radius <= 3; ++radius) {
      const std::string what = std::to_string(sw) + "x" + std::to_string(sh) + " strata, radius " +
                               std::to_string(radius);
      Image expected(sw, sh, 1, -1.f);
      const GradientLambdaKernel k{sw, GradientPlanes<const float>(in.plane(0), in.plane(1),
                                                                   in.plane(2)),
                                   expected.plane(0), sh, radius};
      cpu::for_each_pixel(sw, sh, k);
      test::for_each_runnable_variant([&](const cpu::CpuVariant& v) {
        Image got(sw, sh, 1, -2.f);
        GradientLambdaKernel r = k;
        r.lambda = got.plane(0);
        v.gradient_lambda_rows(r, sw, sh);
        test::require_identical(got, expected, what + " on " + v.name);
      });
    }
  }
}

TEST_CASE("cpu rows: gradient sample rows equal the per-stratum kernel bitwise", "[cpu_rows]") {
  // Frames whose sides are and are not multiples of the stratum (partial last columns and
  // rows run the kernel), down to one pixel. Masks: strata with none, with one at any of the
  // nine places, with several (the first in raster order counts), NaN and 0.5 (not masked);
  // the samples' luminances with NaN, Inf and negative values (no data) and -0.
  const int sizes[][2] = {{129, 48}, {131, 50}, {3, 3}, {1, 1}, {2, 7}, {64, 5}};
  uint32_t seed = 900;
  for (const auto& size : sizes) {
    const int w = size[0], h = size[1], sw = strata_along(w), sh = strata_along(h);
    std::mt19937 rng(++seed);
    std::uniform_real_distribution<float> u(0.f, 1.f);
    Image samples(w, h, 3);
    const float odd_values[] = {kNaN, kInf, -1.f, -0.f, 0.f};
    for (int i = 0; i < w * h; ++i) {
      samples.plane(0)[i] = u(rng) * 2.f;
      samples.plane(1)[i] = u(rng) * 2.f;
      const float r = u(rng);
      samples.plane(2)[i] = r < 0.12f ? 1.f : (r < 0.14f ? kNaN : (r < 0.16f ? 0.5f : 0.f));
      if (r > 0.97f) samples.plane(static_cast<int>(r * 1000.f) % 2)[i] = odd_values[i % 5];
    }
    GradientSamplesKernel k;
    k.width = w;
    k.height = h;
    k.samples = GradientSampleView{samples.plane(0), samples.plane(1), samples.plane(2)};
    k.strata_width = sw;
    Image expected(sw, sh, 4, -1.f);
    k.out = GradientPlanes<float>(expected.plane(0), expected.plane(1), expected.plane(2));
    k.guide_offset = expected.plane(3);
    cpu::for_each_pixel(sw, sh, k);
    test::for_each_runnable_variant([&](const cpu::CpuVariant& v) {
      Image got(sw, sh, 4, -2.f);
      GradientSamplesKernel r = k;
      r.out = GradientPlanes<float>(got.plane(0), got.plane(1), got.plane(2));
      r.guide_offset = got.plane(3);
      v.gradient_samples_rows(r, sw, sh);
      test::require_identical(got, expected, std::to_string(w) + "x" + std::to_string(h) +
                                                 " pixels on " + v.name);
    });
  }
}

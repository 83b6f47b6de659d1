// The vectorized CPU row drivers must give the per-pixel kernels' bits exactly (the per-pixel
// kernels are what the GPU runs), for every step, border, power and guide oddity.
#include <algorithm>
#include <limits>

#include <catch2/catch.hpp>

#include "methods/svgf/atrous.h"
#include "methods/svgf/sinks.h"
#include "methods/svgf/variance.h"
#include "kernels_cpu/svgf_rows.h"
#include "kernels_cpu/parallel_for.h"
#include "kernels_cpu/row_tools.h"
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

// One a-trous iteration of `in` over the frame's guides, per-pixel kernel against the rows.
void require_atrous_rows_match(const Frame& f, const Image& in, float phi, int step) {
  const int w = in.width(), h = in.height();
  Image a(w, h, 4, -1.f), b(w, h, 4, -2.f);
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

// The spatial variance estimate, likewise, with its copy of the accumulated color into the
// color history (VarianceEstimate::color_history), which must hold every pixel's.
void require_variance_rows_match(const Frame& f, const Image& acc, const Image& moments,
                                 const Image& history, float phi, int radius = 3) {
  const int w = acc.width(), h = acc.height();
  Image a(w, h, 4), b(w, h, 4), history_a(w, h, 3, -1.f), history_b(w, h, 3, -2.f);
  SvgfParams p;
  p.phi_normal = phi;
  p.spatial_variance_radius = radius;
  const VarianceKernel k{f.guides(), {acc.rgb(), acc.plane(3)}, moments.plane(0),
                         moments.plane(1), history.plane(0), {a.rgb(), a.plane(3)}, p,
                         history_a.rgb()};
  VarianceKernel k2 = k;
  k2.out = {b.rgb(), b.plane(3)};
  k2.color_history = history_b.rgb();
  cpu::for_each_pixel(w, h, k);
  cpu::run_variance_rows(k2, w, h);
  const std::string where = "variance " + std::to_string(w) + "x" + std::to_string(h) +
                            ", radius " + std::to_string(radius);
  test::require_identical(b, a, where);
  test::require_identical(history_b, history_a, where + ", color history");
  Image acc_color(w, h, 3);
  for (int c = 0; c < 3; ++c) std::copy_n(acc.plane(c), w * h, acc_color.plane(c));
  test::require_identical(history_a, acc_color, where + ", color history vs accumulation");
}

}  // namespace

TEST_CASE("cpu rows: a-trous rows equal the per-pixel kernel bitwise", "[cpu_rows]") {
  // {0, 5} and {6, 0}: no rows or no columns (nothing to write, no band to divide). {100, 6}:
  // a right border narrower than a vector at step 1, its loop widened into the interior.
  const int sizes[][2] = {{257, 89}, {16, 16}, {3, 2},  {1, 7},
                          {64, 33},  {100, 6},  {0, 5}, {6, 0}};
  const float phis[] = {128.f, 1.f, 0.f, 100.f};
  uint32_t seed = 0;
  for (const auto& size : sizes) {
    const int w = size[0], h = size[1];
    Frame f = random_guides(w, h, ++seed);
    if (w * h > 100) f.normal.plane(1)[w + 1] = std::numeric_limits<float>::quiet_NaN();
    Image in(w, h, 4);
    test::fill_uniform(in, 0.f, 3.f, ++seed);
    for (float phi : phis)
      for (int step : {1, 2, 4, 8, 16}) require_atrous_rows_match(f, in, phi, step);
  }
}

namespace {

// One a-trous iteration into the pipeline's fused outputs (methods/svgf/pipeline.h,
// kFusedOutputs): the per-pixel kernel with the sink against the CPU engine's driver for it
// (the rows, kernels_cpu/svgf_rows.h), every plane either writes compared.
void require_fused_outputs_match(const Frame& f, const Image& in, bool emission, int step) {
  const int w = in.width(), h = in.height();
  Image albedo(w, h, 3), light(w, h, 3);
  test::fill_uniform(albedo, 0.f, 1.f, 7u + static_cast<uint32_t>(step));  // some under epsilon
  test::fill_uniform(light, 0.f, 0.5f, 11u);
  if (w * h > 100) albedo.plane(1)[w + 3] = std::numeric_limits<float>::quiet_NaN();
  const ConstRgbView emitted = emission ? ConstRgbView(light.rgb()) : ConstRgbView();
  const std::string what = std::to_string(w) + "x" + std::to_string(h) + " step " +
                           std::to_string(step) + (emission ? " with emission" : "");
  Image out_a(w, h, 3, -1.f), out_b(w, h, 3, -2.f), signal_a(w, h, 4, -1.f),
      signal_b(w, h, 4, -2.f), history_a(w, h, 3, -1.f), history_b(w, h, 3, -2.f);
  const RemodulateSink remodulate_a{albedo.rgb(), emitted, out_a.rgb()},
      remodulate_b{albedo.rgb(), emitted, out_b.rgb()};
  const IllumVarView next_a{signal_a.rgb(), signal_a.plane(3)},
      next_b{signal_b.rgb(), signal_b.plane(3)};
  const auto run_both = [&](const auto& sink_a, const auto& sink_b) {
    using Out = std::decay_t<decltype(sink_a)>;
    using Iteration = AtrousIteration<SvgfExact, NormalPower<ExactArith>, Out>;
    const Iteration a{f.guides(), {in.rgb(), in.plane(3)}, sink_a, step, SvgfParams()};
    const Iteration b{f.guides(), {in.rgb(), in.plane(3)}, sink_b, step, SvgfParams()};
    cpu::for_each_pixel(w, h, a);
    cpu::PixelDriver<Iteration>::run(b, w, h);
  };
  run_both(remodulate_a, remodulate_b);
  test::require_identical(out_b, out_a, "remodulated a-trous " + what);
  run_both(FeedbackTee<IllumVarView>{next_a, history_a.rgb()},
           FeedbackTee<IllumVarView>{next_b, history_b.rgb()});
  test::require_identical(signal_b, signal_a, "fed-back a-trous " + what);
  test::require_identical(history_b, history_a, "fed-back a-trous's history " + what);
  out_a = Image(w, h, 3, -1.f);
  out_b = Image(w, h, 3, -2.f);
  history_a = Image(w, h, 3, -1.f);
  history_b = Image(w, h, 3, -2.f);
  run_both(FeedbackTee<RemodulateSink>{{albedo.rgb(), emitted, out_a.rgb()}, history_a.rgb()},
           FeedbackTee<RemodulateSink>{{albedo.rgb(), emitted, out_b.rgb()}, history_b.rgb()});
  test::require_identical(out_b, out_a, "fed-back, remodulated a-trous " + what);
  test::require_identical(history_b, history_a, "fed-back, remodulated a-trous's history " + what);
}

}  // namespace

TEST_CASE("cpu rows: a-trous rows with fused outputs equal the per-pixel kernel with its sinks",
          "[cpu_rows]") {
  const int sizes[][2] = {{257, 89}, {16, 16}, {3, 2}, {0, 5}};
  uint32_t seed = 500;
  for (const auto& size : sizes) {
    const int w = size[0], h = size[1];
    const Frame f = random_guides(w, h, ++seed);
    Image in(w, h, 4);
    test::fill_uniform(in, 0.f, 3.f, ++seed);
    for (bool emission : {false, true})
      for (int step : {1, 4}) require_fused_outputs_match(f, in, emission, step);
  }
}

namespace {

// Guides and signal where every select of the edge-stopping weight decides (the rows evaluate
// them as max/min instructions against opaque constants, RowExactArith): cosines below 0 and
// above 1 (saturate), NaN and -0 normals, NaN, -0, subnormal and Inf depths, luminance
// differences whose exponent falls below the clamp at -104, NaN and Inf colors (a NaN term that
// max(., 0) must drop, a NaN weight positive_part must zero), -0 and subnormal values.
Frame clamp_guides(int w, int h, uint32_t seed) {
  Frame f = random_guides(w, h, seed);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  for (int i = 0; i < w * h; ++i) {
    switch (i % 11) {
      case 1:  // anti-parallel: the cosine is negative
        for (int c = 0; c < 3; ++c) f.normal.plane(c)[i] = -f.normal.plane(c)[i];
        break;
      case 2:  // longer than 1 (half-float normals): the cosine exceeds 1
        for (int c = 0; c < 3; ++c) f.normal.plane(c)[i] *= 1.0003f;
        break;
      case 3: f.normal.plane(i % 3)[i] = nan; break;
      case 4: f.normal.plane(0)[i] = -0.f; break;
      case 5: f.depth.plane(0)[i] = i % 2 ? -0.f : 1e-40f; break;  // background / subnormal
      case 6: f.depth.plane(0)[i] = i % 3 ? nan : inf; break;
      case 7: f.depth_gradient.plane(i % 2)[i] = 0.f; break;
      default: break;
    }
  }
  return f;
}

void fill_clamp_signal(Image& in) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  const int n = in.width() * in.height();
  for (int i = 0; i < n; ++i) {
    float* v[4] = {&in.plane(0)[i], &in.plane(1)[i], &in.plane(2)[i], &in.plane(3)[i]};
    switch (i % 13) {
      case 1: *v[0] = 1e30f; break;  // |l_p - l_q| / phi_l far beyond 104
      case 2: *v[1] = nan; break;
      case 3: *v[2] = inf; break;
      case 4: *v[i % 4] = -0.f; break;
      case 5: *v[3] = 1e-42f; break;  // a subnormal variance
      case 6: *v[3] = 0.f; break;
      default: break;
    }
  }
}

}  // namespace

TEST_CASE("cpu rows: RowExactArith gives ExactArith's bits, NaN, -0 and Inf included",
          "[cpu_rows]") {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  const float values[] = {nan, -nan, inf, -inf, 0.f, -0.f, 1e-42f, -1e-42f, 1.f, 1.0003f, -1.f,
                          0.5f, -103.9f, -104.f, -104.1f, -200.f, 88.f, 3e38f};
  int differing = 0;
  const auto same = [&](float a, float b) { differing += float_bits(a) != float_bits(b); };
  for (float a : values) {
    for (float c : {0.f, 1.f, -104.f}) same(cpu::RowExactArith::max(a, c), ExactArith::max(a, c));
    same(cpu::RowExactArith::saturate(a), ExactArith::saturate(a));
    same(cpu::RowExactArith::positive_part(a), ExactArith::positive_part(a));
    if (!(a > 0.f)) same(cpu::RowExactArith::exp_nonpositive(a), ExactArith::exp_nonpositive(a));
    for (float b : values)
      if (!(a < 0.f) && !(b < 0.f))
        same(cpu::RowExactArith::exp_neg_sum(a, b), ExactArith::exp_neg_sum(a, b));
  }
  REQUIRE(differing == 0);
}

TEST_CASE("cpu rows: a-trous and variance rows equal the kernels where the clamps decide",
          "[cpu_rows]") {
  const int sizes[][2] = {{131, 37}, {29, 17}};
  uint32_t seed = 300;
  for (const auto& size : sizes) {
    const int w = size[0], h = size[1];
    const Frame f = clamp_guides(w, h, ++seed);
    Image in(w, h, 4);
    test::fill_uniform(in, 0.f, 3.f, ++seed);
    fill_clamp_signal(in);
    for (float phi : {128.f, 100.f, 0.f})
      for (int step : {1, 2, 4}) require_atrous_rows_match(f, in, phi, step);
    Image moments(w, h, 2), history(w, h, 1, 1.f);  // every pixel young: all take the 7x7
    test::fill_uniform(moments, 0.f, 2.f, ++seed);
    for (float phi : {128.f, 3.f}) require_variance_rows_match(f, in, moments, history, phi);
  }
}

TEST_CASE("cpu rows: spatial variance rows equal the per-pixel kernel bitwise", "[cpu_rows]") {
  const int sizes[][2] = {{257, 89}, {5, 3}, {31, 40}};
  uint32_t seed = 100;
  for (const auto& size : sizes) {
    const int w = size[0], h = size[1];
    const Frame f = random_guides(w, h, ++seed);
    Image acc(w, h, 4), moments(w, h, 2), history(w, h, 1);
    test::fill_uniform(acc, 0.f, 3.f, ++seed);
    test::fill_uniform(moments, 0.f, 2.f, ++seed);
    test::fill_uniform(history, 1.f, 6.f, ++seed);
    for (float& v : history.data()) v = std::floor(v);  // a mix of young (<4) and old history
    for (float phi : {128.f, 3.f}) require_variance_rows_match(f, acc, moments, history, phi);
    // Radius 3 (the default) takes the tap rows where all seven taps lie inside; the others
    // one tap at a time.
    for (int radius : {1, 2}) require_variance_rows_match(f, acc, moments, history, 128.f, radius);
  }
}

// Few young pixels, as in a renderer's frame: the rows run the estimate over short spans of a
// row, each widened to whole 16-pixel vectors where the row has room (leftwards at the right
// end, clipped in a row narrower than that). Runs of 1 to 20 young pixels at the ends and in
// the middle of rows, isolated ones, and gaps just below and above the 16 pixels that merge two
// runs into one span; the old pixels in a widened span keep the temporal variance.
TEST_CASE("cpu rows: spatial variance rows over sparse young pixels equal the kernel",
          "[cpu_rows]") {
  const int sizes[][2] = {{257, 41}, {40, 12}, {12, 9}, {16, 5}};
  uint32_t seed = 300;
  for (const auto& size : sizes) {
    const int w = size[0], h = size[1];
    const Frame f = random_guides(w, h, ++seed);
    Image acc(w, h, 4), moments(w, h, 2), history(w, h, 1), coin(w, h, 1);
    test::fill_uniform(acc, 0.f, 3.f, ++seed);
    test::fill_uniform(moments, 0.f, 2.f, ++seed);
    test::fill_uniform(coin, 0.f, 1.f, ++seed);
    for (int y = 0; y < h; ++y) {
      const int run = 1 + y % 20, gap = 15 + y % 3;  // gaps of 15, 16 and 17 pixels
      for (int x = 0; x < w; ++x) {
        const int at = y % 4 == 0 ? x : (y % 4 == 1 ? w - 1 - x : x - w / 3);
        const bool in_run = at >= 0 && at % (run + gap) < run && at < 2 * (run + gap);
        const bool young = in_run || coin.plane(0)[y * w + x] < 0.02f;
        history.plane(0)[y * w + x] = young ? static_cast<float>(1 + (x + y) % 3) : 7.f;
      }
    }
    for (float phi : {128.f, 3.f}) require_variance_rows_match(f, acc, moments, history, phi);
    require_variance_rows_match(f, acc, moments, history, 128.f, 2);
  }
}

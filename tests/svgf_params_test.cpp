// Parameter pins added by the planted-bug check (docs/svgf.md, "Planted-bug check"): each test
// here catches a planted bug that the other CPU tests missed. Every expected value is derived
// by hand or computed in double precision from constants written out in this file, never read
// from the code under test (SvgfParams's defaults included).
#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <catch2/catch.hpp>

#include "methods/svgf/atrous.h"
#include "methods/svgf/demodulate.h"
#include "methods/svgf/remodulate.h"
#include "methods/svgf/reproject.h"
#include "methods/svgf/stages.h"
#include "pipeline/make_denoiser.h"
#include "kernels_cpu/parallel_for.h"
#include "test_support.h"

using namespace svgf;

namespace {

// The documented values (docs/svgf.md), written out: the defaults, and where the defaults moved
// away from Falcor's (issue 12), Falcor's, which the stage pins below run with
// svgf_preset("falcor").
constexpr double kAlbedoEpsilon = 1e-3;
constexpr double kAlpha = 0.05;  // Falcor's; the default is 0.03
constexpr double kMomentsAlpha = 0.2;
constexpr double kReprojectMinWeight = 0.01;
constexpr double kPhiColor = 10;  // Falcor's; the default is 4
constexpr double kPhiNormal = 128;
constexpr double kPhiDepth = 1;
constexpr double kVarianceEpsilon = 1e-4;
constexpr double kDepthGradientFloor = 1e-8;

double relative_difference(double got, double want) {
  return std::fabs(got - want) / std::max(1e-12, std::fabs(want));
}

}  // namespace

TEST_CASE("params: the demodulate and remodulate kernels' own albedo epsilon is 1e-3",
          "[params][demodulate]") {
  // A kernel built without naming the epsilon (the member's default) divides black albedo by
  // 1e-3: 2 / 1e-3 = 2000, and multiplies it back by 1e-3.
  Image color(3, 2, 3, 2.f), albedo(3, 2, 3, 0.f), illum(3, 2, 3), out(3, 2, 3);
  DemodulateKernel k;
  k.width = 3;
  k.color = color.rgb();
  k.albedo = albedo.rgb();
  k.illumination = illum.rgb();
  cpu::for_each_pixel(3, 2, k);
  for (float v : illum.data()) REQUIRE(relative_difference(v, 2.0 / kAlbedoEpsilon) < 1e-6);

  Image filtered(3, 2, 3, 500.f);
  RemodulateSink sink;
  sink.albedo = albedo.rgb();
  sink.output = out.rgb();
  for (int i = 0; i < 6; ++i) sink.store(i, make_vec3(500.f, 500.f, 500.f));
  for (float v : out.data()) REQUIRE(relative_difference(v, 500.0 * kAlbedoEpsilon) < 1e-6);
}

TEST_CASE("params: the pipeline's default albedo epsilon is 1e-3", "[params][pipeline]") {
  // Black albedo on the first frame: the demodulated illumination is color / 1e-3.
  Frame f = test::flat_frame(6, 5, 2.f, 0.f);
  for (float& v : f.color.data()) v = 0.5f;
  DenoiserConfig c;
  c.backend = Backend::Cpu;
  c.threads = 1;
  c.keep_scratch = true;
  auto d = make_denoiser(c);
  Image out;
  d->denoise(f, out);
  const Image illum = d->read_buffer(svgf_buffer::kIllumination);
  for (float v : illum.data()) REQUIRE(relative_difference(v, 0.5 / kAlbedoEpsilon) < 1e-6);
  // ...and the output is the input again (filtered constant * 1e-3).
  for (float v : out.data()) REQUIRE(relative_difference(v, 0.5) < 1e-5);
}

TEST_CASE("params: a-trous with default parameters against a double reference of the "
          "documented values",
          "[params][atrous]") {
  // The a-trous test of svgf_atrous_test.cpp checks each parameter's role with the reference
  // reading the parameter struct; this one pins the default values themselves. The scene makes
  // every default matter: zero variance (so sigma_l = phi_color sqrt(variance_epsilon) = 0.1),
  // luminance steps of 0.02 to 0.2, a zero depth gradient (so the depth tolerance is the floor
  // 1e-8 times phi_depth) with depths 1e-3 apart by a few 1e-9, normals tilted by a few degrees
  // (cos^128 in 0.5 .. 1).
  const int w = 11, h = 9;
  Frame f = test::flat_frame(w, h, 1e-3f);
  Image in(w, h, 4), out(w, h, 4);
  std::mt19937 rng(2026);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      f.depth.at(x, y, 0) = 1e-3f + 3e-9f * std::floor(4.f * u(rng));
      const float nx = 0.08f * (u(rng) - 0.5f), ny = 0.08f * (u(rng) - 0.5f);
      const float len = std::sqrt(nx * nx + ny * ny + 1.f);
      f.normal.at(x, y, 0) = nx / len;
      f.normal.at(x, y, 1) = ny / len;
      f.normal.at(x, y, 2) = 1.f / len;
      const float g = 0.5f + 0.2f * u(rng);
      in.at(x, y, 0) = g;
      in.at(x, y, 1) = g + 0.01f * u(rng);
      in.at(x, y, 2) = g;
      in.at(x, y, 3) = 0.f;
    }
  const double b3[3] = {3.0 / 8, 1.0 / 4, 1.0 / 16};
  auto lum = [&](int x, int y) {
    return 0.2126 * in.at(x, y, 0) + 0.7152 * in.at(x, y, 1) + 0.0722 * in.at(x, y, 2);
  };
  for (int step : {1, 2}) {
    cpu::for_each_pixel(w, h, AtrousKernel{f.guides(), {in.rgb(), in.plane(3)},
                                           {out.rgb(), out.plane(3)}, step, svgf_preset("falcor")});
    double worst = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const double sigma_l = kPhiColor * std::sqrt(kVarianceEpsilon);  // variance 0
        const double sigma_z = kPhiDepth * kDepthGradientFloor;            // fwidth 0
        double ws = 0, cs[3] = {0, 0, 0};
        for (int dy = -2; dy <= 2; ++dy)
          for (int dx = -2; dx <= 2; ++dx) {
            const int xq = x + dx * step, yq = y + dy * step;
            if (xq < 0 || yq < 0 || xq >= w || yq >= h) continue;
            double wt = b3[std::abs(dx)] * b3[std::abs(dy)];
            if (dx != 0 || dy != 0) {
              double cosine = 0;
              for (int c = 0; c < 3; ++c) cosine += double(f.normal.at(x, y, c)) * f.normal.at(xq, yq, c);
              cosine = std::min(1.0, std::max(0.0, cosine));
              const double dist = std::sqrt(double(dx * dx + dy * dy)) * step;
              const double e_z =
                  std::fabs(double(f.depth.at(x, y, 0)) - f.depth.at(xq, yq, 0)) / (sigma_z * dist);
              const double e_l = std::fabs(lum(x, y) - lum(xq, yq)) / sigma_l;
              wt *= std::exp(-e_l - e_z) * std::pow(cosine, kPhiNormal);
            }
            ws += wt;
            for (int c = 0; c < 3; ++c) cs[c] += wt * in.at(xq, yq, c);
          }
        for (int c = 0; c < 3; ++c)
          worst = std::max(worst, relative_difference(out.at(x, y, c), cs[c] / ws));
      }
    INFO("step " << step << ": worst relative difference " << worst);
    REQUIRE(worst < 2e-5);
  }
}

TEST_CASE("params: every SvgfParams and GaussianParams default is its documented value",
          "[params][params]") {
  // The table of docs/svgf.md (and methods/gaussian/params.h), written out. The behavioural
  // tests pin each parameter's role; this pins the value a default-configured denoiser starts
  // from, including the ones whose effect only shows in rare pixels (albedo below 1e-3, depth
  // gradients below 1e-8).
  const SvgfParams p;
  CHECK(p.albedo_epsilon == 1e-3f);
  CHECK(p.alpha == 0.03f);
  CHECK(p.moments_alpha == 0.2f);
  CHECK(p.history_cap == 64);
  CHECK(p.variance_of_mean);
  CHECK(p.antilag == Antilag::Gradient);
  CHECK(p.gradient_iterations == 1);
  CHECK(p.gradient_lambda_radius == 1);
  CHECK(p.reproject_depth_gradient_scale == 10.f);
  CHECK(p.reproject_depth_relative == 0.03f);
  CHECK(p.reproject_normal_cos == 0.9f);
  CHECK(p.reproject_min_weight == 0.01f);
  CHECK(p.spatial_variance_history == 4);
  CHECK(p.spatial_variance_radius == 3);
  CHECK(p.spatial_variance_phi_depth == 3.f);
  CHECK(p.iterations == 4);
  CHECK(p.feedback_tap == -1);
  CHECK(p.phi_color == 4.f);
  CHECK(p.phi_normal == 128.f);
  CHECK(p.phi_depth == 1.f);
  CHECK(p.variance_epsilon == 1e-4f);
  CHECK(p.depth_gradient_floor == 1e-8f);
  const GaussianParams g;
  CHECK(g.sigma == 2.f);
  CHECK(g.radius == 0);
  CHECK(g.effective_radius() == 6);
}

namespace {

// History length at the centre of a static 5x5 frame after two frames, with every previous
// pixel's depth and normal replaced (so the 3x3 fallback finds nothing else): 2 when the history
// was kept, 1 when rejected. Default parameters; this frame's depth 2, normal +z, and depth
// gradient (fwidth) `fwidth`.
float history_after(float fwidth, float prev_depth, Vec3 prev_normal) {
  const int w = 5, h = 5;
  Frame cur = test::flat_frame(w, h), prev = test::flat_frame(w, h);
  for (int i = 0; i < w * h; ++i) {
    cur.depth_gradient.plane(0)[i] = fwidth;
    prev.depth.plane(0)[i] = prev_depth;
    prev.normal.plane(0)[i] = prev_normal.x;
    prev.normal.plane(1)[i] = prev_normal.y;
    prev.normal.plane(2)[i] = prev_normal.z;
  }
  Image illum(w, h, 3, 0.5f), prev_color(w, h, 3, 0.5f), prev_moments(w, h, 2, 0.25f),
      prev_history(w, h, 1, 1.f), accumulated(w, h, 4), moments(w, h, 2), history(w, h, 1);
  ReprojectKernel k;
  k.params = svgf_preset("falcor");  // Falcor's documented values, no anti-lag
  k.guides = cur.guides();
  k.prev_guides = prev.guides();
  k.illumination = illum.rgb();
  k.prev_color = prev_color.rgb();
  k.prev_moment1 = prev_moments.plane(0);
  k.prev_moment2 = prev_moments.plane(1);
  k.prev_history = prev_history.plane(0);
  k.has_history = true;
  k.accumulated = {accumulated.rgb(), accumulated.plane(3)};
  k.moment1 = moments.plane(0);
  k.moment2 = moments.plane(1);
  k.history = history.plane(0);
  cpu::for_each_pixel(w, h, k);
  return history.at(2, 2, 0);
}

}  // namespace

TEST_CASE("params: the reprojection depth test keeps a tap exactly at the tolerance",
          "[params][reproject]") {
  // |z - z_prev| <= 10 fwidth + 0.03 z, inclusive. With z = 2 and fwidth = 0x1.47ae26p-7
  // (0.0100000082), the float tolerance 10 fwidth + 0.06 rounds to 0x1.47ae2p-3 (0.160000086),
  // and z_prev = 2 + that is a float (0x1.147ae2p+1), so |z - z_prev| equals the tolerance
  // exactly: kept. One ulp further (0x1.147ae4p+1): rejected. (Worked out step by step in float
  // arithmetic; a strict comparison, or either default moved by a few parts in 10^6, fails.)
  const float fwidth = 0x1.47ae26p-7f;
  const Vec3 n = make_vec3(0.f, 0.f, 1.f);
  REQUIRE(history_after(fwidth, 0x1.147ae2p+1f, n) == 2.f);
  REQUIRE(history_after(fwidth, 0x1.147ae4p+1f, n) == 1.f);
}

TEST_CASE("params: the reprojection normal test keeps n . n_prev exactly 0.9",
          "[params][reproject]") {
  // This frame's normal is +z, so n . n_prev = n_prev.z (0 * x + 0 * y + z, exact). 0.9f is
  // kept (>=, default 0.9), the next float below is rejected.
  const float nz = 0.9f, nx = std::sqrt(1.f - nz * nz);
  REQUIRE(history_after(0.01f, 2.f, make_vec3(nx, 0.f, nz)) == 2.f);
  REQUIRE(history_after(0.01f, 2.f, make_vec3(nx, 0.f, std::nextafter(nz, 0.f))) == 1.f);
}

namespace {

// One ReprojectKernel pass with default parameters over a static w x h frame (depth 2, normal +z,
// mesh 1): this frame's illumination `c`, the previous frame's color, moments and history
// constant, except where `prev_mesh` (per pixel, may be empty) moves pixels to another mesh.
// Every pixel's motion is (mx, my).
struct ReprojectRun {
  Image accumulated, moments, history;
};
ReprojectRun reproject_once(int w, int h, float c, float prev_c, float prev_m1, float prev_m2,
                            const std::vector<float>& prev_history,
                            const std::vector<uint32_t>& prev_mesh, float mx = 0.f,
                            float my = 0.f) {
  Frame cur = test::flat_frame(w, h), prev = test::flat_frame(w, h);
  for (int i = 0; i < w * h; ++i) {
    cur.motion.plane(0)[i] = mx;
    cur.motion.plane(1)[i] = my;
    if (!prev_mesh.empty()) prev.mesh_id[i] = prev_mesh[i];
  }
  Image illum(w, h, 3, c), prev_color(w, h, 3, prev_c), prev_moments(w, h, 2),
      prev_hist(w, h, 1);
  for (int i = 0; i < w * h; ++i) {
    prev_moments.plane(0)[i] = prev_m1;
    prev_moments.plane(1)[i] = prev_m2;
    prev_hist.plane(0)[i] = prev_history[i];
  }
  ReprojectRun r{Image(w, h, 4), Image(w, h, 2), Image(w, h, 1)};
  ReprojectKernel k;
  k.params = svgf_preset("falcor");  // Falcor's documented values, no anti-lag
  k.guides = cur.guides();
  k.prev_guides = prev.guides();
  k.illumination = illum.rgb();
  k.prev_color = prev_color.rgb();
  k.prev_moment1 = prev_moments.plane(0);
  k.prev_moment2 = prev_moments.plane(1);
  k.prev_history = prev_hist.plane(0);
  k.has_history = true;
  k.accumulated = {r.accumulated.rgb(), r.accumulated.plane(3)};
  k.moment1 = r.moments.plane(0);
  k.moment2 = r.moments.plane(1);
  k.history = r.history.plane(0);
  cpu::for_each_pixel(w, h, k);
  return r;
}

}  // namespace

TEST_CASE("params: a long history is capped at 32 and blended with alpha 0.05 and 0.2",
          "[params][reproject]") {
  // Previous history 40 frames: the new length is min(40 + 1, 32) = 32, and since 1/32 is
  // below both alphas, color blends with 0.05 and the moments with 0.2:
  //   color 0.5 + (1.5 - 0.5) * 0.05 = 0.55,
  //   m1 = 0.25 + (1.5 - 0.25) * 0.2 = 0.5,  m2 = 0.1 + (2.25 - 0.1) * 0.2 = 0.53,
  //   variance = 0.53 - 0.5^2 = 0.28 (luminance of a grey 1.5 is 1.5).
  // A previous history of 31 gives length exactly 32 too, and 30 gives 31 (below the cap).
  const int w = 3, h = 3;
  for (const auto& [prev_len, want_len] : {std::pair<float, float>{40.f, 32.f}, {31.f, 32.f},
                                           {30.f, 31.f}}) {
    const ReprojectRun r =
        reproject_once(w, h, 1.5f, 0.5f, 0.25f, 0.1f, std::vector<float>(w * h, prev_len), {});
    INFO("previous history " << prev_len);
    REQUIRE(r.history.at(1, 1, 0) == want_len);
    for (int ch = 0; ch < 3; ++ch)
      REQUIRE(relative_difference(r.accumulated.at(1, 1, ch), 0.5 + 1.0 * kAlpha) < 1e-6);
    const double m1 = 0.25 + (1.5 - 0.25) * kMomentsAlpha;
    const double m2 = 0.1 + (2.25 - 0.1) * kMomentsAlpha;
    REQUIRE(relative_difference(r.moments.at(1, 1, 0), m1) < 1e-6);
    REQUIRE(relative_difference(r.moments.at(1, 1, 1), m2) < 1e-6);
    REQUIRE(relative_difference(r.accumulated.at(1, 1, 3), m2 - m1 * m1) < 1e-5);
  }
}

TEST_CASE("params: bilinear taps are kept down to a total weight of 0.01", "[params][reproject]") {
  // Motion (1/8, fy) from pixel (2, 2) of a 5x5 frame: the bilinear taps are (2..3, 2..3), and
  // only (3, 3), of weight fx * fy, is on this pixel's mesh; so is (1, 1), which only the 3x3
  // fallback around the nearest pixel (2, 2) reaches. History 4 at (3, 3) and 2 at (1, 1): the
  // bilinear read gives length 4 + 1 = 5, the fallback (4 + 2) / 2 + 1 = 4.
  //   fy = 21/256: weight 21/2048 = 0.01025 >= 0.01, bilinear;
  //   fy = 20/256: weight 20/2048 = 0.00977 <  0.01, fallback. (Both products exact in float.)
  const int w = 5, h = 5;
  std::vector<uint32_t> mesh(w * h, 7u);
  std::vector<float> hist(w * h, 1.f);
  mesh[3 * w + 3] = 1u;
  hist[3 * w + 3] = 4.f;
  mesh[1 * w + 1] = 1u;
  hist[1 * w + 1] = 2.f;
  REQUIRE(0.125 * 21 / 256 >= kReprojectMinWeight);
  REQUIRE(0.125 * 20 / 256 < kReprojectMinWeight);
  const ReprojectRun kept = reproject_once(w, h, 1.f, 1.f, 1.f, 1.f, hist, mesh, 0.125f, 21.f / 256);
  REQUIRE(kept.history.at(2, 2, 0) == 5.f);
  const ReprojectRun fallback =
      reproject_once(w, h, 1.f, 1.f, 1.f, 1.f, hist, mesh, 0.125f, 20.f / 256);
  REQUIRE(fallback.history.at(2, 2, 0) == 4.f);
}

TEST_CASE("params: the paper's, Falcor's and the converging configurations by name",
          "[params]") {
  // Schied et al. 2017 (Sec. 4-5): 5 iterations, the first one's output fed back, sigma_l 4,
  // alpha 0.2 for color and moments. Falcor's SVGFPass: 4 iterations, tap 1, phi_color 10,
  // alpha 0.05, moments 0.2, history capped at 32. Neither divides the variance by the history.
  const SvgfParams paper = svgf_preset("paper");
  CHECK(paper.iterations == 5);
  CHECK(paper.feedback_tap == 0);
  CHECK(paper.phi_color == 4.f);
  CHECK(paper.alpha == 0.2f);
  CHECK(paper.moments_alpha == 0.2f);
  CHECK(paper.history_cap == 32);
  CHECK_FALSE(paper.variance_of_mean);
  const SvgfParams falcor = svgf_preset("falcor");
  CHECK(falcor.iterations == 4);
  CHECK(falcor.feedback_tap == 1);
  CHECK(falcor.phi_color == 10.f);
  CHECK(falcor.alpha == 0.05f);
  CHECK(falcor.moments_alpha == 0.2f);
  CHECK(falcor.history_cap == 32);
  CHECK_FALSE(falcor.variance_of_mean);
  // docs/svgf.md, Static convergence.
  const SvgfParams converge = svgf_preset("converge");
  CHECK(converge.iterations == 4);
  CHECK(converge.feedback_tap == -1);
  CHECK(converge.phi_color == 4.f);
  CHECK(converge.alpha == 0.03f);
  CHECK(converge.history_cap == 64);
  CHECK(converge.variance_of_mean);
  CHECK(converge.antilag == Antilag::Off);
  CHECK(paper.antilag == Antilag::Off);
  CHECK(falcor.antilag == Antilag::Off);
  CHECK(falcor.gradient_iterations == 3);
  // The defaults are "converge" with A-SVGF's anti-lag (docs/svgf.md: Defaults); "default" is
  // SvgfParams().
  const SvgfParams def;
  CHECK(def.antilag == Antilag::Gradient);
  CHECK(def.gradient_iterations == 1);
  CHECK(def.gradient_lambda_radius == 1);
  CHECK((def.feedback_tap == converge.feedback_tap && def.phi_color == converge.phi_color &&
         def.alpha == converge.alpha && def.history_cap == converge.history_cap &&
         def.variance_of_mean == converge.variance_of_mean));
  CHECK(converge.phi_normal == SvgfParams().phi_normal);
  CHECK(converge.moments_alpha == SvgfParams().moments_alpha);
  CHECK(svgf_preset("default").feedback_tap == SvgfParams().feedback_tap);
  CHECK(svgf_preset("default").variance_of_mean == SvgfParams().variance_of_mean);
  for (const SvgfParams& p : {paper, falcor, converge}) REQUIRE_NOTHROW(p.validate());
  REQUIRE_THROWS_WITH(svgf_preset("Falcor"),
                      Catch::Contains("default, falcor, paper or converge") &&
                          Catch::Contains("'Falcor'"));
}

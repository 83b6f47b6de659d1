// The joint bilateral filter (methods/jbf/, GAMES202 homework 5): one pass in both forms against
// a double-precision reference written from the homework's formula (docs/jbf.md), edges that
// stop it, bad samples, the a-trous form against the full window on a rendered frame, and the
// interface; every body on the CPU, CUDA exact and CUDA fast (tests/test_device.h).
#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <catch2/catch.hpp>

#include "io/sequence.h"
#include "methods/jbf/denoiser.h"
#include "metrics/image_metrics.h"
#include "pipeline/make_denoiser.h"
#include "synthetic_sequence.h"
#include "test_device.h"
#include "test_support.h"

using namespace svgf;
using svgf::test::StageRunner;
using svgf::test::TestDevice;
using svgf::test::with_arith;

namespace {

// A bumpy tilted surface: positions on the plane z = 0.05 x + 0.08 y (pixel units scaled by
// 0.1) with jitter, normals within ~6 degrees of the plane's, noisy color; one background pixel.
Frame jbf_bumpy_frame(int w, int h, uint32_t seed) {
  Frame f = test::flat_frame(w, h);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.f, 1.f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      f.position.at(x, y, 0) = 0.1f * x;
      f.position.at(x, y, 1) = 0.1f * y;
      f.position.at(x, y, 2) = 0.005f * x + 0.008f * y + 0.004f * u(rng);
      const float nx = -0.05f + 0.1f * u(rng), ny = -0.08f + 0.1f * u(rng);
      const float len = std::sqrt(nx * nx + ny * ny + 1.f);
      f.normal.at(x, y, 0) = nx / len;
      f.normal.at(x, y, 1) = ny / len;
      f.normal.at(x, y, 2) = 1.f / len;
    }
  test::fill_uniform(f.color, 0.f, 1.5f, seed + 1);
  f.depth.at(2, 3, 0) = 0.f;
  return f;
}

// One pass in double: J from the homework's formula (acos of the clamped dot, the plane
// distance 0 where the positions coincide), B3 weights in the a-trous form, taps outside the
// image or without a surface skipped, background passing through.
Image reference_pass(const Frame& f, const Image& in, int radius, int step, bool b3,
                     const JbfParams& p) {
  const int w = f.width(), h = f.height();
  const double h5[3] = {3.0 / 8, 1.0 / 4, 1.0 / 16};
  auto v3 = [](const Image& im, int x, int y) {
    return std::array<double, 3>{im.at(x, y, 0), im.at(x, y, 1), im.at(x, y, 2)};
  };
  Image out(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (!(f.depth.at(x, y, 0) > 0)) {
        for (int c = 0; c < 3; ++c) out.at(x, y, c) = in.at(x, y, c);
        continue;
      }
      const auto ci = v3(in, x, y), ni = v3(f.normal, x, y), xi = v3(f.position, x, y);
      double ws = 0, cs[3] = {0, 0, 0};
      for (int dy = -radius; dy <= radius; ++dy)
        for (int dx = -radius; dx <= radius; ++dx) {
          const int xq = x + dx * step, yq = y + dy * step;
          if (xq < 0 || yq < 0 || xq >= w || yq >= h || !(f.depth.at(xq, yq, 0) > 0)) continue;
          const auto cj = v3(in, xq, yq), nj = v3(f.normal, xq, yq), xj = v3(f.position, xq, yq);
          double dc = 0, nd = 0, len2 = 0, pd = 0;
          for (int c = 0; c < 3; ++c) {
            dc += (ci[c] - cj[c]) * (ci[c] - cj[c]);
            nd += ni[c] * nj[c];
            len2 += (xj[c] - xi[c]) * (xj[c] - xi[c]);
            pd += ni[c] * (xj[c] - xi[c]);
          }
          const double angle = std::acos(std::min(1.0, std::max(-1.0, nd)));
          const double plane = len2 > 0 ? pd / std::sqrt(len2) : 0.0;
          const double d2 = double(dx * dx + dy * dy) * step * step;
          double wt = (dx == 0 && dy == 0)
                          ? 1.0
                          : std::exp(-d2 / (2.0 * p.sigma_coord * p.sigma_coord) -
                                     dc / (2.0 * p.sigma_color * p.sigma_color) -
                                     angle * angle / (2.0 * p.sigma_normal * p.sigma_normal) -
                                     plane * plane / (2.0 * p.sigma_plane * p.sigma_plane));
          if (b3) wt *= h5[std::abs(dx)] * h5[std::abs(dy)];
          ws += wt;
          for (int c = 0; c < 3; ++c) cs[c] += wt * cj[c];
        }
      for (int c = 0; c < 3; ++c) out.at(x, y, c) = static_cast<float>(cs[c] / ws);
    }
  return out;
}

void jbf_pass_against_double(const TestDevice& d) {
  const int w = 23, h = 19;
  const Frame f = jbf_bumpy_frame(w, h, 3);
  std::vector<std::pair<std::string, JbfParams>> sets;
  auto with = [&](const std::string& name, auto change) {
    JbfParams p;
    change(p);
    sets.emplace_back(name, p);
  };
  // The defaults, then each sigma moved so that its term decides the weights.
  with("defaults", [](JbfParams&) {});
  with("sigma_coord 1.5", [](JbfParams& p) { p.sigma_coord = 1.5f; });
  with("sigma_color 0.2", [](JbfParams& p) { p.sigma_color = 0.2f; });
  // The normal term is ill-conditioned at small angles: the float dot product's rounding
  // (~6e-8) moves acos by 6e-8 / sin(angle), which 1 / (2 sigma_normal^2) = 556 magnifies; this
  // set gets a wider tolerance below.
  with("sigma_normal 0.03", [](JbfParams& p) { p.sigma_normal = 0.03f; });
  with("sigma_plane 0.01", [](JbfParams& p) { p.sigma_plane = 0.01f; });
  with("all wide", [](JbfParams& p) {
    p.sigma_color = 5.f;
    p.sigma_normal = 2.f;
    p.sigma_plane = 3.f;
  });
  struct Form {
    int radius, step;
    bool b3;
  };
  for (const auto& set : sets)
    for (const Form form : {Form{4, 1, false}, Form{2, 1, true}, Form{2, 2, true},
                            Form{2, 4, true}}) {
      const JbfParams& p = set.second;
      Image out(w, h, 3);
      StageRunner r(d);
      with_arith(d, [&](auto arith) {
        using Arith = decltype(arith);
        r.run(JbfPass<Arith>{r.guides(f), r.rgb(f.position), r.rgb(f.color), r.rgb(out),
                             form.radius, form.step, form.b3, JbfScales::of(p)},
              w, h, "jbf pass");
      });
      const double worst = test::max_relative_difference(
          out, reference_pass(f, f.color, form.radius, form.step, form.b3, p), 1e-3);
      INFO(set.first << ", radius " << form.radius << " step " << form.step
                     << (form.b3 ? " (a-trous)" : " (full)") << ": worst relative difference "
                     << worst);
      REQUIRE(worst < d.tolerance(p.sigma_normal < 0.05f ? 1e-4 : 2e-5));
    }
}

std::unique_ptr<Denoiser> jbf_on(const TestDevice& d, Method m, const JbfParams& p,
                                 int threads = 2) {
  DenoiserConfig c = d.config(DenoiserConfig());
  c.method = m;
  c.threads = threads;
  c.jbf = p;
  return make_denoiser(c);
}

void jbf_constant_stays_constant(const TestDevice& d) {
  for (Method m : {Method::Jbf, Method::JbfAtrous}) {
    Frame f = jbf_bumpy_frame(31, 21, 5);
    for (float& v : f.color.data()) v = 0.45f;
    JbfParams p;
    p.radius = 5;
    Image out;
    jbf_on(d, m, p)->denoise(f, out);
    INFO(to_string(m));
    for (float v : out.data()) REQUIRE(v == Approx(0.45f).epsilon(d.tolerance(1e-6)));
  }
}

// Two regions left and right of x = 10 that differ in one guide, with different colors close
// enough that the color term alone would blend them.
void no_bleeding(const TestDevice& d, const std::function<void(Frame&)>& split) {
  for (Method m : {Method::Jbf, Method::JbfAtrous}) {
    Frame f = test::flat_frame(20, 8);
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 20; ++x) {
        f.position.at(x, y, 0) = 0.1f * x;
        f.position.at(x, y, 1) = 0.1f * y;
        for (int c = 0; c < 3; ++c) f.color.at(x, y, c) = x < 10 ? 0.4f : 0.6f;
      }
    split(f);
    JbfParams p;
    p.radius = 6;
    p.sigma_color = 10.f;  // the color term lets everything through
    Image out;
    jbf_on(d, m, p)->denoise(f, out);
    for (int y = 0; y < 8; ++y) {
      INFO(to_string(m) << ", row " << y);
      REQUIRE(out.at(9, y, 0) == Approx(0.4f).epsilon(1e-3));
      REQUIRE(out.at(10, y, 0) == Approx(0.6f).epsilon(1e-3));
    }
  }
}

void jbf_edges_stop_the_filter(const TestDevice& d) {
  SECTION("normal: 0.6 rad apart, exp(-0.36 / 0.02)") {
    no_bleeding(d, [](Frame& f) {
      for (int y = 0; y < 8; ++y)
        for (int x = 10; x < 20; ++x) {
          f.normal.at(x, y, 0) = std::sin(0.6f);
          f.normal.at(x, y, 2) = std::cos(0.6f);
        }
    });
  }
  SECTION("plane: a step of 0.5 in z, the same normals") {
    no_bleeding(d, [](Frame& f) {
      for (int y = 0; y < 8; ++y)
        for (int x = 10; x < 20; ++x) f.position.at(x, y, 2) = 0.5f;
    });
  }
}

void jbf_bad_samples_replaced(const TestDevice& d) {
  Frame f = jbf_bumpy_frame(16, 12, 7);
  f.color.at(3, 4, 0) = std::numeric_limits<float>::quiet_NaN();
  f.color.at(5, 5, 1) = std::numeric_limits<float>::infinity();
  f.color.at(8, 2, 2) = -2.f;
  JbfParams p;
  p.radius = 3;
  for (Method m : {Method::Jbf, Method::JbfAtrous}) {
    auto den = jbf_on(d, m, p);
    Image out;
    den->denoise(f, out);
    REQUIRE(den->last_report().replaced_samples == 3);
    for (float v : out.data()) REQUIRE(std::isfinite(v));
    REQUIRE(den->last_report().repairs.total() == 3);
  }
}

// The a-trous form against the full window on a rendered frame (the first frame of each
// fixture with a reference, else the synthetic scene): how far apart they are, and that both
// beat the noisy input. The numbers are in docs/jbf.md.
void atrous_against_full(const TestDevice& d) {
  std::vector<Frame> frames;
  const char* root = std::getenv("SVGF_FIXTURES_DIR");
  const std::string dir = std::string(root ? root : SVGF_SOURCE_DIR "/fixtures") + "/cornell-moving";
  try {
    frames.push_back(io::Sequence(dir).read(0));
  } catch (const std::exception&) {
    test::SyntheticScene scene;
    frames.push_back(scene.frame(0));
  }
  for (const Frame& f : frames) {
    Image full, atrous;
    jbf_on(d, Method::Jbf, JbfParams())->denoise(f, full);
    jbf_on(d, Method::JbfAtrous, JbfParams())->denoise(f, atrous);
    const double noisy = metrics::psnr(f.color, f.reference);
    const double p_full = metrics::psnr(full, f.reference);
    const double p_atrous = metrics::psnr(atrous, f.reference);
    const double between = metrics::psnr(atrous, full);
    std::printf("jbf on %s frame 0 (%s): noisy %.2f dB, full window %.2f dB, a-trous %.2f dB, "
                "a-trous against full %.2f dB\n", dir.c_str(), d.name().c_str(), noisy, p_full,
                p_atrous, between);
    INFO("noisy " << noisy << ", full " << p_full << ", a-trous " << p_atrous
                  << ", a-trous against full " << between << " dB");
    REQUIRE(p_full > noisy + 3.0);
    REQUIRE(p_atrous > noisy + 3.0);
    REQUIRE(std::fabs(p_atrous - p_full) < 3.0);
  }
}

// Two frames of a static view: the second frame's output is lerp(clamp(F0), F1, alpha) with
// the clamp per channel to mean +- k sigma of F1 over the 7x7 block (inside the image), F0 and
// F1 the frames' filtered colors (read back as the "filtered" buffer). In double, from the
// homework's formula; every alpha and k moves the result.
void temporal_known_answer(const TestDevice& d) {
  const int w = 19, h = 13;
  Frame f0 = jbf_bumpy_frame(w, h, 21), f1 = f0;
  test::fill_uniform(f1.color, 0.f, 1.5f, 99);  // not jbf_bumpy_frame's own seed (22)
  for (const std::pair<float, float>& ak : {std::pair<float, float>{0.2f, 1.f}, {0.5f, 0.3f},
                                            {0.2f, 100.f}}) {
    JbfParams p;
    p.radius = 3;
    p.alpha = ak.first;
    p.clamp_k = ak.second;
    auto den = jbf_on(d, Method::Jbf, p);
    Image out0, out1;
    den->denoise(f0, out0);
    const Image filtered0 = den->read_buffer(jbf_buffer::kFiltered);
    test::require_identical(out0, filtered0, "first frame: the filtered color");
    den->denoise(f1, out1);
    const Image filtered1 = den->read_buffer(jbf_buffer::kFiltered);
    test::require_identical(den->read_buffer(jbf_buffer::kAccumulated), out1, "history = output");
    int clamped = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        if (!(f1.depth.at(x, y, 0) > 0)) continue;
        for (int c = 0; c < 3; ++c) {
          double m1 = 0, m2 = 0;
          int n = 0;
          for (int dy = -3; dy <= 3; ++dy)
            for (int dx = -3; dx <= 3; ++dx) {
              if (x + dx < 0 || y + dy < 0 || x + dx >= w || y + dy >= h) continue;
              const double v = filtered1.at(x + dx, y + dy, c);
              m1 += v;
              m2 += v * v;
              ++n;
            }
          const double mean = m1 / n, sd = std::sqrt(std::max(0.0, m2 / n - mean * mean));
          const double hist = filtered0.at(x, y, c);
          const double held = std::min(std::max(hist, mean - p.clamp_k * sd), mean + p.clamp_k * sd);
          clamped += held != hist;
          const double want = held + (filtered1.at(x, y, c) - held) * p.alpha;
          INFO("alpha " << p.alpha << " k " << p.clamp_k << " at (" << x << "," << y << ") " << c);
          REQUIRE(out1.at(x, y, c) == Approx(want).epsilon(d.tolerance(1e-5)).margin(1e-6));
        }
      }
    if (p.clamp_k < 50.f) REQUIRE(clamped > 0);  // the clamp was exercised
    else REQUIRE(clamped == 0);
  }
}

// No history where the previous pixel shows another object, lies outside the image, or after
// reset(): those pixels take this frame's filtered color.
void temporal_invalid_history(const TestDevice& d) {
  const int w = 16, h = 10;
  Frame f0 = jbf_bumpy_frame(w, h, 31), f1 = f0;
  test::fill_uniform(f1.color, 0.f, 1.5f, 98);  // not jbf_bumpy_frame's own seed (32)
  for (int y = 0; y < h; ++y) f1.mesh_id[y * w + 5] = 7;  // a new object in column 5
  for (int y = 0; y < h; ++y) f1.motion.at(w - 1, y, 0) = 4.f;  // the last column came from outside
  JbfParams p;
  p.radius = 2;
  auto den = jbf_on(d, Method::Jbf, p);
  Image out;
  den->denoise(f0, out);
  den->denoise(f1, out);
  const Image filtered = den->read_buffer(jbf_buffer::kFiltered);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const bool fresh = x == 5 || x == w - 1;
      INFO("(" << x << "," << y << ")");
      if (fresh) REQUIRE(out.at(x, y, 1) == filtered.at(x, y, 1));
    }
  int with_history = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) with_history += out.at(x, y, 1) != filtered.at(x, y, 1);
  INFO(with_history << " pixels differ from the filtered color");
  REQUIRE(with_history > w * h / 2);  // elsewhere the history counts
  den->reset();
  den->denoise(f1, out);
  test::require_identical(out, den->read_buffer(jbf_buffer::kFiltered), "after reset");
}

}  // namespace

SVGF_DEVICE_TEST("jbf: one pass against a double-precision reference, both forms, every sigma",
                 "[jbf]", jbf_pass_against_double)
SVGF_DEVICE_TEST("jbf: a constant image stays constant, both forms", "[jbf]",
                 jbf_constant_stays_constant)
SVGF_DEVICE_TEST("jbf: normal and plane edges stop the filter, both forms", "[jbf]",
                 jbf_edges_stop_the_filter)
SVGF_DEVICE_TEST("jbf: NaN, Inf and negative color are replaced by 0 and counted", "[jbf]",
                 jbf_bad_samples_replaced)
SVGF_DEVICE_TEST("jbf: the a-trous form against the full window on a rendered frame", "[jbf]",
                 atrous_against_full)
SVGF_DEVICE_TEST("jbf: temporal accumulation, the clamped history blended with alpha", "[jbf]",
                 temporal_known_answer)
SVGF_DEVICE_TEST("jbf: no history across an object change, from outside, or after reset",
                 "[jbf]", temporal_invalid_history)

TEST_CASE("jbf: same bits on 1 and 2 threads; stages, defaults and errors", "[jbf]") {
  const Frame f = jbf_bumpy_frame(29, 17, 11);
  JbfParams small;
  small.radius = 4;
  Image a, b;
  jbf_on(test::kCpu, Method::Jbf, small, 1)->denoise(f, a);
  auto two = jbf_on(test::kCpu, Method::Jbf, small, 2);
  two->denoise(f, b);
  test::require_identical(a, b, "1 vs 2 threads");
  REQUIRE(two->stages() == std::vector<std::string>{"sanitize", "filter", "temporal"});
  REQUIRE(jbf_on(test::kCpu, Method::JbfAtrous, small)->stages() ==
          std::vector<std::string>{"sanitize", "atrous", "temporal"});
  // The homework framework's defaults (docs/jbf.md: src/denoiser.h, Filter()).
  const JbfParams p;
  REQUIRE(p.radius == 16);
  REQUIRE(p.sigma_coord == 32.f);
  REQUIRE(p.sigma_color == 0.6f);
  REQUIRE(p.sigma_normal == 0.1f);
  REQUIRE(p.sigma_plane == 0.1f);
  REQUIRE(p.alpha == 0.2f);
  REQUIRE(p.clamp_k == 1.f);
  REQUIRE(parse_method("jbf") == Method::Jbf);
  REQUIRE(parse_method("jbf-atrous") == Method::JbfAtrous);
  auto bad = [](auto change) {
    JbfParams q;
    change(q);
    return jbf_on(test::kCpu, Method::Jbf, q);
  };
  REQUIRE_THROWS_WITH(bad([](JbfParams& q) { q.radius = 0; }), Catch::Contains("--jbf-radius"));
  REQUIRE_THROWS_WITH(bad([](JbfParams& q) { q.sigma_coord = -1.f; }), Catch::Contains("--jbf-sigma-coord"));
  REQUIRE_THROWS_WITH(bad([](JbfParams& q) { q.sigma_color = 0.f; }), Catch::Contains("--jbf-sigma-color"));
  REQUIRE_THROWS_WITH(bad([](JbfParams& q) { q.sigma_normal = NAN; }), Catch::Contains("--jbf-sigma-normal"));
  REQUIRE_THROWS_WITH(bad([](JbfParams& q) { q.sigma_plane = -2.f; }), Catch::Contains("--jbf-sigma-plane"));
  REQUIRE_THROWS_WITH(bad([](JbfParams& q) { q.alpha = 0.f; }), Catch::Contains("--jbf-alpha"));
  REQUIRE_THROWS_WITH(bad([](JbfParams& q) { q.clamp_k = -1.f; }), Catch::Contains("--jbf-clamp-k"));
  Frame no_position = f;
  no_position.position = Image();
  Image out;
  REQUIRE_THROWS_WITH(jbf_on(test::kCpu, Method::Jbf, small)->denoise(no_position, out),
                      Catch::Contains("position"));
}

// A-SVGF's gradient stages (methods/svgf/gradient.h) and their use in the reprojection, on
// every backend (tests/test_device.h). Fast mode runs these exact kernels: CPU and CUDA exact.
#include <cmath>
#include <limits>
#include <random>
#include <utility>

#include <catch2/catch.hpp>

#include "methods/svgf/gradient.h"
#include "methods/svgf/gradient_tile.h"
#include "methods/svgf/reproject.h"
#include "test_device.h"
#include "test_support.h"

using namespace svgf;
using svgf::test::TestDevice;

namespace {

// A 7x5 frame (3x2 strata, the last column and row partial) with hand-placed samples:
//   stratum (0,0): sample at (1,2): previous 2, current 3          -> delta 1, normalizer 3
//   stratum (1,0): samples at (5,0) [first in raster order] and (3,2) -> (5,0): 4, 4 -> 0, 4
//   stratum (2,0): sample at (6,0): 0, 0                           -> 0, 0, with data
//   stratum (0,1): sample at (0,4): 1.5, 0.5                       -> -1, 1.5
//   stratum (1,1): sample at (4,3) with a NaN current              -> no data, guide there
//   stratum (2,1): no sample                                       -> no data, guide (6,4)
Frame hand_made_frame() {
  Frame f = test::flat_frame(7, 5);
  f.gradient = Image(7, 5, 3);
  const auto sample = [&](int x, int y, float previous, float current) {
    f.gradient.at(x, y, 0) = previous;
    f.gradient.at(x, y, 1) = current;
    f.gradient.at(x, y, 2) = 1.f;
  };
  sample(1, 2, 2.f, 3.f);
  sample(5, 0, 4.f, 4.f);
  sample(3, 2, 9.f, 1.f);
  sample(6, 0, 0.f, 0.f);
  sample(0, 4, 1.5f, 0.5f);
  sample(4, 3, 1.f, std::nanf(""));
  return f;
}

// Stage 1 on `f` into `signal` (3 planes of strata) and `offset`.
void run_samples(test::StageRunner& r, const Frame& f, Image& signal, Image& offset) {
  GradientSamplesKernel k;
  k.width = f.width();
  k.height = f.height();
  k.samples = {r.plane(f.gradient, 0), r.plane(f.gradient, 1), r.plane(f.gradient, 2)};
  k.out = {r.plane(signal, 0), r.plane(signal, 1), r.plane(signal, 2)};
  k.strata_width = signal.width();
  k.guide_offset = r.plane(offset);
  r.run(k, signal.width(), signal.height(), "gradient samples");
}

void samples_per_stratum(const TestDevice& d) {
  const Frame f = hand_made_frame();
  REQUIRE(strata_along(7) == 3);
  REQUIRE(strata_along(5) == 2);
  Image signal(3, 2, 3), offset(3, 2, 1);
  test::StageRunner r(d);
  run_samples(r, f, signal, offset);
  const float delta[6] = {1.f, 0.f, 0.f, -1.f, 0.f, 0.f};
  const float normalizer[6] = {3.f, 4.f, 0.f, 1.5f, 0.f, 0.f};
  const float weight[6] = {1.f, 1.f, 1.f, 1.f, 0.f, 0.f};
  // Offsets k = dy * 3 + dx: (1,2) -> 7, (5,0) -> 2, (6,0) -> 0, (0,4) -> 3, (4,3) -> 1, and
  // the partial stratum (2,1)'s centre clamped into it: (6,4) -> 3.
  const float guide[6] = {7.f, 2.f, 0.f, 3.f, 1.f, 3.f};
  for (int s = 0; s < 6; ++s) {
    INFO("stratum " << s);
    REQUIRE(signal.plane(0)[s] == delta[s]);
    REQUIRE(signal.plane(1)[s] == normalizer[s]);
    REQUIRE(signal.plane(2)[s] == weight[s]);
    REQUIRE(offset.plane(0)[s] == guide[s]);
  }
  // The guide pixel each offset names.
  const StratumGuides at{7, 3, offset.plane(0)};
  REQUIRE(at.pixel(0, 0) == 2 * 7 + 1);
  REQUIRE(at.pixel(1, 1) == 3 * 7 + 4);
  REQUIRE(at.pixel(2, 1) == 4 * 7 + 6);

  // Lambda without filtering: |1| / 3, 0, 0 (no normalizer), |-1| / 1.5, and 0 without data.
  Image lambda(3, 2, 1);
  r.run(GradientLambdaKernel{3, {r.plane(std::as_const(signal), 0),
                                 r.plane(std::as_const(signal), 1),
                                 r.plane(std::as_const(signal), 2)},
                             r.plane(lambda)},
        3, 2, "gradient lambda");
  const float want[6] = {1.f / 3.f, 0.f, 0.f, 1.f / 1.5f, 0.f, 0.f};
  for (int s = 0; s < 6; ++s) REQUIRE(lambda.plane(0)[s] == want[s]);

  // Radius 1: each stratum takes the largest lambda of the 3x3 strata around it, clipped to
  // the 3x2 stratum image: stratum 3's 2/3 reaches strata 0, 1, 3 and 4; strata 2 and 5 see
  // strata 1, 2, 4 and 5 only, all 0 (stratum 0's 1/3 is two columns away).
  r.run(GradientLambdaKernel{3,
                             {r.plane(std::as_const(signal), 0), r.plane(std::as_const(signal), 1),
                              r.plane(std::as_const(signal), 2)},
                             r.plane(lambda), 2, 1},
        3, 2, "gradient lambda, radius 1");
  const float want_r1[6] = {1.f / 1.5f, 1.f / 1.5f, 0.f, 1.f / 1.5f, 1.f / 1.5f, 0.f};
  for (int s = 0; s < 6; ++s) {
    INFO("stratum " << s);
    REQUIRE(lambda.plane(0)[s] == want_r1[s]);
  }
}

// lambda = min(1, |delta| / normalizer) and alpha' = (1 - lambda) alpha + lambda (Eq. 15).
TEST_CASE("gradient: lambda and alpha' known answers", "[gradient]") {
  REQUIRE(gradient_lambda(1.f, 4.f) == 0.25f);
  REQUIRE(gradient_lambda(-3.f, 4.f) == 0.75f);
  REQUIRE(gradient_lambda(5.f, 2.f) == 1.f);  // rounding or a bad filter: never above 1
  REQUIRE(gradient_lambda(0.f, 0.f) == 0.f);
  REQUIRE(gradient_lambda(1.f, 0.f) == 0.f);
  REQUIRE(antilag_alpha(0.05f, 0.f) == 0.05f);  // lambda 0 leaves alpha's bits alone
  REQUIRE(antilag_alpha(0.05f, 1.f) == 1.f);
  REQUIRE(antilag_alpha(0.05f, 0.25f) == (1.f - 0.25f) * 0.05f + 0.25f);
  REQUIRE(antilag_alpha(0.05f, 0.25f) == Approx(0.2875).epsilon(1e-7));
  REQUIRE(antilag_alpha(1.f, 0.3f) <= 1.f);
}

// The a-trous's taps take their depth scale from two distances a stratum (axis, diagonal):
// the bits of tap_depth_scale for every tap of every step the parameters allow (1 to 2^7
// strata), over tolerances from tiny to huge.
TEST_CASE("gradient: a tap's depth scale by its distance class is tap_depth_scale's", "[gradient]") {
  for (int it = 0; it < 8; ++it) {
    GradientAtrousKernel k;
    k.step = 1 << it;
    const GradientAtrousKernel::InvTapDistances distances = k.inv_tap_distances();
    for (float inv_phi_z : {0.f, 1e-30f, 3e-8f, 0.37f, 1.f, 7.3f, 1e8f, 3e30f,
                            std::numeric_limits<float>::infinity()})
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          if (dx == 0 && dy == 0) continue;
          INFO("step " << k.step << ", tap (" << dx << ", " << dy << "), 1/phi_z " << inv_phi_z);
          const float want = ExactArith::tap_depth_scale(inv_phi_z, dx, dy, 3 * k.step);
          const float got = distances.depth_scale(inv_phi_z, dx, dy);
          REQUIRE(float_bits(got) == float_bits(want));
        }
  }
}

// A 3x1 or 5x1 row of strata over a flat frame (9 or 15 x 3 pixels), each stratum's guide its
// centre pixel; `data` strata have (delta, normalizer).
struct StrataRow {
  Frame frame;
  Image signal, out, offset;
  StrataRow(int strata) : frame(test::flat_frame(3 * strata, 3)), signal(strata, 1, 3),
                          out(strata, 1, 3), offset(strata, 1, 1, 4.f) {}
  void set(int s, float delta, float normalizer) {
    signal.at(s, 0, 0) = delta;
    signal.at(s, 0, 1) = normalizer;
    signal.at(s, 0, 2) = 1.f;
  }
  void run(test::StageRunner& r, int step, const SvgfParams& p = SvgfParams()) {
    GradientAtrousKernel k;
    k.guides = r.guides(frame);
    k.at = StratumGuides{frame.width(), signal.width(), r.plane(std::as_const(offset))};
    k.strata_height = 1;
    k.in = {r.plane(std::as_const(signal), 0), r.plane(std::as_const(signal), 1),
            r.plane(std::as_const(signal), 2)};
    k.out = {r.plane(out, 0), r.plane(out, 1), r.plane(out, 2)};
    k.step = step;
    k.phi_depth = p.gradient_phi_depth;
    k.phi_normal = p.gradient_phi_normal;
    k.depth_gradient_floor = p.depth_gradient_floor;
    r.run(k, signal.width(), 1, "gradient atrous");
  }
};

void atrous_known_answers(const TestDevice& d) {
  {  // Equal guides weigh 1: a box average of the strata with data; none in reach stays none.
    StrataRow row(3);
    row.set(0, 3.f, 6.f);
    row.set(2, 0.f, 2.f);
    test::StageRunner r(d);
    row.run(r, 1);
    REQUIRE(row.out.at(0, 0, 0) == 3.f);
    REQUIRE(row.out.at(0, 0, 1) == 6.f);
    REQUIRE(row.out.at(1, 0, 0) == 1.5f);  // filled from both sides
    REQUIRE(row.out.at(1, 0, 1) == 4.f);
    REQUIRE(row.out.at(1, 0, 2) == 1.f);
    REQUIRE(row.out.at(2, 0, 0) == 0.f);
    REQUIRE(row.out.at(2, 0, 1) == 2.f);
  }
  {  // Another mesh weighs 0.
    StrataRow row(3);
    row.set(0, 3.f, 6.f);
    row.set(2, 0.f, 2.f);
    for (int y = 0; y < 3; ++y)
      for (int x = 6; x < 9; ++x) row.frame.mesh_id[y * 9 + x] = 2;
    test::StageRunner r(d);
    row.run(r, 1);
    REQUIRE(row.out.at(1, 0, 0) == 3.f);
    REQUIRE(row.out.at(1, 0, 1) == 6.f);
  }
  {  // Depth: |2.3 - 2| / (phi_depth 1 * fwidth 0.1 * 3 pixels) = 1, a weight of exp(-1).
    StrataRow row(3);
    row.set(0, 3.f, 6.f);
    row.set(2, 0.f, 2.f);
    for (int i = 0; i < 27; ++i) row.frame.depth_gradient.plane(0)[i] = 0.1f;
    for (int y = 0; y < 3; ++y)
      for (int x = 6; x < 9; ++x) row.frame.depth.at(x, y, 0) = 2.3f;
    test::StageRunner r(d);
    row.run(r, 1);
    const double w = std::exp(-double(2.3f - 2.f) / (double(0.1f) * 3.0));  // about exp(-1)
    REQUIRE(w == Approx(std::exp(-1.0)).epsilon(1e-5));
    REQUIRE(row.out.at(1, 0, 0) == Approx(3.0 / (1.0 + w)).epsilon(1e-5));
    REQUIRE(row.out.at(1, 0, 1) == Approx((6.0 + 2.0 * w) / (1.0 + w)).epsilon(1e-5));
  }
  {  // Step 2 skips the neighbours: stratum 2 reads 0 and 4 only.
    StrataRow row(5);
    row.set(0, 1.f, 2.f);
    row.set(1, 100.f, 100.f);
    row.set(4, 3.f, 4.f);
    test::StageRunner r(d);
    row.run(r, 2);
    REQUIRE(row.out.at(2, 0, 0) == 2.f);
    REQUIRE(row.out.at(2, 0, 1) == 3.f);
    REQUIRE(row.out.at(3, 0, 0) == 100.f);  // 1 and 5 (outside): only 1
  }
}

// The reprojection under lambda: a 6x3 static frame (strata 2x1) with a history of length 10,
// color 1; this frame's illumination 3. Stratum 0 has lambda 0, stratum 1 lambda `l`.
struct LambdaRun {
  Image accumulated, moments, history;
};
LambdaRun reproject_with_lambda(const TestDevice& d, float l) {
  const int w = 6, h = 3;
  Frame cur = test::flat_frame(w, h), prev = test::flat_frame(w, h);
  Image illum(w, h, 3, 3.f), prev_color(w, h, 3, 1.f), prev_moments(w, h, 2, 1.f),
      prev_hist(w, h, 1, 10.f), lambda(2, 1, 1);
  lambda.at(1, 0, 0) = l;
  LambdaRun out{Image(w, h, 4), Image(w, h, 2), Image(w, h, 1)};
  test::StageRunner r(d);
  ReprojectKernel k;
  k.guides = r.guides(cur);
  k.prev_guides = r.guides(prev);
  k.illumination = r.rgb(std::as_const(illum));
  k.color = r.rgb(std::as_const(illum));
  k.albedo = r.rgb(std::as_const(cur.albedo));
  k.prev_color = r.rgb(std::as_const(prev_color));
  k.prev_moment1 = r.plane(std::as_const(prev_moments), 0);
  k.prev_moment2 = r.plane(std::as_const(prev_moments), 1);
  k.prev_history = r.plane(std::as_const(prev_hist));
  k.has_history = true;
  k.gradient_lambda = r.plane(std::as_const(lambda));
  k.accumulated = r.illum_var(out.accumulated);
  k.moment1 = r.plane(out.moments, 0);
  k.moment2 = r.plane(out.moments, 1);
  k.history = r.plane(out.history);
  k.params.antilag = Antilag::Gradient;
  r.run(k, w, h, "reproject");
  return out;
}

void reprojection_follows_lambda(const TestDevice& d) {
  const LambdaRun half = reproject_with_lambda(d, 0.5f);
  // Stratum 0 (x < 3): alpha = max(0.05, 1/11), history 11.
  const float a0 = 1.f / 11.f;
  REQUIRE(half.history.at(1, 1, 0) == 11.f);
  REQUIRE(half.accumulated.at(1, 1, 0) == 1.f + (3.f - 1.f) * a0);
  // Stratum 1: alpha' = 0.5 / 11 + 0.5, the moments' 0.5 * 0.2 + 0.5 = 0.6, history 1 / alpha'.
  const float a1 = (1.f - 0.5f) * a0 + 0.5f;
  const float am = (1.f - 0.5f) * 0.2f + 0.5f;
  const float l = luminance(make_vec3(3.f, 3.f, 3.f));
  for (int x = 3; x < 6; ++x) {
    INFO("x " << x);
    REQUIRE(half.accumulated.at(x, 2, 0) == 1.f + (3.f - 1.f) * a1);
    REQUIRE(half.accumulated.at(x, 2, 0) == Approx(1.0 + 2.0 * (0.5 / 11 + 0.5)));
    REQUIRE(half.moments.at(x, 2, 0) == 1.f + (l - 1.f) * am);
    REQUIRE(half.history.at(x, 2, 0) == 1.f / a1);
  }
  // Lambda 1 drops the history whole: the pixel restarts with this frame's sample.
  const LambdaRun all = reproject_with_lambda(d, 1.f);
  REQUIRE(all.history.at(4, 0, 0) == 1.f);
  REQUIRE(all.accumulated.at(4, 0, 0) == 3.f);
  REQUIRE(all.moments.at(4, 0, 1) == l * l);
  REQUIRE(all.history.at(2, 0, 0) == 11.f);
}

// A w x h frame for the fused stages: guides in patches of two meshes (strays of a third,
// holes, and guides the sanitize stage repairs: NaN depth and normals, normals too long, an
// infinite depth gradient), and gradient samples at about one pixel in six, so that strata have
// none, one or several; some samples are not radiance (NaN, negative: no data).
Frame random_gradient_frame(int w, int h, uint32_t seed) {
  Frame f = test::flat_frame(w, h);
  f.gradient = Image(w, h, 3);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  for (int i = 0; i < w * h; ++i) {
    const int x = i % w, y = i / w;
    const bool near = (x / 7 + y / 5) % 3 == 0;
    const float odd = u(rng);
    f.depth.plane(0)[i] = odd < 0.02f ? 0.f : (near ? 2.f + u(rng) * 0.05f : 5.f + u(rng));
    f.depth_gradient.plane(0)[i] = u(rng) * 0.1f - 0.05f;
    f.mesh_id[i] = odd > 0.97f ? 9u : (near ? 1u : 2u);
    const float tilt = u(rng) * 0.6f - 0.3f, n = std::sqrt(1.f + tilt * tilt);
    f.normal.plane(0)[i] = tilt / n;
    f.normal.plane(1)[i] = 0.f;
    f.normal.plane(2)[i] = 1.f / n;
    if (odd > 0.02f && odd < 0.025f) f.depth.plane(0)[i] = std::nanf("");
    if (odd > 0.03f && odd < 0.035f) f.normal.plane(1)[i] = std::nanf("");
    if (odd > 0.04f && odd < 0.045f)
      for (int c = 0; c < 3; ++c) f.normal.plane(c)[i] *= 2.f;
    if (odd > 0.05f && odd < 0.055f)
      f.depth_gradient.plane(1)[i] = std::numeric_limits<float>::infinity();
    if (u(rng) < 1.f / 6.f) {
      const float previous = u(rng) * 2.f, current = u(rng) < 0.3f ? previous : u(rng) * 2.f;
      f.gradient.at(x, y, 0) = odd > 0.5f && odd < 0.51f ? -1.f : previous;
      f.gradient.at(x, y, 1) = odd > 0.6f && odd < 0.61f ? std::nanf("") : current;
      f.gradient.at(x, y, 2) = 1.f;
    }
  }
  return f;
}

// `f` with its guides as the sanitize stage leaves them (core/sanitize.h); `repaired`: how many
// pixels it changed.
Frame with_sanitized_guides(Frame f, int& repaired) {
  repaired = 0;
  for (size_t i = 0; i < f.color.pixel_count(); ++i) {
    Vec3 n{f.normal.plane(0)[i], f.normal.plane(1)[i], f.normal.plane(2)[i]}, position;
    repaired += sanitize_guides(0u, f.depth.plane(0)[i], f.depth_gradient.plane(0)[i],
                                f.depth_gradient.plane(1)[i], n, position, false) != 0;
    f.normal.plane(0)[i] = n.x;
    f.normal.plane(1)[i] = n.y;
    f.normal.plane(2)[i] = n.z;
  }
  return f;
}

// The three stages as three passes (the stratum planes) and as GradientTileKernel's one block
// kernel give the same lambdas, bit for bit: sizes with partial strata, partial tiles, an image
// narrower than a tile and one of several tiles each way; every setting the tile kernel takes.
// The passes run after the sanitize stage; the tile kernel may run before it (CUDA fuses that
// stage into the demodulation: methods/svgf/pipeline.h) and reads the guides through its rule,
// so it is given the frame as it was and as the stage leaves it.
void tile_kernel_matches_the_stages(const TestDevice& d) {
  const SvgfParams p;
  for (const auto& size : {std::pair<int, int>{7, 5}, {61, 37}, {100, 151}, {197, 64}}) {
    const int w = size.first, h = size.second;
    const Frame raw = random_gradient_frame(w, h, static_cast<uint32_t>(w * 1000 + h));
    int repaired = 0;
    const Frame f = with_sanitized_guides(raw, repaired);
    if (w * h > 1000) REQUIRE(repaired > 0);
    const int sw = strata_along(w), sh = strata_along(h);
    for (int iterations : {0, 1})
      for (int radius : {0, 1}) {
        const std::string what = std::to_string(w) + "x" + std::to_string(h) + ", " +
                                 std::to_string(iterations) + " step(s), radius " +
                                 std::to_string(radius);
        INFO(what);
        Image signal(sw, sh, 3), filtered(sw, sh, 3), offset(sw, sh, 1);
        Image three(sw, sh, 1, -1.f), fused(sw, sh, 1, -1.f);
        test::StageRunner r(d);
        run_samples(r, f, signal, offset);
        GradientAtrousKernel a;
        a.guides = r.guides(f);
        a.at = StratumGuides{w, sw, r.plane(std::as_const(offset))};
        a.strata_height = sh;
        a.in = {r.plane(std::as_const(signal), 0), r.plane(std::as_const(signal), 1),
                r.plane(std::as_const(signal), 2)};
        a.out = {r.plane(filtered, 0), r.plane(filtered, 1), r.plane(filtered, 2)};
        a.step = 1;
        a.phi_depth = p.gradient_phi_depth;
        a.phi_normal = p.gradient_phi_normal;
        a.depth_gradient_floor = p.depth_gradient_floor;
        if (iterations > 0) r.run(a, sw, sh, "gradient atrous");
        const Image& last = iterations > 0 ? filtered : signal;
        r.run(GradientLambdaKernel{sw,
                                   {r.plane(last, 0), r.plane(last, 1), r.plane(last, 2)},
                                   r.plane(three), sh, radius},
              sw, sh, "gradient lambda");

        GradientTileKernel t;
        t.samples.width = w;
        t.samples.height = h;
        t.samples.samples = {r.plane(f.gradient, 0), r.plane(f.gradient, 1),
                             r.plane(f.gradient, 2)};
        t.samples.strata_width = sw;
        t.atrous = a;
        t.atrous.in = {};
        t.atrous.out = {};
        t.lambda = r.plane(fused);
        t.iterations = iterations;
        t.radius = radius;
        t.strata_width = sw;
        t.strata_height = sh;
        REQUIRE(GradientTileKernel::handles(iterations, radius));
        r.run_blocks(t, t.blocks(), "gradient tiles");
        test::require_identical(fused, three, what + ": lambda, fused against three passes");
        Image before(sw, sh, 1, -1.f);
        t.atrous.guides = r.guides(raw);
        t.lambda = r.plane(before);
        r.run_blocks(t, t.blocks(), "gradient tiles, guides not yet sanitized");
        test::require_identical(before, three,
                                what + ": lambda, fused before the sanitize stage");
        // Something to compare: lambdas strictly between 0 and 1 (and 0 where strata have no
        // sample and nothing spreads it), none outside [0, 1].
        int zero = 0, between = 0, one = 0;
        for (size_t i = 0; i < fused.pixel_count(); ++i) {
          const float l = fused.plane(0)[i];
          zero += l == 0.f;
          between += l > 0.f && l < 1.f;
          one += l == 1.f;
        }
        if (w * h > 1000) {
          CHECK(between > 0);
          if (iterations == 0 && radius == 0) CHECK(zero > 0);  // strata without a sample
        }
        CHECK(zero + between + one == static_cast<int>(fused.pixel_count()));
      }
  }
  REQUIRE_FALSE(GradientTileKernel::handles(2, 1));
  REQUIRE_FALSE(GradientTileKernel::handles(1, 2));
}

}  // namespace


SVGF_BACKEND_TEST("gradient: per-stratum samples of a hand-made 7x5 frame, and their lambda",
                  "[gradient]", samples_per_stratum)
SVGF_BACKEND_TEST("gradient: a-trous steps over the strata weigh by mesh, depth and data",
                  "[gradient]", atrous_known_answers)
SVGF_BACKEND_TEST("gradient: the reprojection blends with alpha' = (1 - lambda) alpha + lambda",
                  "[gradient][reproject]", reprojection_follows_lambda)
SVGF_BACKEND_TEST("gradient: the fused tile kernel gives the three stages' lambdas",
                  "[gradient]", tile_kernel_matches_the_stages)

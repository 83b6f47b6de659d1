// metrics/lighting_change.h on hand-made images: the shadow and lit regions a moving shadow
// leaves, the contrast, the changed pixels and the lag.
#include <cmath>
#include <vector>

#include <catch2/catch.hpp>

#include "metrics/lighting_change.h"

#include "test_support.h"

using namespace svgf;
using namespace svgf::metrics;

namespace {

Image gray(int w, int h, float v) { return Image(w, h, 3, v); }

using svgf::test::set_gray;

}  // namespace

// A 12x1 floor (mesh 1) lit at 1.0; a 2-pixel shadow (0.2) at x = 2..3 in frame 0 and at
// x = 8..9 in frame 1; pixel 11 is background (mesh 0) and x = 4 a penumbra (0.6) in frame 0.
TEST_CASE("lighting change: shadow regions, contrast", "[metrics]") {
  std::vector<Image> refs = {gray(12, 1, 1.f), gray(12, 1, 1.f)};
  set_gray(refs[0], 2, 0, 0.2f);
  set_gray(refs[0], 3, 0, 0.2f);
  set_gray(refs[0], 4, 0, 0.6f);
  set_gray(refs[1], 8, 0, 0.2f);
  set_gray(refs[1], 9, 0, 0.2f);
  std::vector<uint32_t> mesh(12, 1);
  mesh[11] = 0;
  const std::vector<std::vector<uint32_t>> meshes = {mesh, mesh};
  ShadowRule rule;
  rule.ring = 2;
  const ShadowFinder finder(refs, meshes, rule);

  const ShadowRegions r0 = finder.regions(0);
  REQUIRE(r0.shadow.count == 2);
  REQUIRE(r0.shadow.inside[2] == 1);
  REQUIRE(r0.shadow.inside[3] == 1);
  // Lit within 2 pixels of the shadow: x = 0, 1 and 5 (x = 4 is penumbra, in neither).
  REQUIRE(r0.lit.count == 3);
  REQUIRE(r0.lit.inside[0] == 1);
  REQUIRE(r0.lit.inside[1] == 1);
  REQUIRE(r0.lit.inside[4] == 0);
  REQUIRE(r0.lit.inside[5] == 1);
  REQUIRE(shadow_contrast(refs[0], r0) == Approx(0.8));

  const ShadowRegions r1 = finder.regions(1);
  REQUIRE(r1.shadow.count == 2);
  REQUIRE(r1.shadow.inside[8] == 1);
  // x = 6, 7 and 10; x = 11 is background.
  REQUIRE(r1.lit.count == 3);
  REQUIRE(r1.lit.inside[11] == 0);

  // A denoiser that spread the shadow over its neighbours halves the contrast: shadow 0.6,
  // lit 1.0 -> 0.4 (against the reference's 0.8); one that erased it gives 0.
  Image half = refs[0];
  set_gray(half, 2, 0, 0.6f);
  set_gray(half, 3, 0, 0.6f);
  REQUIRE(shadow_contrast(half, r0) == Approx(0.4));
  REQUIRE(shadow_contrast(gray(12, 1, 0.7f), r0) == Approx(0.0).margin(1e-12));

  // No shadow anywhere: the contrast is undefined, not 0.
  const std::vector<Image> flat = {gray(12, 1, 1.f)};
  const std::vector<std::vector<uint32_t>> one = {mesh};
  const ShadowFinder none(flat, one);
  REQUIRE(std::isnan(shadow_contrast(flat[0], none.regions(0))));
}

TEST_CASE("lighting change: changed pixels and error in them", "[metrics]") {
  Image before = gray(4, 1, 1.f), after = gray(4, 1, 1.f);
  set_gray(after, 0, 0, 0.5f);   // halved: changed
  set_gray(after, 1, 0, 0.9f);   // 10%: under the 25% rule
  set_gray(after, 3, 0, 0.1f);   // changed, but another mesh now
  const std::vector<uint32_t> mb = {1, 1, 1, 1}, ma = {1, 1, 1, 2};
  const PixelMask m = changed_pixels(before, after, mb, ma);
  REQUIRE(m.count == 1);
  REQUIRE(m.inside[0] == 1);
  // relMSE over that pixel alone: (0.6 - 0.5)^2 / (0.25 + 0.01).
  Image out = after;
  set_gray(out, 0, 0, 0.6f);
  set_gray(out, 2, 0, 5.f);  // outside the mask: not counted
  REQUIRE(relmse_in(out, after, m) == Approx(0.01 / 0.26).epsilon(1e-6));
  REQUIRE(std::isnan(relmse_in(out, after, PixelMask{std::vector<uint8_t>(4, 0), 0})));
}

TEST_CASE("lighting change: lag", "[metrics]") {
  // Steady at -20 dB before the change at frame 3; back within 1 dB at frame 5.
  const std::vector<double> err = {-20, -20, -20, -5, -15, -19.5, -20};
  REQUIRE(lag_frames(err, 3) == 2);
  REQUIRE(lag_frames(err, 3, 3, 6.0) == 1);
  // Never back: -1.
  REQUIRE(lag_frames({-20, -20, -20, -5, -6, -7}, 3) == -1);
  // Back at once: 0.
  REQUIRE(lag_frames({-20, -20, -20, -19.5}, 3) == 0);
  REQUIRE_THROWS(lag_frames(err, 2, 3));

  // Against the restart baseline: frame 3 + k is held to frame k's error. A history that was
  // still converging (-10, -14, -16) and restarts at the change (-9, -13.5, -16) lags 1 frame;
  // one that keeps the old light (-5, -7, -9) never gets back.
  const std::vector<double> restarted = {-10, -14, -16, -9, -13.5, -16};
  const std::vector<double> base = restart_baseline(restarted, 3);
  REQUIRE(base == std::vector<double>{-10, -14, -16, -10, -14, -16});
  REQUIRE(lag_frames(restarted, base, 3) == 0);  // -9 <= -10 + 1
  REQUIRE(lag_frames(restarted, base, 3, 0.5) == 1);
  const std::vector<double> kept = {-10, -14, -16, -5, -7, -9};
  REQUIRE(lag_frames(kept, restart_baseline(kept, 3), 3) == -1);
}

TEST_CASE("lighting change: a still scene's convergence", "[metrics]") {
  // Frames 0..3 are not judged; after frame 4 the largest drop is 32.0 -> 31.8.
  const std::vector<double> psnr = {20, 25, 28, 29, 30, 31, 32, 31.8, 32.5};
  const StaticConvergence c = static_convergence(psnr);
  REQUIRE(c.worst_drop == Approx(0.2));
  REQUIRE(c.gain == Approx(2.5));
  REQUIRE_FALSE(c.meets_rule());
  REQUIRE(static_convergence({30, 30, 30, 30, 30, 30.5, 32.1}).meets_rule());
  REQUIRE_THROWS(static_convergence({30, 31, 32, 33}));
}

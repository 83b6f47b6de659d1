#pragma once
// A-SVGF's temporal gradients (Schied, Peters, Dachsbacher 2018, "Gradient Estimation for
// Real-Time Adaptive Temporal Filtering"): the renderer re-shades one sample of the previous
// frame per 3x3 stratum at this frame with the same random numbers (Frame::gradient), so the
// difference of the two luminances is the change of the signal, without noise where nothing
// changed. Three stages over the stratum image (ceil(w/3) x ceil(h/3)), all in exact arithmetic
// in every mode (they feed the history decisions, as the reprojection does):
//   1. GradientSamplesKernel  per stratum: delta = current - previous, normalizer =
//                             max(current, previous) (the paper's Delta), weight 1; no sample
//                             (or one that is not radiance): 0, 0 and weight 0;
//   2. GradientAtrousKernel   a-trous steps of 3x3 taps (Schied's reference code: box taps),
//                             edge-stopped by mesh id, depth and normal at the strata's guide
//                             pixels; strata without data weigh 0;
//   3. GradientLambdaKernel   lambda = min(1, |delta| / normalizer) (0 where the normalizer is
//                             0), the largest over the (2 r + 1)^2 strata around (Schied's
//                             reference code, gGradientFilterRadius), which the reprojection
//                             turns into alpha' = (1 - lambda) alpha + lambda (the paper's
//                             Eq. 15; methods/svgf/reproject.h).
#include <cstdint>
#include <type_traits>

#include "core/arith.h"
#include "core/frame.h"
#include "core/frame_inputs.h"
#include "core/hd.h"
#include "core/normal_weight.h"
#include "core/sanitize.h"
#include "core/views.h"
#include "methods/svgf/edge_stopping.h"

namespace svgf {

// Strata along an axis of `pixels` (the last one partial).
SVGF_HD int strata_along(int pixels) {
  return (pixels + kGradientStratum - 1) / kGradientStratum;
}

// The filtered quantities of a stratum image, one plane each (T: float or const float).
template <class T>
struct GradientPlanes {
  T* delta = nullptr;       // current - previous luminance
  T* normalizer = nullptr;  // max(current, previous)
  T* weight = nullptr;      // 1: the stratum has data, 0: none
  GradientPlanes() = default;
  SVGF_HD GradientPlanes(T* d, T* n, T* w) : delta(d), normalizer(n), weight(w) {}
  template <class U, class = std::enable_if_t<std::is_same<const U, T>::value &&
                                              !std::is_same<U, T>::value>>
  SVGF_HD GradientPlanes(const GradientPlanes<U>& o)
      : delta(o.delta), normalizer(o.normalizer), weight(o.weight) {}
};

// Where a stratum's guides are read: the pixel of its sample, or its centre (clamped into a
// partial stratum) when it has none. Stored per stratum as the offset k = dy * 3 + dx in the
// stratum (0 .. 8, exact in a float plane).
struct StratumGuides {
  int width = 0;               // frame width, pixels
  int strata_width = 0;
  const float* offset = nullptr;
  SVGF_HD int pixel(int sx, int sy) const {
    return pixel_at(width, sx, sy, static_cast<int>(offset[sy * strata_width + sx]));
  }
  // The pixel at offset k of stratum (sx, sy) in a frame `width` pixels wide.
  SVGF_HD static int pixel_at(int width, int sx, int sy, int k) {
    return (sy * kGradientStratum + k / kGradientStratum) * width + sx * kGradientStratum +
           k % kGradientStratum;
  }
};

// The guides a stratum's a-trous taps compare: those at its guide pixel.
struct StratumGuide {
  EdgeSample edge;  // depth and normal (no luminance term)
  uint32_t mesh;
};
SVGF_HD StratumGuide stratum_guide(const GuideView& g, int p) {
  return StratumGuide{EdgeSample{g.depth[p], g.normal.load(p), 0.f}, g.mesh_id[p]};
}

// The same at a pixel of planes the sanitize stage may not have passed yet, as it would leave
// them (its guide rule, core/sanitize.h: nothing changes on planes it passed), with the depth's
// fwidth: what the fused gradient launch reads where the frame's sanitize stage is fused into
// the launch after it (methods/svgf/gradient_tile.h, pipeline.h).
struct SanitizedGuide {
  StratumGuide guide;
  float depth_fwidth;
};
SVGF_HD SanitizedGuide sanitized_stratum_guide(const GuideView& g, int p) {
  float depth = g.depth[p], dx = g.depth_dx[p], dy = g.depth_dy[p];
  Vec3 normal = g.normal.load(p), position;
  sanitize_guides(0u, depth, dx, dy, normal, position, /*has_position=*/false);
  return SanitizedGuide{StratumGuide{EdgeSample{depth, normal, 0.f}, g.mesh_id[p]},
                        depth_fwidth_of(dx, dy)};
}

// One stratum's filtered quantities, as a stage stores them in GradientPlanes.
struct StratumValue {
  float delta = 0.f, normalizer = 0.f, weight = 0.f;
};

// Stage 1, per stratum (sx, sy): its sample (the first masked pixel in raster order; the
// contract has one) -> delta, normalizer, weight and the guide offset.
struct GradientSamplesKernel {
  int width = 0, height = 0;  // frame, pixels
  GradientSampleView samples;
  GradientPlanes<float> out;
  int strata_width = 0;
  float* guide_offset = nullptr;

  // A stratum's sample and the offset of the pixel its guides are read at.
  struct Sample {
    StratumValue value;
    int guide = 0;
  };

  SVGF_HD void operator()(int sx, int sy) const { store(sy * strata_width + sx, sample(sx, sy)); }

  SVGF_HD Sample sample(int sx, int sy) const {
    const int x0 = sx * kGradientStratum, y0 = sy * kGradientStratum;
    const int xc = min_i(x0 + 1, width - 1), yc = min_i(y0 + 1, height - 1);
    // The first masked pixel in raster order: the nine masks are loaded before any is tested
    // (a partial stratum's missing pixels read the clamped centre's and count as unmasked), so
    // the GPU issues them together instead of one after the other's test; then the sample.
    int first = -1;
#if defined(__CUDA_ARCH__)
#pragma unroll
#endif
    for (int k = kGradientStratum * kGradientStratum - 1; k >= 0; --k) {
      const int x = x0 + k % kGradientStratum, y = y0 + k / kGradientStratum;
      const bool inside = x < width && y < height;
      const float mask = samples.mask[inside ? y * width + x : yc * width + xc];
      if (inside && masked(mask)) first = k;
    }
    return sample_at(first, x0, y0, (yc - y0) * kGradientStratum + (xc - x0));
  }

  // Whether a pixel holds the stratum's sample (NaN does not).
  SVGF_HD static bool masked(float mask) { return mask > 0.5f; }

  // The sample of the stratum whose pixels start at (x0, y0) and whose first masked pixel in
  // raster order is at offset `first` (-1: none; its guides are then read at offset `centre`).
  SVGF_HD Sample sample_at(int first, int x0, int y0, int centre) const {
    Sample m;
    m.guide = centre;
    if (first >= 0) {
      m.guide = first;
      const int i = (y0 + first / kGradientStratum) * width + x0 + first % kGradientStratum;
      const float previous = samples.previous[i], current = samples.current[i];
      if (radiance_ok(previous) && radiance_ok(current)) {  // NaN, Inf, negative: no data
        m.value.delta = current - previous;
        m.value.normalizer = max_f(current, previous);
        m.value.weight = 1.f;
      }
    }
    return m;
  }

  // Stratum s's outputs.
  SVGF_HD void store(int s, const Sample& m) const {
    out.delta[s] = m.value.delta;
    out.normalizer[s] = m.value.normalizer;
    out.weight[s] = m.value.weight;
    guide_offset[s] = static_cast<float>(m.guide);
  }

 private:
  SVGF_HD static int min_i(int a, int b) { return a < b ? a : b; }
};

// Stage 2: one a-trous step over the stratum image, taps `step` strata apart in raster order.
// A tap weighs exp(-|z_p - z_q| / (phi_depth * fwidth(z_p) * distance in pixels)) *
// max(0, n_p . n_q)^phi_normal (SVGF's edge_stopping_weight without its luminance term), 0 on
// another mesh or without data; the centre, with data, weighs 1. A stratum with no data in
// reach stays without.
struct GradientAtrousKernel {
  GuideView guides;  // this frame's, pixels
  StratumGuides at;
  int strata_height = 0;
  GradientPlanes<const float> in;
  GradientPlanes<float> out;
  int step = 1;
  float phi_depth = 1.f;
  float phi_normal = 128.f;
  float depth_gradient_floor = 1e-8f;

  // The input strata as planes over the stratum image and their guides read at the frame's
  // pixels (the stage's own input).
  struct PlanesInput {
    GradientPlanes<const float> in;
    StratumGuides at;
    GuideView guides;
    SVGF_HD float weight(int qx, int qy) const { return in.weight[index(qx, qy)]; }
    SVGF_HD float delta(int qx, int qy) const { return in.delta[index(qx, qy)]; }
    SVGF_HD float normalizer(int qx, int qy) const { return in.normalizer[index(qx, qy)]; }
    SVGF_HD uint32_t mesh(int qx, int qy) const { return guides.mesh_id[at.pixel(qx, qy)]; }
    SVGF_HD EdgeSample edge(int qx, int qy) const {
      return stratum_guide(guides, at.pixel(qx, qy)).edge;
    }
    SVGF_HD float depth_fwidth(int qx, int qy) const {
      return guides.depth_fwidth(at.pixel(qx, qy));
    }
    SVGF_HD int index(int qx, int qy) const { return qy * at.strata_width + qx; }
  };

  SVGF_HD void operator()(int sx, int sy) const {
    with_normal_power_of<ExactArith>(phi_normal, [&](const auto& power) {
      const StratumValue v = filtered(sx, sy, power, PlanesInput{in, at, guides});
      const int s = sy * at.strata_width + sx;
      out.delta[s] = v.delta;
      out.normalizer[s] = v.normalizer;
      out.weight[s] = v.weight;
    });
  }

  // Stratum (sx, sy) filtered: its 3x3 taps from `input` (anything with weight, delta,
  // normalizer, mesh, edge and depth_fwidth of a stratum: the planes above, or a tile of them
  // in a block's scratch, methods/svgf/gradient_tile.h), the same operations in the same order
  // either way.
  template <class Power, class Input>
  SVGF_HD StratumValue filtered(int sx, int sy, const Power& power, const Input& input) const {
    const EdgeSample c = input.edge(sx, sy);
    const uint32_t mesh = input.mesh(sx, sy);
    const float inv_phi_z = inv_depth_tolerance<ExactArith>(
        phi_depth, input.depth_fwidth(sx, sy), depth_gradient_floor);
    const InvTapDistances distances = inv_tap_distances();
    float weight_sum = 0.f, delta = 0.f, normalizer = 0.f;
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        const int qx = sx + dx * step, qy = sy + dy * step;
        if (qx < 0 || qy < 0 || qx >= at.strata_width || qy >= strata_height) continue;
        if (!(input.weight(qx, qy) > 0.f)) continue;
        float w = 1.f;
        if (dx != 0 || dy != 0) {
          if (input.mesh(qx, qy) != mesh) continue;
          w = edge_stopping_weight<ExactArith>(
              c, input.edge(qx, qy), distances.depth_scale(inv_phi_z, dx, dy), power, 0.f);
        }
        weight_sum = weight_sum + w;
        delta = delta + input.delta(qx, qy) * w;
        normalizer = normalizer + input.normalizer(qx, qy) * w;
      }
    }
    const bool any = weight_sum > 0.f;
    StratumValue v;
    v.delta = any ? delta / weight_sum : 0.f;
    v.normalizer = any ? normalizer / weight_sum : 0.f;
    v.weight = any ? 1.f : 0.f;
    return v;
  }

  // 1 / distance in pixels of the 3x3 taps' two classes, axis and diagonal (the squares of
  // +-step * 3 are the same within a class), once a stratum instead of an IEEE square root and
  // division a tap.
  struct InvTapDistances {
    float axis, diagonal;
    // A neighbour tap's depth scale: tap_depth_scale(inv_phi_z, dx, dy, step * 3)'s bits
    // (tests/svgf_gradient_test.cpp).
    SVGF_HD float depth_scale(float inv_phi_z, int dx, int dy) const {
      return inv_phi_z * (dx != 0 && dy != 0 ? diagonal : axis);
    }
  };
  SVGF_HD InvTapDistances inv_tap_distances() const {
    return {inv_tap_distance(1, 0, step * kGradientStratum),
            inv_tap_distance(1, 1, step * kGradientStratum)};
  }
};

// lambda of a filtered stratum: min(1, |delta| / normalizer), 0 without a normalizer.
SVGF_HD float gradient_lambda(float delta, float normalizer) {
  return normalizer > 0.f ? min_f(1.f, abs_f(delta) / normalizer) : 0.f;
}

// A stratum's own lambda, 0 without data (weight 0). A select, not a branch around the
// division: the CPU rows vectorize it, and the GPU issues the three loads together (a branch
// made each neighbour of the lambda stage a chain of two dependent loads). The planes hold 0
// where the weight is 0; the division's value there is dropped by the select either way.
SVGF_HD float stratum_lambda(float weight, float delta, float normalizer) {
  const float own = gradient_lambda(delta, normalizer);
  return weight > 0.f ? own : 0.f;
}

// The largest own lambda of the strata within `radius` of (sx, sy) in a strata_width x
// strata_height image, own(qx, qy) each stratum's (stratum_lambda). kRadius > 0: the radius,
// known at compile time (the GPU then issues the neighbours' loads together); 0: `radius`. The
// neighbours in one order (the centre, then dy outer, dx inner): max_f keeps a NaN only as its
// second operand.
template <int kRadius, class Own>
SVGF_HD float largest_lambda(int sx, int sy, int radius, int strata_width, int strata_height,
                             const Own& own) {
  const int r = kRadius > 0 ? kRadius : radius;
  float l = own(sx, sy);
#if defined(__CUDA_ARCH__)
#pragma unroll
#endif
  for (int dy = -r; dy <= r; ++dy)
#if defined(__CUDA_ARCH__)
#pragma unroll
#endif
    for (int dx = -r; dx <= r; ++dx) {
      const int qx = sx + dx, qy = sy + dy;
      if (qx < 0 || qy < 0 || qx >= strata_width || qy >= strata_height) continue;
      l = max_f(l, own(qx, qy));
    }
  return l;
}

// Stage 3, per stratum: the largest lambda of the strata within `radius` (a change seen by a
// neighbouring stratum's one sample also restarts this stratum's pixels: a moving shadow's edge
// crosses strata whose sample it missed). Max is exact in any order.
struct GradientLambdaKernel {
  int strata_width = 0;
  GradientPlanes<const float> in;
  float* lambda = nullptr;
  int strata_height = 0;
  int radius = 0;
  SVGF_HD float lambda_of(int s) const {
    return stratum_lambda(in.weight[s], in.delta[s], in.normalizer[s]);
  }
  SVGF_HD void operator()(int sx, int sy) const {
    const auto own = [&](int qx, int qy) { return lambda_of(qy * strata_width + qx); };
    // The default radius as a compile-time loop.
    lambda[sy * strata_width + sx] =
        radius == 1 ? largest_lambda<1>(sx, sy, radius, strata_width, strata_height, own)
                    : largest_lambda<0>(sx, sy, radius, strata_width, strata_height, own);
  }
};

// The history's blend factor under a gradient's lambda (the paper's Eq. 15), in the written
// order; at most 1.
SVGF_HD float antilag_alpha(float alpha, float lambda) {
  return min_f(1.f, (1.f - lambda) * alpha + lambda);
}

}  // namespace svgf

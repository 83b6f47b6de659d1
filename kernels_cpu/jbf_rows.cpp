#include "kernels_cpu/jbf_rows.h"

#include <algorithm>

#include "kernels_cpu/row_tools.h"

namespace svgf::cpu {
namespace {

// N taps of one tap row (offsets off[t], squared distances d2[t], B3 weights kw[t], in the
// kernel's order) for pixels x0..x1 whose N taps all lie inside the image; the body is the
// per-pixel kernel's. The centre and the sums stay in registers across the N taps (the centre's
// nine loads and the sums' loads and stores once per N taps); N = 1 serves the border pixels.
template <int N, bool kB3>
SVGF_TAP_LOOP void jbf_tap_group(const float* __restrict depth, const float* __restrict nx,
                                 const float* __restrict ny, const float* __restrict nz,
                                 const float* __restrict px, const float* __restrict py,
                                 const float* __restrict pz, const float* __restrict cr,
                                 const float* __restrict cg, const float* __restrict cb,
                                 float* __restrict sw, float* __restrict sr,
                                 float* __restrict sg, float* __restrict sb, int row,
                                 const int* offsets, int x0, int x1, const float* d2s,
                                 const float* kws, const JbfScales scales) {
  int off[N];
  float d2[N], kw[N];
  for (int t = 0; t < N; ++t) {
    off[t] = offsets[t];
    d2[t] = d2s[t];
    kw[t] = kws[t];
  }
  // With this many arrays GCC gives up proving them apart despite restrict; they are distinct.
#pragma GCC ivdep
  for (int x = x0; x < x1; ++x) {
    const int i = row + x;
    const JbfSample c{make_vec3(cr[i], cg[i], cb[i]), make_vec3(nx[i], ny[i], nz[i]),
                      make_vec3(px[i], py[i], pz[i])};
    float w_sum = sw[x], r_sum = sr[x], g_sum = sg[x], b_sum = sb[x];
#pragma GCC unroll 8
    for (int t = 0; t < N; ++t) {
      const int j = i + off[t];
      const JbfSample q{make_vec3(cr[j], cg[j], cb[j]), make_vec3(nx[j], ny[j], nz[j]),
                        make_vec3(px[j], py[j], pz[j])};
      float w = jbf_weight<RowExactArith>(c, q, d2[t], scales);
      if (kB3) w = w * kw[t];
      // A tap without a surface adds -0, the identity of IEEE addition (+0 would turn a -0 sum
      // into +0): no branch, so GCC vectorizes the loop.
      const bool surface = depth[j] > 0.f;
      w_sum = w_sum + (surface ? w : -0.f);
      r_sum = r_sum + (surface ? cr[j] * w : -0.f);
      g_sum = g_sum + (surface ? cg[j] * w : -0.f);
      b_sum = b_sum + (surface ? cb[j] * w : -0.f);
    }
    sw[x] = w_sum;
    sr[x] = r_sum;
    sg[x] = g_sum;
    sb[x] = b_sum;
  }
}

// The taps of one tap row, dx = dx0..dx1 (the centre skipped), for every pixel of the row:
// groups of kGroup taps for the pixels where the whole group lies inside, one tap at a time
// for the pixels at the border. Each pixel still adds its taps in dx order.
template <bool kB3>
void jbf_tap_row(const JbfPass<ExactArith>& k, int y, int dy, RowScratch& s) {
  constexpr int kGroup = 5;
  const GuideView& g = k.guides;
  const int w = g.width, row = y * w, row_offset = dy * k.step * w;
  const ColorSums sums(s, 0);
  for (int first = -k.radius; first <= k.radius; first += kGroup) {
    // This group's taps, the centre left out.
    int dxs[kGroup], offsets[kGroup];
    float d2[kGroup], kw[kGroup];
    int n = 0;
    const int last = std::min(k.radius, first + kGroup - 1);
    for (int dx = first; dx <= last; ++dx) {
      if (dx == 0 && dy == 0) continue;
      dxs[n] = dx;
      offsets[n] = row_offset + dx * k.step;
      d2[n] = static_cast<float>((dx * dx + dy * dy) * k.step * k.step);
      kw[n] = binomial_weight(5, dx) * binomial_weight(5, dy);
      ++n;
    }
    if (n == 0) continue;
    // A group function's N taps from tap t0 on, for the pixels from .. to.
    const auto taps = [&](auto group, int t0, int from, int to) {
      if (from < to)
        group(g.depth, g.normal.r, g.normal.g, g.normal.b, k.position.r, k.position.g,
              k.position.b, k.in.r, k.in.g, k.in.b, sums.weight, sums.r, sums.g, sums.b, row,
              offsets + t0, from, to, d2 + t0, kw + t0, k.scales);
    };
    // Pixels whose taps dxs[0] .. dxs[n-1] all lie inside: the group at once.
    const int in0 = std::min(w, std::max(0, -dxs[0] * k.step));
    const int in1 = std::max(in0, std::min(w, w - dxs[n - 1] * k.step));
    for (int t = 0; t < n; ++t) {  // left border: each tap where it lies inside
      const int off = dxs[t] * k.step;
      taps(jbf_tap_group<1, kB3>, t, std::max(0, -off), std::min(in0, w - off));
    }
    taps(n == kGroup ? jbf_tap_group<kGroup, kB3>
         : n == 4    ? jbf_tap_group<4, kB3>
         : n == 3    ? jbf_tap_group<3, kB3>
         : n == 2    ? jbf_tap_group<2, kB3>
                     : jbf_tap_group<1, kB3>,
         0, in0, in1);
    for (int t = 0; t < n; ++t) {  // right border
      const int off = dxs[t] * k.step;
      taps(jbf_tap_group<1, kB3>, t, std::max(in1, std::max(0, -off)), std::min(w, w - off));
    }
  }
}

void jbf_row(const JbfPass<ExactArith>& k, int y, RowScratch& s) {
  const GuideView& g = k.guides;
  const int w = g.width, h = g.height, row = y * w;
  const ColorSums sums(s, 0);
  sums.start(k.in, row, w, k.b3 ? binomial_weight(5, 0) * binomial_weight(5, 0) : 1.f);
  // The tap rows in the per-pixel kernel's order; one outside the image is skipped, as there.
  for (int dy = -k.radius; dy <= k.radius; ++dy) {
    const int yq = y + dy * k.step;
    if (yq < 0 || yq >= h) continue;
    if (k.b3)
      jbf_tap_row<true>(k, y, dy, s);
    else
      jbf_tap_row<false>(k, y, dy, s);
  }
  sums.finish(g.depth, k.in, k.out, row, w);
}

}  // namespace

void run_jbf_rows(const JbfPass<ExactArith>& kernel, int width, int height) {
  parallel_rows(height, [&](int y0, int y1) {
    RowScratch s(4, width);
    for (int y = y0; y < y1; ++y) jbf_row(kernel, y, s);
  });
}

}  // namespace svgf::cpu

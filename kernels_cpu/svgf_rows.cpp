#include "kernels_cpu/svgf_rows.h"

#include <algorithm>
#include <type_traits>
#include <vector>

#include <tbb/task_arena.h>

#include "kernels_cpu/row_tools.h"

namespace svgf::cpu {
namespace {

// Which pixels of a row a tap row runs over (atrous_tap_row; variance_taps the first two).
enum class TapColumns {
  kInterior,  // pixels whose taps in x all lie inside the image: no tests
  kBorder,    // pixels at either end of the row: a tap column outside is skipped, as the
              // per-pixel kernel skips it (loaded anyway, from the neighbouring row, and its
              // terms not added: a select, not a branch, so the loop stays vector code)
  kBorderClamped,  // the same where such a load would leave the image: loaded clamped into
                   // the row (scalar code: keep_scalar; the rows that reach the image's first
                   // or last pixel)
};

// Whether a border tap row's loads for pixels x0..x1 of the tap row starting at index
// row_start, reaching `reach` pixels to either side, all lie in a plane of `size` values:
// kBorder where they do, kBorderClamped where they do not.
inline bool border_loads_in_plane(long row_start, int x0, int x1, int reach, long size) {
  return row_start + x0 - reach >= 0 && row_start + x1 - 1 + reach < size;
}

// Column xq clamped into a row w wide (kBorderClamped's loads).
inline int clamped_column(int xq, int w) { return xq < 0 ? 0 : (xq >= w ? w - 1 : xq); }

// Called at the top of the kBorderClamped loops: an empty asm keeps GCC from vectorizing the
// loop (it changes no value). The kind runs a few pixels of a few rows an iteration, and
// vectorized, its clamped loads as emulated gathers for 12 normal-weight powers, it took GCC
// 48 s of the v4 variant's 98 for the a-trous alone (docs/sanitizers.md).
inline void keep_scalar() { asm volatile("" ::: "memory"); }

// The five taps dx = -2..2 of one a-trous tap row for pixels x0..x1 of a row w wide, in the
// per-pixel kernel's order, with the centre and the running sums held in registers across the
// five (half the loads and stores of a loop a tap). The border kinds add only to the pixels
// active0..active1 (the others' sums are stored back as they were loaded): a border is 2 to
// 16 pixels at the default 4 iterations, too few for one 16-lane vector, so the caller widens
// the loop to a vector's worth (as single-tap loops the border pixels were scalar code, 2% of
// a frame). kSharedNormals: tap t's normal term is shared[t][x] (AtrousNormalPairs), not
// computed from the tap's normal, which is then not read. lum_row: the luminances around the
// row, pixel x's at lum_row[x] (tap j's at lum_row[j - row]: a band's rows, run_atrous_rows).
template <class Power, bool kCentreRow, TapColumns kColumns = TapColumns::kInterior,
          bool kSharedNormals = false>
SVGF_TAP_LOOP void atrous_tap_row(const float* __restrict depth, const float* __restrict nx,
                                  const float* __restrict ny, const float* __restrict nz,
                                  const float* __restrict lum_row, const float* __restrict cr,
                                  const float* __restrict cg, const float* __restrict cb,
                                  const float* __restrict var_in,
                                  const float* __restrict inv_phi_z,
                                  const float* __restrict inv_phi_l, float* __restrict sw,
                                  float* __restrict sr, float* __restrict sg,
                                  float* __restrict sb, float* __restrict sv, int row,
                                  int row_offset, int step, int x0, int x1, int active0,
                                  int active1, int w, const float* inv_dist, const float* kw,
                                  const Power& power, const float* const* shared) {
  constexpr bool kTests = kColumns != TapColumns::kInterior;
  constexpr bool kClamp = kColumns == TapColumns::kBorderClamped;
  const float d[5] = {inv_dist[0], inv_dist[1], inv_dist[2], inv_dist[3], inv_dist[4]};
  const float k[5] = {kw[0], kw[1], kw[2], kw[3], kw[4]};
  const float* nw[5] = {};
  if constexpr (kSharedNormals)
    for (int t = 0; t < 5; ++t) nw[t] = shared[t];
  for (int x = x0; x < x1; ++x) {
    if constexpr (kClamp) keep_scalar();
    const int i = row + x;
    const EdgeSample c{depth[i], make_vec3(nx[i], ny[i], nz[i]), lum_row[x]};
    const float ipz = inv_phi_z[x], ipl = inv_phi_l[x];
    const bool active = !kTests || ((x >= active0) & (x < active1));
    float w_sum = sw[x], r_sum = sr[x], g_sum = sg[x], b_sum = sb[x], v_sum = sv[x];
#pragma GCC unroll 5
    for (int t = 0; t < 5; ++t) {
      if (kCentreRow && t == 2) continue;  // the centre tap is already in the sums
      const int xq = x + (t - 2) * step;
      const bool take = !kTests || (active & (xq >= 0) & (xq < w));
      const int j = kClamp ? row + row_offset + clamped_column(xq, w)
                           : i + row_offset + (t - 2) * step;
      float w_normal;
      if constexpr (kSharedNormals)
        w_normal = nw[t][x];
      else
        w_normal = edge_normal_weight<RowExactArith>(c.normal, make_vec3(nx[j], ny[j], nz[j]),
                                                     power);
      const EdgeSample q{depth[j], Vec3{}, lum_row[j - row]};  // its normal is in w_normal
      const float wt =
          edge_stopping_weight_given_normal<RowExactArith>(c, q, ipz * d[t], w_normal, ipl) *
          k[t];
      // Every load unconditional (GCC 12 vectorizes no loop with a load under a condition).
      const float w_with = w_sum + wt, r_with = r_sum + cr[j] * wt, g_with = g_sum + cg[j] * wt,
                  b_with = b_sum + cb[j] * wt, v_with = v_sum + var_in[j] * (wt * wt);
      w_sum = take ? w_with : w_sum;
      r_sum = take ? r_with : r_sum;
      g_sum = take ? g_with : g_sum;
      b_sum = take ? b_with : b_sum;
      v_sum = take ? v_with : v_sum;
    }
    sw[x] = w_sum;
    sr[x] = r_sum;
    sg[x] = g_sum;
    sb[x] = b_sum;
    sv[x] = v_sum;
  }
}

// N neighbouring taps of one tap row of the 7x7 spatial variance estimate, dx = first_dx ..
// first_dx + N - 1 (inv_dist[t] each), for pixels x0..x1 of a row w wide; the body is the
// per-pixel kernel's. The centre and the sums stay in registers across the N taps (as
// jbf_tap_group): N = 7 is a whole tap row at the default radius, N = 1 one tap (other radii).
// kInterior: every pixel's N taps lie inside the image. The border kinds skip a tap column
// outside, as the per-pixel kernel does (atrous_tap_row's kinds): the pixels within 3 of the
// image's left or right edge, in a loop of a vector's worth of pixels. A camera pan uncovers its young pixels at an edge, so most spans reach one: their 3
// edge pixels ran as 21 single-tap loops a tap row and the rest of the vector as the tap row's
// scalar tail, 25% of the stage (docs/benchmarks.md).
template <int N, class Power, TapColumns kColumns = TapColumns::kInterior>
SVGF_TAP_LOOP void variance_taps(const float* __restrict depth, const float* __restrict nx,
                                 const float* __restrict ny, const float* __restrict nz,
                                 const float* __restrict lum, const float* __restrict cr,
                                 const float* __restrict cg, const float* __restrict cb,
                                 const float* __restrict m1_in, const float* __restrict m2_in,
                                 const float* __restrict inv_phi_z, float inv_phi_l,
                                 float* __restrict sw, float* __restrict sr,
                                 float* __restrict sg, float* __restrict sb,
                                 float* __restrict sm1, float* __restrict sm2, int row,
                                 int row_offset, int first_dx, int x0, int x1, int w,
                                 const float* inv_dist, const Power& power) {
  constexpr bool kTests = kColumns != TapColumns::kInterior;
  constexpr bool kClamp = kColumns == TapColumns::kBorderClamped;
  float d[N];
  for (int t = 0; t < N; ++t) d[t] = inv_dist[t];
  for (int x = x0; x < x1; ++x) {
    if constexpr (kClamp) keep_scalar();
    const int i = row + x;
    const EdgeSample c{depth[i], make_vec3(nx[i], ny[i], nz[i]), lum[i]};
    const float ipz = inv_phi_z[x];
    float w_sum = sw[x], r_sum = sr[x], g_sum = sg[x], b_sum = sb[x], m1_sum = sm1[x],
          m2_sum = sm2[x];
#pragma GCC unroll 7
    for (int t = 0; t < N; ++t) {
      const int xq = x + first_dx + t;
      const bool take = !kTests || ((xq >= 0) & (xq < w));
      const int j = kClamp ? row + row_offset + clamped_column(xq, w)
                           : i + row_offset + first_dx + t;
      const EdgeSample q{depth[j], make_vec3(nx[j], ny[j], nz[j]), lum[j]};
      const float wt = edge_stopping_weight<RowExactArith>(c, q, ipz * d[t], power, inv_phi_l);
      // Every load unconditional, the terms added by a select (as atrous_tap_row).
      const float w_with = w_sum + wt, r_with = r_sum + cr[j] * wt, g_with = g_sum + cg[j] * wt,
                  b_with = b_sum + cb[j] * wt, m1_with = m1_sum + m1_in[j] * wt,
                  m2_with = m2_sum + m2_in[j] * wt;
      w_sum = take ? w_with : w_sum;
      r_sum = take ? r_with : r_sum;
      g_sum = take ? g_with : g_sum;
      b_sum = take ? b_with : b_sum;
      m1_sum = take ? m1_with : m1_sum;
      m2_sum = take ? m2_with : m2_sum;
    }
    sw[x] = w_sum;
    sr[x] = r_sum;
    sg[x] = g_sum;
    sb[x] = b_sum;
    sm1[x] = m1_sum;
    sm2[x] = m2_sum;
  }
}

// --- a-trous ---------------------------------------------------------------------------------

// A row's centre terms, the per-pixel kernel's first lines: 1 / phi_l from the prefiltered
// variance (in place), 1 / phi_z, and the centre's own term in the sums. A function of its own
// with restrict arguments, like the tap loops, so that GCC vectorizes its divisions and square
// roots (inlined into the row they stayed scalar: 2 divisions and a root a pixel).
SVGF_TAP_LOOP void atrous_centre_terms(const float* __restrict depth_dx,
                                       const float* __restrict depth_dy,
                                       const float* __restrict cr, const float* __restrict cg,
                                       const float* __restrict cb, const float* __restrict var_in,
                                       float* __restrict inv_phi_l, float* __restrict inv_phi_z,
                                       float* __restrict sw, float* __restrict sr,
                                       float* __restrict sg, float* __restrict sb,
                                       float* __restrict sv, int row, int w, SvgfParams p) {
  const float center_k = b3_weight(0) * b3_weight(0);
  for (int x = 0; x < w; ++x) {
    const int i = row + x;
    inv_phi_l[x] = atrous_inv_phi_luminance(p, inv_phi_l[x]);
    inv_phi_z[x] = inv_depth_tolerance(p.phi_depth, depth_fwidth_of(depth_dx[i], depth_dy[i]),
                                       p.depth_gradient_floor);
    sw[x] = center_k;
    sr[x] = cr[i] * center_k;
    sg[x] = cg[i] * center_k;
    sb[x] = cb[i] * center_k;
    sv[x] = var_in[i] * (center_k * center_k);
  }
}

// A row's results, the per-pixel kernel's last lines: the sums over the weight (the variance
// over its square) on surfaces, the input passed through elsewhere. Restrict, likewise (4
// divisions a pixel). The image planes come offset to the row, so every array is indexed by x:
// indexed by row + x against the sums' x, GCC 12 could not clear the loads of the conditional
// branch against the stores and left the loop scalar.
SVGF_TAP_LOOP void atrous_normalize(const float* __restrict depth, const float* __restrict in_r,
                                    const float* __restrict in_g, const float* __restrict in_b,
                                    const float* __restrict var_in, const float* __restrict sw,
                                    const float* __restrict sr, const float* __restrict sg,
                                    const float* __restrict sb, const float* __restrict sv,
                                    float* __restrict out_r, float* __restrict out_g,
                                    float* __restrict out_b, float* __restrict out_v, int w) {
  for (int x = 0; x < w; ++x) {
    const bool surface = has_surface(depth[x]);
    out_r[x] = surface ? sr[x] / sw[x] : in_r[x];
    out_g[x] = surface ? sg[x] / sw[x] : in_g[x];
    out_b[x] = surface ? sb[x] / sw[x] : in_b[x];
    out_v[x] = surface ? sv[x] / (sw[x] * sw[x]) : var_in[x];
  }
}

// n results remodulated into the output planes o*: RemodulateSink's remodulated(), the same
// function, by albedo a* and emission e* (none without kEmission: zero, as load_or_zero gives).
// Restrict, like the tap loops (vectorized).
template <bool kEmission>
SVGF_TAP_LOOP void remodulate_span(const float* __restrict r, const float* __restrict g,
                                   const float* __restrict b, const float* __restrict ar,
                                   const float* __restrict ag, const float* __restrict ab,
                                   const float* __restrict er, const float* __restrict eg,
                                   const float* __restrict eb, float* __restrict o_r,
                                   float* __restrict o_g, float* __restrict o_b, int n,
                                   float albedo_epsilon) {
  for (int x = 0; x < n; ++x) {
    const Vec3 emission = kEmission ? make_vec3(er[x], eg[x], eb[x]) : Vec3();
    const Vec3 o = remodulated(make_vec3(r[x], g[x], b[x]), make_vec3(ar[x], ag[x], ab[x]),
                               emission, albedo_epsilon);
    o_r[x] = o.x;
    o_g[x] = o.y;
    o_b[x] = o.z;
  }
}

// Row `row` (its first index) of results r, g, b into the sink, as RemodulateSink::store.
void remodulate_row(const RemodulateSink& sink, const float* r, const float* g, const float* b,
                    int row, int w) {
  const ConstRgbView& a = sink.albedo;
  const ConstRgbView& e = sink.emission;
  const RgbView& o = sink.output;
  if (e.r)
    remodulate_span<true>(r, g, b, a.r + row, a.g + row, a.b + row, e.r + row, e.g + row,
                          e.b + row, o.r + row, o.g + row, o.b + row, w, sink.albedo_epsilon);
  else
    remodulate_span<false>(r, g, b, a.r + row, a.g + row, a.b + row, nullptr, nullptr, nullptr,
                           o.r + row, o.g + row, o.b + row, w, sink.albedo_epsilon);
}

// The normal terms of n pixels (normals n*) with the pixels at the same index of q* (their
// partners, offset by the caller): out[x] = edge_normal_weight(n[x], q[x]). Restrict, like the
// tap loops (vectorized).
template <class Power>
SVGF_TAP_LOOP void normal_weight_span(const float* __restrict nx, const float* __restrict ny,
                                      const float* __restrict nz, const float* __restrict qx,
                                      const float* __restrict qy, const float* __restrict qz,
                                      float* __restrict out, int n, const Power& power) {
  for (int x = 0; x < n; ++x)
    out[x] = edge_normal_weight<RowExactArith>(make_vec3(nx[x], ny[x], nz[x]),
                                               make_vec3(qx[x], qy[x], qz[x]), power);
}

// The normal terms of the pairs a row starts (AtrousNormalPairs), pairs kFirstDy..2 rows of
// steps below (0: the row's own pairs dx = 1, 2 too) for pixels x0..x1, whose partners all lie
// in the image: one pass loading the row's normals once for its 12 pairs, not once a pair
// (normal_weight_span: the edges' remainders). n: the row's normal planes, offset to it;
// below[r]: row r + 1 steps below's; out[pair]: the pair's terms (AtrousNormalPairs::started).
// Where pair (dy, dx) of the 12 a row starts lies among them: dy = 0 with dx = 1, 2 first,
// then dy = 1 and 2 with dx = -2..2.
constexpr int atrous_pair_index(int dy, int dx) {
  return dy == 0 ? dx - 1 : 2 + (dy - 1) * 5 + (dx + 2);
}

struct NormalPairPlanes {
  const float* n[3];
  const float* below[2][3];
  float* out[12];
};
template <int kFirstDy, class Power>
SVGF_TAP_LOOP void normal_pairs_span(const NormalPairPlanes& planes, int step, int x0, int x1,
                                     const Power& power) {
  const float* __restrict nx = planes.n[0];
  const float* __restrict ny = planes.n[1];
  const float* __restrict nz = planes.n[2];
  const float* below[2][3];
  float* out[12];
  for (int r = 0; r < 2; ++r)
    for (int c = 0; c < 3; ++c) below[r][c] = planes.below[r][c];
  for (int k = 0; k < 12; ++k) out[k] = planes.out[k];
#pragma GCC ivdep
  for (int x = x0; x < x1; ++x) {
    const Vec3 c = make_vec3(nx[x], ny[x], nz[x]);
    if constexpr (kFirstDy == 0) {
#pragma GCC unroll 2
      for (int dx = 1; dx <= 2; ++dx) {
        const int q = x + dx * step;
        out[atrous_pair_index(0, dx)][x] =
            edge_normal_weight<RowExactArith>(c, make_vec3(nx[q], ny[q], nz[q]), power);
      }
    }
#pragma GCC unroll 2
    for (int dy = kFirstDy < 1 ? 1 : kFirstDy; dy <= 2; ++dy) {
      const float* const* b = below[dy - 1];
#pragma GCC unroll 5
      for (int dx = -2; dx <= 2; ++dx) {
        const int q = x + dx * step;
        out[atrous_pair_index(dy, dx)][x] =
            edge_normal_weight<RowExactArith>(c, make_vec3(b[0][q], b[1][q], b[2][q]), power);
      }
    }
  }
}

// The a-trous normal terms computed once a pair of pixels. A tap's normal term is symmetric to
// the bit (edge_normal_weight), and a pixel p's tap (dy, dx) has a pixel q whose tap (-dy, -dx)
// is p: a row computes the terms of the pairs it starts (its taps below it, dy = 1, 2, and
// those to its right, dy = 0 and dx = 1, 2: 12 of the 24) and reads the others from the rows
// above that started them. The rows of one step run as a chain y, y + step, y + 2 step ..., so
// a row's terms are read one and two rows of the chain later: three rows of terms are kept
// (slots by y / step). The interior pixels read every tap's term from here (7 loads a tap
// instead of 9, none of the term's 14 float operations: 370 -> 282 instructions for a tap row of
// 16 pixels with x86-64-v4), each term computed once for two taps; the border pixels compute
// theirs in the tap row as before.
class AtrousNormalPairs {
 public:
  AtrousNormalPairs(const GuideView& g, int step)
      : g_(g), step_(step), pad_(2 * step), stride_(g.width + 4 * step),
        values_(static_cast<size_t>(kSlots) * kPairs * stride_) {}

  // The terms of the pairs row y starts, those with the rows dy = first_dy..2 steps below
  // (first_dy = 0: its own row too), for every pixel whose partner lies in the image.
  template <class Power>
  void compute(int y, int first_dy, const Power& power) {
    const int w = g_.width, h = g_.height;
    // Where every pair's partner lies in the image (all of the row's rows below present): one
    // pass for all; the rest pair by pair.
    const int inner0 = std::min(w, 2 * step_), inner1 = std::max(inner0, w - 2 * step_);
    const bool fused = y + 2 * step_ < h && inner0 < inner1;
    if (fused) {
      NormalPairPlanes planes{};
      const size_t at = static_cast<size_t>(y) * w;
      planes.n[0] = g_.normal.r + at;
      planes.n[1] = g_.normal.g + at;
      planes.n[2] = g_.normal.b + at;
      for (int dy = 1; dy <= 2; ++dy) {
        const size_t below = static_cast<size_t>(y + dy * step_) * w;
        planes.below[dy - 1][0] = g_.normal.r + below;
        planes.below[dy - 1][1] = g_.normal.g + below;
        planes.below[dy - 1][2] = g_.normal.b + below;
      }
      for (int dy = 0; dy <= 2; ++dy)
        for (int dx = dy == 0 ? 1 : -2; dx <= 2; ++dx)
          planes.out[atrous_pair_index(dy, dx)] = started(y, dy, dx);
      if (first_dy == 0) normal_pairs_span<0>(planes, step_, inner0, inner1, power);
      else if (first_dy == 1) normal_pairs_span<1>(planes, step_, inner0, inner1, power);
      else normal_pairs_span<2>(planes, step_, inner0, inner1, power);
    }
    for (int dy = first_dy; dy <= 2; ++dy) {
      const int yq = y + dy * step_;
      if (yq >= h) break;
      for (int dx = dy == 0 ? 1 : -2; dx <= 2; ++dx) {
        const int shift = dx * step_;
        const int x0 = std::max(0, -shift), x1 = std::min(w, w - shift);
        if (x0 >= x1) continue;
        if (fused) {  // the remainders at either end
          span(y, yq, dy, dx, x0, inner0, power);
          span(y, yq, dy, dx, inner1, x1, power);
          continue;
        }
        span(y, yq, dy, dx, x0, x1, power);
      }
    }
  }

  // Pair (dy, dx)'s terms of row y (its partner row yq) for pixels x0..x1.
  template <class Power>
  void span(int y, int yq, int dy, int dx, int x0, int x1, const Power& power) {
    if (x0 >= x1) return;
    const int w = g_.width, shift = dx * step_;
    const size_t at = static_cast<size_t>(y) * w + x0;
    const size_t q = static_cast<size_t>(yq) * w + x0 + shift;
    normal_weight_span(g_.normal.r + at, g_.normal.g + at, g_.normal.b + at, g_.normal.r + q,
                       g_.normal.g + q, g_.normal.b + q, started(y, dy, dx) + x0, x1 - x0,
                       power);
  }

  // What pixel x of row y reads at [x] for its tap (dy, dx) (not the centre): the term its pair
  // started, here or in the row dy steps above.
  const float* tap(int y, int dy, int dx) {
    if (dy > 0 || (dy == 0 && dx > 0)) return started(y, dy, dx);
    return started(y + dy * step_, -dy, -dx) + dx * step_;
  }

 private:
  static constexpr int kSlots = 3;
  static constexpr int kPairs = 12;  // dy = 0: dx = 1, 2; dy = 1, 2: dx = -2..2
  // The terms of the pairs row y starts with its tap (dy, dx), indexed by x (padded by two steps
  // on either side, so that tap()'s offset stays inside the buffer).
  float* started(int y, int dy, int dx) {
    const int slot = (y / step_) % kSlots;
    return values_.data() +
           (static_cast<size_t>(slot) * kPairs + atrous_pair_index(dy, dx)) * stride_ + pad_;
  }

  GuideView g_;
  int step_, pad_;
  size_t stride_;
  std::vector<float> values_;
};

// Row scratch of an a-trous row: 7 for its terms and sums, 4 for a result that is not stored in
// the output signal (AtrousRowOutputs::remodulate).
constexpr int kAtrousScratch = 11;

template <class Power>
void atrous_row(const AtrousKernel& k, const AtrousRowOutputs& outputs,
                const float* __restrict lum_row, int y, RowScratch& s, const Power& power,
                AtrousNormalPairs& pairs) {
  const GuideView& g = k.guides;
  const SvgfParams& p = k.params;
  const int w = g.width, h = g.height, row = y * w;
  const float* __restrict var_in = k.in.variance;
  float* __restrict inv_phi_l = s[0];  // holds the prefiltered variance first
  float* __restrict inv_phi_z = s[1];
  float* __restrict sw = s[2];
  float* __restrict sr = s[3];
  float* __restrict sg = s[4];
  float* __restrict sb = s[5];
  float* __restrict sv = s[6];

  // Centre terms: prefiltered variance (into inv_phi_l), reciprocal tolerances, the centre's own contribution.
  if (y > 0 && y < h - 1 && w > 2) {
    inv_phi_l[0] = prefiltered_variance(g, var_in, 0, y);
    for (int x = 1; x < w - 1; ++x) inv_phi_l[x] = prefiltered_variance_interior(var_in, w, row + x);
    inv_phi_l[w - 1] = prefiltered_variance(g, var_in, w - 1, y);
  } else {
    for (int x = 0; x < w; ++x) inv_phi_l[x] = prefiltered_variance(g, var_in, x, y);
  }
  atrous_centre_terms(g.depth_dx, g.depth_dy, k.in.color.r, k.in.color.g, k.in.color.b, var_in,
                      inv_phi_l, inv_phi_z, sw, sr, sg, sb, sv, row, w, p);
  // Taps in the per-pixel kernel's order; a tap row or column outside the image is skipped,
  // exactly as the per-pixel kernel skips it.
  const float* __restrict depth = g.depth;
  const float* __restrict nx = g.normal.r;
  const float* __restrict ny = g.normal.g;
  const float* __restrict nz = g.normal.b;
  const float* __restrict cr = k.in.color.r;
  const float* __restrict cg = k.in.color.g;
  const float* __restrict cb = k.in.color.b;
  // Pixels whose 5 taps in x all lie inside (inner0..inner1) may take a tap row's five without
  // tests; the others, with a test a tap. The tested loops run whole vectors at either end of
  // the row (kVectorLanes pixels, or 2 steps), and the untested one the whole vectors between
  // them: no scalar tail (at 720p the first iterations' 12 and 8 pixels a tap row), as the
  // tested loops' extra pixels pass their tests. Each pixel adds dx = -2..2 in order.
  const int inner0 = std::min(w, 2 * k.step), inner1 = std::max(inner0, w - 2 * k.step);
  const int left = std::min(w, std::max(inner0, kVectorLanes));
  const int right = inner1 > left ? left + (inner1 - left) / kVectorLanes * kVectorLanes
                                  : std::max(left, inner1);
  for (int dy = -2; dy <= 2; ++dy) {
    const int yq = y + dy * k.step;
    if (yq < 0 || yq >= h) continue;
    float kw[5], inv_dist[5];
    for (int dx = -2; dx <= 2; ++dx) {
      kw[dx + 2] = b3_weight(dx < 0 ? -dx : dx) * b3_weight(dy < 0 ? -dy : dy);
      inv_dist[dx + 2] = inv_tap_distance(dx, dy, k.step);
    }
    const int row_offset = (yq - y) * w;
    // The interior, then the border pixels on the left and on the right, each border's loop
    // widened to 16 pixels where the row has them and its loads stay in the image.
    const auto tap_rows = [&](auto centre_row) {
      constexpr bool kCentre = decltype(centre_row)::value;
      const float* shared[5] = {};
      const auto call = [&](auto columns, int x0, int x1, int active0, int active1) {
        constexpr TapColumns kColumns = decltype(columns)::value;
        atrous_tap_row<Power, kCentre, kColumns, kColumns == TapColumns::kInterior>(
            depth, nx, ny, nz, lum_row, cr, cg, cb, var_in, inv_phi_z, inv_phi_l, sw, sr, sg, sb,
            sv, row, row_offset, k.step, x0, x1, active0, active1, w, inv_dist, kw, power,
            shared);
      };
      using Interior = std::integral_constant<TapColumns, TapColumns::kInterior>;
      using Border = std::integral_constant<TapColumns, TapColumns::kBorder>;
      using Clamped = std::integral_constant<TapColumns, TapColumns::kBorderClamped>;
      if (left < right) {
        for (int dx = -2; dx <= 2; ++dx)
          if (dy != 0 || dx != 0) shared[dx + 2] = pairs.tap(y, dy, dx);
        call(Interior{}, left, right, left, right);
      }
      const auto border = [&](int active0, int active1, int x0, int x1) {
        if (active0 >= active1) return;
        if (border_loads_in_plane(static_cast<long>(row) + row_offset, x0, x1, 2 * k.step,
                                  static_cast<long>(w) * h))
          call(Border{}, x0, x1, active0, active1);
        else
          call(Clamped{}, active0, active1, active0, active1);
      };
      border(0, left, 0, left);
      border(right, w, std::max(0, std::min(right, w - kVectorLanes)), w);
    };
    if (dy == 0)
      tap_rows(std::true_type{});
    else
      tap_rows(std::false_type{});
  }
  // The result: into the output signal, or into scratch for the remodulation (its variance
  // then goes nowhere, as RemodulateSink stores the color alone); the feedback tap's color
  // copied into the history.
  const bool remodulate = outputs.remodulate != nullptr;
  float* out_r = remodulate ? s[7] : k.out.color.r + row;
  float* out_g = remodulate ? s[8] : k.out.color.g + row;
  float* out_b = remodulate ? s[9] : k.out.color.b + row;
  float* out_v = remodulate ? s[10] : k.out.variance + row;
  atrous_normalize(g.depth + row, k.in.color.r + row, k.in.color.g + row, k.in.color.b + row,
                   var_in + row, sw, sr, sg, sb, sv, out_r, out_g, out_b, out_v, w);
  if (const RgbView& history = outputs.color_history; history.r) {
    std::copy(out_r, out_r + w, history.r + row);
    std::copy(out_g, out_g + w, history.g + row);
    std::copy(out_b, out_b + w, history.b + row);
  }
  if (remodulate) remodulate_row(*outputs.remodulate, out_r, out_g, out_b, row, w);
}

// --- spatial variance estimate -----------------------------------------------------------------

// Every pixel of a row as the steady state passes it on: the accumulated color, and the
// temporal variance (a division a pixel). Restrict, with the planes offset to the row, like the
// a-trous's loops (vectorized; it was scalar). The estimate overwrites the young pixels.
SVGF_TAP_LOOP void variance_pass_through(const float* __restrict cr, const float* __restrict cg,
                                         const float* __restrict cb,
                                         const float* __restrict var_in,
                                         const float* __restrict history, float* __restrict out_r,
                                         float* __restrict out_g, float* __restrict out_b,
                                         float* __restrict out_v, int w, SvgfParams p) {
  for (int x = 0; x < w; ++x) {
    out_r[x] = cr[x];
    out_g[x] = cg[x];
    out_b[x] = cb[x];
    out_v[x] = temporal_variance(p, var_in[x], history[x]);
  }
}

// The estimate's centre terms for the pixels of a span: 1 / phi_z, and the sums at 0. Offset to
// the span's first pixel, likewise.
SVGF_TAP_LOOP void variance_span_start(const float* __restrict depth_dx,
                                       const float* __restrict depth_dy,
                                       float* __restrict inv_phi_z, float* __restrict sw,
                                       float* __restrict sr, float* __restrict sg,
                                       float* __restrict sb, float* __restrict sm1,
                                       float* __restrict sm2, int n, SvgfParams p) {
  for (int x = 0; x < n; ++x) {
    inv_phi_z[x] = inv_depth_tolerance(p.spatial_variance_phi_depth,
                                       depth_fwidth_of(depth_dx[x], depth_dy[x]),
                                       p.depth_gradient_floor);
    sw[x] = sr[x] = sg[x] = sb[x] = sm1[x] = sm2[x] = 0.f;
  }
}

// The estimate's results for the pixels of a span, the per-pixel kernel's last lines, where
// they are young and on a surface; the others keep what the pass-through wrote (a select, so
// the loop vectorizes: 5 divisions a pixel). Offset to the span's first pixel, likewise.
SVGF_TAP_LOOP void variance_span_finish(const float* __restrict depth,
                                        const float* __restrict history,
                                        const float* __restrict sw, const float* __restrict sr,
                                        const float* __restrict sg, const float* __restrict sb,
                                        const float* __restrict sm1,
                                        const float* __restrict sm2, float* __restrict out_r,
                                        float* __restrict out_g, float* __restrict out_b,
                                        float* __restrict out_v, int n, SvgfParams p) {
  const float young = static_cast<float>(p.spatial_variance_history);
  for (int x = 0; x < n; ++x) {
    const float hist = history[x];
    const bool estimated = (hist < young) & has_surface(depth[x]);
    const float ws = max_f(sw[x], 1e-6f);
    const float m1 = sm1[x] / ws, m2 = sm2[x] / ws;
    out_r[x] = estimated ? sr[x] / ws : out_r[x];
    out_g[x] = estimated ? sg[x] / ws : out_g[x];
    out_b[x] = estimated ? sb[x] / ws : out_b[x];
    out_v[x] = estimated ? spatial_variance(p, m1, m2, hist) : out_v[x];
  }
}

// The 7x7 estimate for the pixels lo..hi of row y (the centre terms and the taps; the results
// where the pixel is young and on a surface).
template <class Power>
void variance_span(const VarianceKernel& k, const float* __restrict lum, int y, int lo, int hi,
                   RowScratch& s, const Power& power) {
  const GuideView& g = k.guides;
  const SvgfParams& p = k.params;
  const int w = g.width, h = g.height, row = y * w;
  float* __restrict inv_phi_z = s[0];
  float* __restrict sw = s[2];
  float* __restrict sr = s[3];
  float* __restrict sg = s[4];
  float* __restrict sb = s[5];
  float* __restrict sm1 = s[6];
  float* __restrict sm2 = s[1];
  variance_span_start(g.depth_dx + row + lo, g.depth_dy + row + lo, inv_phi_z + lo, sw + lo,
                      sr + lo, sg + lo, sb + lo, sm1 + lo, sm2 + lo, hi - lo, p);
  const float inv_phi_l = 1.f / p.phi_color;
  const int r = p.spatial_variance_radius;
  const ConstRgbView c = k.accumulated.color;
  constexpr int kRowRadius = 3;
  if (r != kRowRadius) {
    // Another radius: one tap at a time, over the pixels that have it inside the image; each
    // pixel still adds dx = -r..r in order.
    for (int dy = -r; dy <= r; ++dy) {
      const int yq = y + dy;
      if (yq < 0 || yq >= h) continue;
      for (int dx = -r; dx <= r; ++dx) {
        const int x0 = std::max(lo, -dx), x1 = std::min(hi, w - dx);
        const float dist = inv_tap_distance(dx, dy, 1);
        if (x0 < x1)
          variance_taps<1>(g.depth, g.normal.r, g.normal.g, g.normal.b, lum, c.r, c.g, c.b,
                           k.moment1, k.moment2, inv_phi_z, inv_phi_l, sw, sr, sg, sb, sm1, sm2,
                           row, dy * w, dx, x0, x1, w, &dist, power);
      }
    }
  } else {
    // The default radius: a tap row's seven taps at once. The pixels whose seven taps in x lie
    // inside run without tests; the span's pixels within 3 of the image's left or right edge
    // run with them, in a vector's worth of pixels (the span is whole vectors where the row has
    // room), so that neither part has a scalar tail.
    const int inner0 = std::min(hi, std::max(lo, kRowRadius));
    const int inner1 = std::max(inner0, std::min(hi, w - kRowRadius));
    const int left_end = inner0 > lo ? std::min(hi, std::max(inner0, lo + kVectorLanes)) : lo;
    const int right_begin =
        inner1 < hi ? std::max(left_end, std::min(inner1, hi - kVectorLanes)) : hi;
    for (int dy = -r; dy <= r; ++dy) {
      const int yq = y + dy;
      if (yq < 0 || yq >= h) continue;
      float inv_dist[2 * kRowRadius + 1];
      for (int dx = -r; dx <= r; ++dx) inv_dist[dx + r] = inv_tap_distance(dx, dy, 1);
      const auto call = [&](auto columns, int x0, int x1) {
        if (x0 < x1)
          variance_taps<2 * kRowRadius + 1, Power, decltype(columns)::value>(
              g.depth, g.normal.r, g.normal.g, g.normal.b, lum, c.r, c.g, c.b, k.moment1,
              k.moment2, inv_phi_z, inv_phi_l, sw, sr, sg, sb, sm1, sm2, row, dy * w,
              -kRowRadius, x0, x1, w, inv_dist, power);
      };
      using Interior = std::integral_constant<TapColumns, TapColumns::kInterior>;
      using Border = std::integral_constant<TapColumns, TapColumns::kBorder>;
      using Clamped = std::integral_constant<TapColumns, TapColumns::kBorderClamped>;
      call(Interior{}, left_end, right_begin);
      // A border's skipped taps are loaded from the neighbouring row, or clamped into the row
      // where that would leave the plane (the first row's left edge, the last row's right).
      const auto border = [&](int x0, int x1) {
        if (x0 >= x1) return;
        if (border_loads_in_plane(static_cast<long>(yq) * w, x0, x1, kRowRadius,
                                  static_cast<long>(w) * h))
          call(Border{}, x0, x1);
        else
          call(Clamped{}, x0, x1);
      };
      border(lo, left_end);
      border(right_begin, hi);
    }
  }
  const int at = row + lo;
  variance_span_finish(g.depth + at, k.history + at, sw + lo, sr + lo, sg + lo, sb + lo,
                       sm1 + lo, sm2 + lo, k.out.color.r + at, k.out.color.g + at,
                       k.out.color.b + at, k.out.variance + at, hi - lo, p);
}

template <class Power>
void variance_row(const VarianceKernel& k, const float* __restrict lum, int y, RowScratch& s,
                  const Power& power) {
  const GuideView& g = k.guides;
  const int w = g.width, row = y * w;
  const float young = static_cast<float>(k.params.spatial_variance_history);
  variance_pass_through(k.accumulated.color.r + row, k.accumulated.color.g + row,
                        k.accumulated.color.b + row, k.accumulated.variance + row,
                        k.history + row, k.out.color.r + row, k.out.color.g + row,
                        k.out.color.b + row, k.out.variance + row, w, k.params);
  if (k.color_history.r) {  // the color history's one slot (methods/svgf/variance.h)
    std::copy_n(k.accumulated.color.r + row, w, k.color_history.r + row);
    std::copy_n(k.accumulated.color.g + row, w, k.color_history.g + row);
    std::copy_n(k.accumulated.color.b + row, w, k.color_history.b + row);
  }
  // The 7x7 work runs only over runs of pixels that need it (young history on a surface): after
  // a disocclusion, or at the edge a camera pan uncovers, they are short. Runs closer than
  // kGap pixels share one span (fewer, longer vector loops), and a span is widened to whole
  // vectors (kVectorLanes) where the row has room: 16% of the tap loop's time was its scalar
  // tail before, 8% after, the stage about as fast on camera-pan (docs/benchmarks.md). The
  // extra pixels keep the pass-through's values (variance_span_finish selects the young ones).
  constexpr int kGap = 16;
  const auto span = [&](int from, int to) {
    const int n = (to - from + kVectorLanes - 1) / kVectorLanes * kVectorLanes;
    to = std::min(w, from + n);
    from = std::max(0, to - n);
    variance_span(k, lum, y, from, to, s, power);
  };
  int lo = -1, hi = -1;
  for (int x = 0; x <= w; ++x) {
    const bool needs = x < w && k.history[row + x] < young && g.is_surface(row + x);
    if (needs) {
      if (lo >= 0 && x - hi >= kGap) {
        span(lo, hi);
        lo = -1;
      }
      if (lo < 0) lo = x;
      hi = x + 1;
    }
  }
  if (lo >= 0) span(lo, hi);
}

// Luminances of n pixels (restrict: vectorized).
SVGF_TAP_LOOP void luminance_span(const float* __restrict r, const float* __restrict g,
                                  const float* __restrict b, float* __restrict lum, int n) {
  for (int i = 0; i < n; ++i) lum[i] = luminance(make_vec3(r[i], g[i], b[i]));
}

// Luminance of every pixel of `color`, once per stage instead of once per tap.
UninitializedPlane<float> luminance_plane(ConstRgbView color, int w, int h) {
  UninitializedPlane<float> lum(static_cast<size_t>(w) * h);
  parallel_rows(h, [&](int y0, int y1) {
    const int i = y0 * w;
    luminance_span(color.r + i, color.g + i, color.b + i, lum.data() + i, (y1 - y0) * w);
  });
  return lum;
}

// The luminances an a-trous band reads: of rows first..last - 1 of the iteration's input (the
// band's and those two steps above and below it, inside the image), computed by the band
// itself. A pass over the frame writing a luminance plane and reading it back took 0.4 ms of an
// iteration's 8 (camera-pan 720p, 2 threads, Zen 5 VM) and a barrier; a band's rows and their
// taps' rows are in its cache when its taps read them. Padded by two steps on either side: a
// border tap row's loads reach that far past the rows (kBorder; not taken).
class BandLuminance {
 public:
  // For bands of up to `rows` rows.
  BandLuminance(int width, int rows, int step)
      : w_(width), pad_(2 * step),
        values_(static_cast<size_t>(rows + 4 * step) * width + 2 * pad_) {}

  void compute(ConstRgbView color, int first, int last) {
    first_ = first;
    const size_t n = static_cast<size_t>(last - first) * w_;
    const size_t at = static_cast<size_t>(first) * w_;
    float* values = values_.data();
    std::fill_n(values, pad_, 0.f);
    luminance_span(color.r + at, color.g + at, color.b + at, values + pad_, static_cast<int>(n));
    std::fill_n(values + pad_ + n, pad_, 0.f);
  }
  // Row y's luminances: pixel x's at [x].
  const float* row(int y) const {
    return values_.data() + pad_ + static_cast<size_t>(y - first_) * w_;
  }

 private:
  int w_;
  size_t pad_;
  int first_ = 0;
  UninitializedPlane<float> values_;
};

}  // namespace

// The rows of an iteration run in bands of whole chains (AtrousNormalPairs): a band's rows y0..
// as the chains y0 + r, y0 + r + step, ... for r < step, each chain starting from the terms
// of the two rows above it, computed first. Bands of at least 8 rows a chain keep those extra
// rows to a quarter of a row's normal terms a chain row or less; any partition gives the same
// bits (a term is the same value whichever row computes it). The bands are made as many as a
// multiple of the threads, of equal heights: 720 rows in 11 bands of 64 and one of 16 kept
// one of 2 threads waiting 3 to 6% of an iteration (Zen 5 VM), in 12 of 60 about 2%.
void run_atrous_rows(const AtrousKernel& kernel, int width, int height,
                     const AtrousRowOutputs& outputs) {
  if (width <= 0 || height <= 0) return;  // no rows (and no bands to divide them into)
  const int step = kernel.step;
  const int threads = std::max(1, tbb::this_task_arena::max_concurrency());
  const int tallest = std::max(64, 8 * step);  // the bands' height before they are evened
  int bands = (height + tallest - 1) / tallest;
  bands = std::min(height, (bands + threads - 1) / threads * threads);
  const int band = (height + bands - 1) / bands;
  bands = (height + band - 1) / band;
  with_normal_power(kernel.params.phi_normal, [&](const auto& power) {
    tbb::parallel_for(
        tbb::blocked_range<int>(0, bands, 1),
        [&](const tbb::blocked_range<int>& r) {
          ScopedIeeeFloat ieee;
          RowScratch s(kAtrousScratch, width);
          AtrousNormalPairs pairs(kernel.guides, step);
          BandLuminance lum(width, band, step);
          for (int b = r.begin(); b != r.end(); ++b) {
            const int y0 = b * band, y1 = std::min(height, y0 + band);
            lum.compute(kernel.in.color, std::max(0, y0 - 2 * step),
                        std::min(height, y1 + 2 * step));
            for (int first = y0; first < std::min(y1, y0 + step); ++first) {
              if (first - 2 * step >= 0) pairs.compute(first - 2 * step, 2, power);
              if (first - step >= 0) pairs.compute(first - step, 1, power);
              for (int y = first; y < y1; y += step) {
                pairs.compute(y, 0, power);
                atrous_row(kernel, outputs, lum.row(y), y, s, power, pairs);
              }
            }
          }
        },
        tbb::simple_partitioner());
  });
}

void run_variance_rows(const VarianceKernel& kernel, int width, int height) {
  const UninitializedPlane<float> lum = luminance_plane(kernel.accumulated.color, width, height);
  with_normal_power(kernel.params.phi_normal, [&](const auto& power) {
    parallel_rows(height, [&](int y0, int y1) {
      RowScratch s(7, width);
      for (int y = y0; y < y1; ++y) variance_row(kernel, lum.data(), y, s, power);
    });
  });
}

}  // namespace svgf::cpu

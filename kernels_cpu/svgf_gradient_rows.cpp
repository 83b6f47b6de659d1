// A-SVGF's gradient stages (methods/svgf/gradient.h) on the CPU, a stratum row at a time. The
// samples: the mask tests of a stratum row's three pixel rows as one vector loop (a byte a
// pixel), then vector loops over its strata: each one's first masked pixel from those bytes,
// its luminances gathered there, its values by the kernel's rule as selects. The a-trous: the
// per-stratum kernel branches on every tap (inside? data? same mesh?) and stays scalar. A row
// runs its interior strata (all nine taps inside the stratum image) as vector loops, one a tap
// row with the sums in row scratch between them (nine taps in one loop spilled): every
// tap's weight by the kernel's own functions, added by a select where the kernel adds it, so a
// skipped tap leaves the sums untouched (adding 0 would not: -0, Inf * 0, NaN * 0), the same
// terms in the same order. A stratum's guides lie at its sample's pixel, one pixel of nine at a
// per-stratum offset: they are gathered once a pass into planes over the strata, so the taps
// load them contiguously (nine gathers a stratum were the stage's cost). The border strata and
// the rows near the top and bottom run the per-stratum kernel. The lambda stage likewise: each
// stratum's own lambda (a division) once, not once for every neighbour that reads it, then the
// neighbourhood's maximum in the kernel's order, a tap at a time along a row. Same bits as the
// kernels (tests/svgf_cpu_gradient_rows_test.cpp).
#include <type_traits>
#include <vector>

#include "kernels_cpu/row_tools.h"
#include "kernels_cpu/svgf_rows.h"

namespace svgf::cpu {
namespace {

// Each pixel's mask test (GradientSamplesKernel::masked) as a byte, n pixels (vectorized).
SVGF_TAP_LOOP void masked_bytes(const float* __restrict mask, uint8_t* __restrict out, int n) {
  for (int i = 0; i < n; ++i) out[i] = GradientSamplesKernel::masked(mask[i]);
}

// Each stratum's first masked pixel in raster order among its nine (-1: none), for the n
// strata of whole columns of a stratum row whose three rows' mask tests are `masked` (rows w
// bytes apart), as GradientSamplesKernel::sample finds it (vectorized: the loads at a stride
// of 3 bytes are permutes).
SVGF_TAP_LOOP void first_masked(const uint8_t* __restrict masked, int w, int* __restrict first,
                                int n) {
  constexpr int k = kGradientStratum;
  for (int sx = 0; sx < n; ++sx) {
    int f = -1;
#pragma GCC unroll 9
    for (int t = k * k - 1; t >= 0; --t) f = masked[(t / k) * w + sx * k + t % k] ? t : f;
    first[sx] = f;
  }
}

// The n strata's guide offsets (the first masked pixel's, or `centre` where there is none) and
// the luminances there (a gather; at the centre loaded, not used). Planes offset to the stratum
// row's first pixel, the offsets to its first stratum. A loop of its own: with the selects below
// in it, GCC sinks the loads under the test for a sample and vectorizes neither.
SVGF_TAP_LOOP void sample_luminances(const int* __restrict first,
                                     const float* __restrict previous,
                                     const float* __restrict current, int w, int centre,
                                     float* __restrict guide_offset, float* __restrict prev,
                                     float* __restrict cur, int n) {
  constexpr int k = kGradientStratum;
  for (int sx = 0; sx < n; ++sx) {
    const int f = first[sx];
    const int at = f >= 0 ? f : centre;
    const int i = (at / k) * w + sx * k + at % k;
    guide_offset[sx] = static_cast<float>(at);
    prev[sx] = previous[i];
    cur[sx] = current[i];
  }
}

// The n strata's samples, GradientSamplesKernel::sample_at with its branches as selects: the
// values where there is a sample and both luminances pass radiance_ok, the kernel's defaults
// (StratumValue) elsewhere. The outputs offset to the row's first stratum.
SVGF_TAP_LOOP void samples_from_first(const int* __restrict first, const float* __restrict prev,
                                      const float* __restrict cur, float* __restrict delta,
                                      float* __restrict normalizer, float* __restrict weight,
                                      int n) {
  const StratumValue none;
  for (int sx = 0; sx < n; ++sx) {
    const int f = first[sx];
    const float p = prev[sx], c = cur[sx];
    const bool data = (f >= 0) & radiance_ok(p) & radiance_ok(c);
    delta[sx] = data ? c - p : none.delta;
    normalizer[sx] = data ? max_f(c, p) : none.normalizer;
    weight[sx] = data ? 1.f : none.weight;
  }
}

// A stratum row's scratch for the samples stage (width pixels).
struct SamplesScratch {
  std::vector<uint8_t> masked;  // its three rows' mask tests
  std::vector<int> first;       // each stratum's first masked pixel
  std::vector<float> prev, cur; // the luminances there
  explicit SamplesScratch(int width)
      : masked(static_cast<size_t>(kGradientStratum) * width),
        first(static_cast<size_t>(width / kGradientStratum)),
        prev(first.size()),
        cur(first.size()) {}
};

// Stratum row sy of the samples stage: its three pixel rows' mask tests at once (they lie one
// after the other in the plane), then its strata of three whole columns find their first
// masked pixels in those bytes and take their samples as the kernel's sample_at does (the
// centre, for the guides without a sample, at offset 4), each pass a vector loop (a stratum at
// a time, scalar, they took 0.6 ms of a 720p frame on the Zen 5 VM). A partial last column or
// row runs the kernel. `scratch`: the row's mask bytes and its strata's first pixels and
// luminances (SamplesScratch).
void gradient_samples_row(const GradientSamplesKernel& k, int sy, SamplesScratch& scratch) {
  constexpr int n = kGradientStratum;
  const int w = k.width, sw = k.strata_width, y0 = sy * n;
  int whole = 0;  // strata of whole columns, in a stratum row of whole pixel rows
  if (y0 + n <= k.height) {
    const size_t row = static_cast<size_t>(y0) * w;
    const size_t s = static_cast<size_t>(sy) * sw;
    whole = w / n;
    masked_bytes(k.samples.mask + row, scratch.masked.data(), n * w);
    first_masked(scratch.masked.data(), w, scratch.first.data(), whole);
    sample_luminances(scratch.first.data(), k.samples.previous + row, k.samples.current + row, w,
                      n + 1, k.guide_offset + s, scratch.prev.data(), scratch.cur.data(), whole);
    samples_from_first(scratch.first.data(), scratch.prev.data(), scratch.cur.data(),
                       k.out.delta + s, k.out.normalizer + s, k.out.weight + s, whole);
  }
  for (int sx = whole; sx < sw; ++sx) k(sx, sy);
}

// The guides the taps read, per stratum (at its sample's pixel, StratumGuides::pixel).
struct StrataGuides {
  UninitializedPlane<float> depth, nx, ny, nz;
  UninitializedPlane<uint32_t> mesh;
  explicit StrataGuides(size_t n) : depth(n), nx(n), ny(n), nz(n), mesh(n) {}
};

// Stratum row sy (sw strata): its guides gathered.
SVGF_TAP_LOOP void gather_strata_guides(const GradientAtrousKernel& kernel, int sy, int sw,
                                        float* __restrict depth, float* __restrict nx,
                                        float* __restrict ny, float* __restrict nz,
                                        uint32_t* __restrict mesh) {
  const GradientAtrousKernel k = kernel;
  for (int sx = 0; sx < sw; ++sx) {
    const int s = sy * sw + sx, p = k.at.pixel(sx, sy);
    depth[s] = k.guides.depth[p];
    nx[s] = k.guides.normal.r[p];
    ny[s] = k.guides.normal.g[p];
    nz[s] = k.guides.normal.b[p];
    mesh[s] = k.guides.mesh_id[p];
  }
}

// The interior strata's centre terms (1 / phi_z from the depth's fwidth at each one's guide
// pixel) and their sums at 0, for strata x0..x1 of stratum row sy; scratch indexed by sx.
SVGF_TAP_LOOP void gradient_atrous_centres(const GradientAtrousKernel& kernel, int sy, int x0,
                                           int x1, float* __restrict inv_phi_z,
                                           float* __restrict sum_w, float* __restrict sum_d,
                                           float* __restrict sum_n) {
  const GradientAtrousKernel k = kernel;  // a local copy: its plane pointers stay in registers
  for (int sx = x0; sx < x1; ++sx) {
    inv_phi_z[sx] = inv_depth_tolerance<ExactArith>(
        k.phi_depth, k.guides.depth_fwidth(k.at.pixel(sx, sy)), k.depth_gradient_floor);
    sum_w[sx] = sum_d[sx] = sum_n[sx] = 0.f;
  }
}

// The three taps dx = -1, 0, 1 of tap row dy (kCentreRow: dy = 0) for strata x0..x1 of a
// stratum row starting at index `row`, added to the sums in the kernel's order: each tap's
// weight by the kernel's own functions, added by a select where the kernel adds it, so a
// skipped tap leaves the sums untouched (adding 0 would not: -0, Inf * 0, NaN * 0). A tap row a
// loop (the nine taps in one loop kept 65 values on the stack).
template <class Power, bool kCentreRow>
SVGF_TAP_LOOP void gradient_atrous_tap_row(
    const float* __restrict depth, const float* __restrict nx, const float* __restrict ny,
    const float* __restrict nz, const uint32_t* __restrict mesh_of,
    const float* __restrict weight_in, const float* __restrict delta_in,
    const float* __restrict normalizer_in, const float* __restrict inv_phi_z,
    float* __restrict sum_w, float* __restrict sum_d, float* __restrict sum_n, int row, int dy,
    int sw, int step, GradientAtrousKernel::InvTapDistances distances, int x0, int x1,
    const Power& power) {
  for (int sx = x0; sx < x1; ++sx) {
    const int s = row + sx;
    const EdgeSample c{depth[s], make_vec3(nx[s], ny[s], nz[s]), 0.f};
    const uint32_t mesh = mesh_of[s];
    const float ipz = inv_phi_z[sx];
    float weight_sum = sum_w[sx], delta = sum_d[sx], normalizer = sum_n[sx];
#pragma GCC unroll 3
    for (int dx = -1; dx <= 1; ++dx) {
      const int q = s + (dy * sw + dx) * step;
      const bool centre = kCentreRow && dx == 0;
      const EdgeSample e{depth[q], make_vec3(nx[q], ny[q], nz[q]), 0.f};
      // The kernel's scale (the centre's is not used).
      const float scale = distances.depth_scale(ipz, dx, dy);
      const float w = centre ? 1.f : edge_stopping_weight<RowExactArith>(c, e, scale, power, 0.f);
      const bool take = (weight_in[q] > 0.f) & (centre | (mesh_of[q] == mesh));
      const float with_sum = weight_sum + w;
      const float with_delta = delta + delta_in[q] * w;
      const float with_normalizer = normalizer + normalizer_in[q] * w;
      weight_sum = take ? with_sum : weight_sum;
      delta = take ? with_delta : delta;
      normalizer = take ? with_normalizer : normalizer;
    }
    sum_w[sx] = weight_sum;
    sum_d[sx] = delta;
    sum_n[sx] = normalizer;
  }
}

// The interior strata's results from their sums, the kernel's last lines.
SVGF_TAP_LOOP void gradient_atrous_results(const float* __restrict sum_w,
                                           const float* __restrict sum_d,
                                           const float* __restrict sum_n,
                                           float* __restrict delta, float* __restrict normalizer,
                                           float* __restrict weight, int x0, int x1) {
  for (int sx = x0; sx < x1; ++sx) {
    const bool any = sum_w[sx] > 0.f;
    delta[sx] = any ? sum_d[sx] / sum_w[sx] : 0.f;
    normalizer[sx] = any ? sum_n[sx] / sum_w[sx] : 0.f;
    weight[sx] = any ? 1.f : 0.f;
  }
}

// A stratum row's scratch for the a-trous (its strata's centre terms and sums).
struct AtrousScratch {
  std::vector<float> inv_phi_z, sum_w, sum_d, sum_n;
  explicit AtrousScratch(int strata)
      : inv_phi_z(static_cast<size_t>(strata)), sum_w(inv_phi_z.size()),
        sum_d(inv_phi_z.size()), sum_n(inv_phi_z.size()) {}
};

template <class Power>
void gradient_atrous_row(const GradientAtrousKernel& k, const StrataGuides& g, int sy,
                         AtrousScratch& scratch, const Power& power) {
  const int sw = k.at.strata_width, step = k.step;
  const bool inside_y = sy - step >= 0 && sy + step < k.strata_height;
  const int x0 = inside_y ? (step < sw ? step : sw) : sw;  // [x0, x1): interior strata
  const int x1 = inside_y && sw - step > x0 ? sw - step : x0;
  for (int sx = 0; sx < x0; ++sx) k(sx, sy);
  if (x1 > x0) {
    float* ipz = scratch.inv_phi_z.data();
    float* sum_w = scratch.sum_w.data();
    float* sum_d = scratch.sum_d.data();
    float* sum_n = scratch.sum_n.data();
    gradient_atrous_centres(k, sy, x0, x1, ipz, sum_w, sum_d, sum_n);
    const GradientAtrousKernel::InvTapDistances d = k.inv_tap_distances();
    const int row = sy * sw;
    for (int dy = -1; dy <= 1; ++dy) {  // dy outer, dx inner, as the kernel
      const auto taps = [&](auto centre_row) {
        gradient_atrous_tap_row<Power, decltype(centre_row)::value>(
            g.depth.data(), g.nx.data(), g.ny.data(), g.nz.data(), g.mesh.data(), k.in.weight,
            k.in.delta, k.in.normalizer, ipz, sum_w, sum_d, sum_n, row, dy, sw, step, d, x0,
            x1, power);
      };
      if (dy == 0)
        taps(std::true_type{});
      else
        taps(std::false_type{});
    }
    gradient_atrous_results(sum_w, sum_d, sum_n, k.out.delta + row, k.out.normalizer + row,
                            k.out.weight + row, x0, x1);
  }
  for (int sx = x1; sx < sw; ++sx) k(sx, sy);
}

// Stratum row sy's own lambdas (stratum_lambda, as GradientLambdaKernel::lambda_of), at
// own[0..sw).
SVGF_TAP_LOOP void own_lambdas(const float* __restrict delta, const float* __restrict normalizer,
                               const float* __restrict weight, float* __restrict own, int sw) {
  for (int sx = 0; sx < sw; ++sx)
    own[sx] = stratum_lambda(weight[sx], delta[sx], normalizer[sx]);
}

// out[x] = max_f(out[x], tap[x]) for x in 0..n: one neighbour of a row of strata, in order.
SVGF_TAP_LOOP void max_tap(const float* __restrict tap, float* __restrict out, int n) {
  for (int x = 0; x < n; ++x) out[x] = max_f(out[x], tap[x]);
}

// Stratum row sy of the lambda stage: the interior strata (the whole neighbourhood inside) by
// max_tap over the own lambdas, a neighbour at a time in the kernel's order (the centre first,
// then dy outer, dx inner, the centre again: max_f is not symmetric in NaN, so the order is
// kept); the others by the kernel.
void gradient_lambda_row(const GradientLambdaKernel& k, const float* own, int sy) {
  const int sw = k.strata_width, r = k.radius;
  const bool inside_y = sy - r >= 0 && sy + r < k.strata_height;
  const int x0 = inside_y ? (r < sw ? r : sw) : sw;  // [x0, x1): interior strata
  const int x1 = inside_y && sw - r > x0 ? sw - r : x0;
  for (int sx = 0; sx < x0; ++sx) k(sx, sy);
  if (x1 > x0) {
    float* out = k.lambda + sy * sw + x0;
    const float* centre = own + sy * sw + x0;
    for (int x = 0; x < x1 - x0; ++x) out[x] = centre[x];
    for (int dy = -r; dy <= r; ++dy)
      for (int dx = -r; dx <= r; ++dx) max_tap(centre + dy * sw + dx, out, x1 - x0);
  }
  for (int sx = x1; sx < sw; ++sx) k(sx, sy);
}

}  // namespace

void run_gradient_samples_rows(const GradientSamplesKernel& kernel, int strata_width,
                               int strata_height) {
  (void)strata_width;  // the kernel's own
  parallel_rows(strata_height, [&](int y0, int y1) {
    SamplesScratch scratch(kernel.width);
    for (int sy = y0; sy < y1; ++sy) gradient_samples_row(kernel, sy, scratch);
  });
}

void run_gradient_lambda_rows(const GradientLambdaKernel& kernel, int strata_width,
                              int strata_height) {
  (void)strata_width;  // the kernel's own (strata_width, strata_height) are the image
  (void)strata_height;
  const int sw = kernel.strata_width, sh = kernel.strata_height;
  UninitializedPlane<float> own(static_cast<size_t>(sw) * static_cast<size_t>(sh));
  parallel_rows(sh, [&](int y0, int y1) {
    for (int sy = y0; sy < y1; ++sy) {
      const int s = sy * sw;
      own_lambdas(kernel.in.delta + s, kernel.in.normalizer + s, kernel.in.weight + s,
                  own.data() + s, sw);
    }
  });
  parallel_rows(sh, [&](int y0, int y1) {
    for (int sy = y0; sy < y1; ++sy) gradient_lambda_row(kernel, own.data(), sy);
  });
}

void run_gradient_atrous_rows(const GradientAtrousKernel& kernel, int strata_width,
                              int strata_height) {
  (void)strata_width;  // the kernel's own (at.strata_width, strata_height) are the image
  (void)strata_height;
  const int sw = kernel.at.strata_width, sh = kernel.strata_height;
  StrataGuides g(static_cast<size_t>(sw) * static_cast<size_t>(sh));
  parallel_rows(sh, [&](int y0, int y1) {
    for (int sy = y0; sy < y1; ++sy)
      gather_strata_guides(kernel, sy, sw, g.depth.data(), g.nx.data(), g.ny.data(),
                           g.nz.data(), g.mesh.data());
  });
  with_normal_power(kernel.phi_normal, [&](const auto& power) {
    parallel_rows(sh, [&](int y0, int y1) {
      AtrousScratch scratch(sw);
      for (int sy = y0; sy < y1; ++sy) gradient_atrous_row(kernel, g, sy, scratch, power);
    });
  });
}

}  // namespace svgf::cpu

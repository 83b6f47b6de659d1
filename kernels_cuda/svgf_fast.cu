// Fast mode. Built with --use_fast_math (FMA contraction, approximate division and sqrt,
// __expf, flush-to-zero). What it does differently from exact mode, and why:
//  - demodulate and reproject are one launch: the illumination stays in registers/L1;
//  - the variance estimate writes color and variance packed as one float4 per pixel, and the
//    a-trous iterations read and write that layout: one 16-byte load per tap instead of four
//    scalar loads, and the guides (depth + normal) likewise as one float4;
//  - the edge-stopping weight uses __expf, reciprocals instead of divisions, and the normal
//    term max(0, n.n')^128 as seven squarings in float instead of det_pow's double loop;
//  - the feedback copy and the remodulation ride on the a-trous iteration that produces them.
// Every pixel is still computed by one thread in a fixed order with no float atomics, so fast
// mode is deterministic too (same bits for any block shape and run); it just is not the CPU's.
#include <string>

#include "core/copy.h"
#include "core/demodulate.h"
#include "core/remodulate.h"
#include "core/reproject.h"
#include "kernels_cuda/exact_launch.h"
#include "kernels_cuda/launch_config.h"
#include "kernels_cuda/pixel_kernels.cuh"
#include "kernels_cuda/svgf_fast.h"

namespace svgf::cuda::fast {
namespace {

using device::pixel_x;
using device::pixel_y;

// Edge-stopping constants of one frame, folded on the host.
struct EdgeParams {
  float phi_normal = 128.f;
  int normal_pow = 128;  // phi_normal as a non-negative integer exponent, or -1 when it is not
};

EdgeParams edge_params(const SvgfParams& p) {
  EdgeParams e;
  e.phi_normal = p.phi_normal;
  const bool integer = p.phi_normal >= 0.f && p.phi_normal <= 65536.f &&
                       static_cast<float>(static_cast<int>(p.phi_normal)) == p.phi_normal;
  e.normal_pow = integer ? static_cast<int>(p.phi_normal) : -1;
  return e;
}

// x^phi_normal for x in [0, 1]. kPow128: the default exponent as seven squarings.
template <bool kPow128>
__device__ __forceinline__ float normal_power(float x, const EdgeParams& e) {
  if (kPow128) {
    float r = x * x;  // x^2
    r = r * r;        // x^4
    r = r * r;        // x^8
    r = r * r;        // x^16
    r = r * r;        // x^32
    r = r * r;        // x^64
    return r * r;     // x^128
  }
  if (e.normal_pow >= 0) {  // integer exponent: square and multiply
    unsigned n = static_cast<unsigned>(e.normal_pow);
    float r = 1.f, base = x;
    while (n != 0u) {
      if (n & 1u) r *= base;
      n >>= 1;
      if (n != 0u) base *= base;
    }
    return r;
  }
  return x > 0.f ? __powf(x, e.phi_normal) : (e.phi_normal > 0.f ? 0.f : 1.f);
}

__device__ __forceinline__ float luminance3(float r, float g, float b) {
  return 0.2126f * r + 0.7152f * g + 0.0722f * b;
}

// The SVGF weight exp(-|dl|/phi_l - |dz|/phi_z) * max(0, n.n')^phi_n with reciprocals passed
// in (inv_phi_z = 0: no depth term). NaN guides give weight 0, as in exact mode.
template <bool kPow128>
__device__ __forceinline__ float edge_weight(float4 gc, float lc, float4 gq, float lq,
                                             float inv_phi_z, float inv_phi_l,
                                             const EdgeParams& e) {
  const float nd = fmaxf(0.f, gc.y * gq.y + gc.z * gq.z + gc.w * gq.w);
  const float w_normal = normal_power<kPow128>(nd, e);
  const float e_depth = fmaxf(fabsf(gc.x - gq.x) * inv_phi_z, 0.f);
  const float e_lum = fmaxf(fabsf(lc - lq) * inv_phi_l, 0.f);
  const float w = __expf(-(e_lum + e_depth)) * w_normal;
  return w > 0.f ? w : 0.f;
}

__device__ __forceinline__ bool inside(int x, int y, int width, int height) {
  return x >= 0 && y >= 0 && x < width && y < height;
}

// --- 2. variance: pass-through or the 7x7 spatial estimate, written packed ------------------

struct VarianceArgs {
  int width = 0, height = 0;
  ConstIllumVarView accumulated;
  const float* moment1 = nullptr;
  const float* moment2 = nullptr;
  const float* history = nullptr;
  const float4* guides = nullptr;
  const float* depth_dx = nullptr;
  const float* depth_dy = nullptr;
  float4* out = nullptr;
  int spatial_history = 4;
  int radius = 3;
  float phi_depth = 3.f;
  float inv_phi_color = 0.1f;
  float depth_gradient_floor = 1e-8f;
  EdgeParams edge;
};

template <bool kPow128>
__global__ void variance_kernel(const VarianceArgs a) {
  const int x = pixel_x();
  const int y = pixel_y();
  if (x >= a.width || y >= a.height) return;
  const int i = y * a.width + x;
  const float h = a.history[i];
  const float4 gc = a.guides[i];
  const float cr = a.accumulated.color.r[i], cg = a.accumulated.color.g[i],
              cb = a.accumulated.color.b[i];
  if (!(h < static_cast<float>(a.spatial_history)) || !(gc.x > 0.f)) {
    a.out[i] = make_float4(cr, cg, cb, a.accumulated.variance[i]);
    return;
  }
  const float lc = luminance3(cr, cg, cb);
  const float phi_z =
      a.phi_depth * fmaxf(fmaxf(fabsf(a.depth_dx[i]), fabsf(a.depth_dy[i])), a.depth_gradient_floor);
  const float inv_phi_z = phi_z == 0.f ? 0.f : 1.f / phi_z;
  float wsum = 0.f, sr = 0.f, sg = 0.f, sb = 0.f, m1 = 0.f, m2 = 0.f;
  for (int dy = -a.radius; dy <= a.radius; ++dy) {
    for (int dx = -a.radius; dx <= a.radius; ++dx) {
      const int xq = x + dx, yq = y + dy;
      if (!inside(xq, yq, a.width, a.height)) continue;
      const int j = yq * a.width + xq;
      const float qr = a.accumulated.color.r[j], qg = a.accumulated.color.g[j],
                  qb = a.accumulated.color.b[j];
      const int d2 = dx * dx + dy * dy;
      const float inv_dist = d2 == 0 ? 0.f : rsqrtf(static_cast<float>(d2));  // centre: no depth term
      const float w = edge_weight<kPow128>(gc, lc, a.guides[j], luminance3(qr, qg, qb),
                                           inv_phi_z * inv_dist, a.inv_phi_color, a.edge);
      wsum += w;
      sr += qr * w;
      sg += qg * w;
      sb += qb * w;
      m1 += a.moment1[j] * w;
      m2 += a.moment2[j] * w;
    }
  }
  const float inv = 1.f / fmaxf(wsum, 1e-6f);
  m1 *= inv;
  m2 *= inv;
  a.out[i] = make_float4(sr * inv, sg * inv, sb * inv,
                         fmaxf(0.f, m2 - m1 * m1) *
                             (static_cast<float>(a.spatial_history) / h));
}

// --- 3. one a-trous iteration on packed color+variance, optionally feeding back/remodulating --

struct AtrousArgs {
  int width = 0, height = 0, step = 1;
  const float4* in = nullptr;
  const float4* guides = nullptr;
  const float* depth_dx = nullptr;
  const float* depth_dy = nullptr;
  float4* out = nullptr;  // null on the last iteration: only the remodulated output is needed
  RgbView feedback;       // r null: this iteration is not the feedback tap
  ConstRgbView albedo;    // with `output`: remodulate (last iteration)
  ConstRgbView emission;  // optional, added back by the remodulation
  RgbView output;         // r null: not the last iteration
  float albedo_epsilon = 1e-3f;
  float phi_color = 10.f;
  float phi_depth = 1.f;
  float variance_epsilon = 1e-4f;
  float depth_gradient_floor = 1e-8f;
  EdgeParams edge;
};

__device__ __forceinline__ void finish_pixel(const AtrousArgs& a, int i, float4 v) {
  if (a.out) a.out[i] = v;
  if (a.feedback.r) a.feedback.store(i, make_vec3(v.x, v.y, v.z));
  if (a.output.r)
    a.output.store(i, remodulated(make_vec3(v.x, v.y, v.z), a.albedo.load(i),
                                  a.emission.load_or_zero(i), a.albedo_epsilon));
}

// 1 / sqrt(dx^2 + dy^2) for the 5x5 taps: compile-time constants once the tap loop is unrolled
// (rsqrtf and the int-to-float conversion are quarter-rate instructions, twice per tap).
__device__ __forceinline__ constexpr float inv_tap_distance(int dx, int dy) {
  const int d2 = dx * dx + dy * dy;
  return d2 == 1 ? 1.f
                 : d2 == 2 ? 0.70710678f
                           : d2 == 4 ? 0.5f : d2 == 5 ? 0.44721360f : 0.35355339f;  // 8
}
__device__ __forceinline__ constexpr float b3(int d) {
  return d == 0 ? 0.375f : (d == 1 || d == -1 ? 0.25f : 0.0625f);
}

// The 24 outer taps of one a-trous pixel. kCheck: some tap may fall outside the image; the
// pixels whose 5x5 footprint is inside skip the 24 bounds tests.
template <bool kPow128, bool kCheck>
__device__ __forceinline__ void atrous_taps(const AtrousArgs& a, int x, int y, float4 gc, float lc,
                                            float inv_phi_z, float inv_phi_l, float& wsum,
                                            float& sr, float& sg, float& sb, float& svar) {
  const int w = a.width;
#pragma unroll
  for (int dy = -2; dy <= 2; ++dy) {
#pragma unroll
    for (int dx = -2; dx <= 2; ++dx) {
      if (dx == 0 && dy == 0) continue;
      const int xq = x + dx * a.step, yq = y + dy * a.step;
      if (kCheck && !inside(xq, yq, w, a.height)) continue;
      const int j = yq * w + xq;
      const float4 q = a.in[j];
      const float wt = edge_weight<kPow128>(gc, lc, a.guides[j], luminance3(q.x, q.y, q.z),
                                            inv_phi_z * inv_tap_distance(dx, dy), inv_phi_l,
                                            a.edge) *
                       (b3(dx) * b3(dy));
      wsum += wt;
      sr += q.x * wt;
      sg += q.y * wt;
      sb += q.z * wt;
      svar += q.w * (wt * wt);
    }
  }
}

template <bool kPow128>
__global__ void atrous_kernel(const AtrousArgs a) {
  const int x = pixel_x();
  const int y = pixel_y();
  if (x >= a.width || y >= a.height) return;
  const int w = a.width, h = a.height;
  const int i = y * w + x;
  const float4 c = a.in[i];
  const float4 gc = a.guides[i];
  if (!(gc.x > 0.f)) {  // background: passes through
    finish_pixel(a, i, c);
    return;
  }
  // 3x3 Gaussian of the variance, renormalized at the border.
  float vsum = 0.f, ksum = 0.f;
#pragma unroll
  for (int dy = -1; dy <= 1; ++dy) {
#pragma unroll
    for (int dx = -1; dx <= 1; ++dx) {
      if (!inside(x + dx, y + dy, w, h)) continue;
      const float k = (dx == 0 ? 0.5f : 0.25f) * (dy == 0 ? 0.5f : 0.25f);
      vsum += a.in[i + dy * w + dx].w * k;
      ksum += k;
    }
  }
  const float variance = __fdividef(vsum, ksum);
  const float phi_l = a.phi_color * sqrtf(fmaxf(0.f, a.variance_epsilon + variance));
  const float inv_phi_l = 1.f / phi_l;
  const float phi_z =
      a.phi_depth * fmaxf(fmaxf(fabsf(a.depth_dx[i]), fabsf(a.depth_dy[i])), a.depth_gradient_floor);
  const float inv_phi_z = phi_z == 0.f ? 0.f : 1.f / (phi_z * static_cast<float>(a.step));
  const float lc = luminance3(c.x, c.y, c.z);

  constexpr float kCenter = 0.375f * 0.375f;
  float wsum = kCenter;
  float sr = c.x * kCenter, sg = c.y * kCenter, sb = c.z * kCenter;
  float svar = c.w * (kCenter * kCenter);
  const int reach = 2 * a.step;
  if (x >= reach && y >= reach && x < w - reach && y < h - reach)
    atrous_taps<kPow128, false>(a, x, y, gc, lc, inv_phi_z, inv_phi_l, wsum, sr, sg, sb, svar);
  else
    atrous_taps<kPow128, true>(a, x, y, gc, lc, inv_phi_z, inv_phi_l, wsum, sr, sg, sb, svar);
  const float inv = 1.f / wsum;
  finish_pixel(a, i, make_float4(sr * inv, sg * inv, sb * inv, svar * (inv * inv)));
}

// --- small helpers: copies when the feedback tap or the a-trous loop is empty ---------------

__global__ void copy_rgb_kernel(const CopyRgbKernel k, int width, int height) {
  const int x = pixel_x();
  const int y = pixel_y();
  if (x < width && y < height) k(x, y);
}

__global__ void remodulate_packed_kernel(const AtrousArgs a) {
  const int x = pixel_x();
  const int y = pixel_y();
  if (x < a.width && y < a.height) finish_pixel(a, y * a.width + x, a.in[y * a.width + x]);
}

template <class Args>
void launch_with_pow(bool pow128, void (*k128)(Args), void (*kany)(Args), const Args& args,
                     const LaunchGeometry& g, cudaStream_t stream, const char* name) {
  if (pow128)
    k128<<<g.grid, g.block, 0, stream>>>(args);
  else
    kany<<<g.grid, g.block, 0, stream>>>(args);
  check_launch(name, g);
}

}  // namespace

void run_frame(CudaEngine& engine, const SvgfFrameBuffers& b, const FastBuffers& f,
               const SvgfParams& p, bool has_history) {
  const int w = b.guides.width;
  const int h = b.guides.height;
  const LaunchGeometry g = launch_geometry(w, h, engine.shape());
  const cudaStream_t stream = engine.stream();
  const EdgeParams edge = edge_params(p);
  const bool pow128 = edge.normal_pow == 128;
  float4* packed[2] = {reinterpret_cast<float4*>(f.packed[0]),
                       reinterpret_cast<float4*>(f.packed[1])};
  float4* guides = reinterpret_cast<float4*>(f.guides);

  // 1. demodulate + reproject: exact code (exact_kernels.cu), one launch, timed as Demodulate.
  engine.mark(Stage::Demodulate, "demodulate+reproject");
  launch_demodulate_reproject(demodulate_kernel_for(b, p), reproject_kernel_for(b, p, has_history),
                              f.guides, engine.shape(), stream, engine.counter());

  // 2. variance -> packed[0].
  VarianceArgs v;
  v.width = w;
  v.height = h;
  v.accumulated = b.accumulated;
  v.moment1 = b.next_moment1;
  v.moment2 = b.next_moment2;
  v.history = b.next_history;
  v.guides = guides;
  v.depth_dx = b.guides.depth_dx;
  v.depth_dy = b.guides.depth_dy;
  v.out = packed[0];
  v.spatial_history = p.spatial_variance_history;
  v.radius = p.spatial_variance_radius;
  v.phi_depth = p.spatial_variance_phi_depth;
  v.inv_phi_color = 1.f / p.phi_color;
  v.depth_gradient_floor = p.depth_gradient_floor;
  v.edge = edge;
  engine.mark(Stage::Variance, "fast variance");
  launch_with_pow(pow128, variance_kernel<true>, variance_kernel<false>, v, g, stream,
                  "fast variance");

  // 3. a-trous; the feedback tap also writes the color history, the last iteration remodulates.
  AtrousArgs a;
  a.width = w;
  a.height = h;
  a.guides = guides;
  a.depth_dx = b.guides.depth_dx;
  a.depth_dy = b.guides.depth_dy;
  a.albedo = b.albedo;
  a.emission = b.emission;
  a.albedo_epsilon = p.albedo_epsilon;
  a.phi_color = p.phi_color;
  a.phi_depth = p.phi_depth;
  a.variance_epsilon = p.variance_epsilon;
  a.depth_gradient_floor = p.depth_gradient_floor;
  a.edge = edge;
  int current = 0;
  for (int it = 0; it < p.iterations; ++it) {
    const bool last = it + 1 == p.iterations;
    a.step = 1 << it;
    a.in = packed[current];
    a.out = last ? nullptr : packed[1 - current];
    a.feedback = it == p.feedback_tap ? b.next_color : RgbView();
    a.output = last ? b.output : RgbView();
    const char* name = last ? "fast atrous+remodulate" : "fast atrous";
    engine.mark(Stage::Atrous, name);
    launch_with_pow(pow128, atrous_kernel<true>, atrous_kernel<false>, a, g, stream, name);
    current = 1 - current;
  }
  if (p.feedback_tap < 0 || p.feedback_tap >= p.iterations) {
    // No feedback tap in range: the unfiltered accumulation is the history (as in exact mode).
    engine.mark(Stage::Feedback, "fast copy_rgb");
    copy_rgb_kernel<<<g.grid, g.block, 0, stream>>>(
        CopyRgbKernel{w, b.accumulated.color, b.next_color}, w, h);
    check_launch("fast copy_rgb", g);
  }
  if (p.iterations <= 0) {
    a.in = packed[0];
    a.out = nullptr;
    a.feedback = RgbView();
    a.output = b.output;
    engine.mark(Stage::Remodulate, "fast remodulate");
    remodulate_packed_kernel<<<g.grid, g.block, 0, stream>>>(a);
    check_launch("fast remodulate", g);
  }
}

}  // namespace svgf::cuda::fast

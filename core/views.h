#pragma once
// Non-owning views of planar images, identical on host and device: a view is a bundle of plane
// pointers, each plane width*height values in row-major order, pixel (x, y) at y*width + x.
// Planar storage keeps GPU loads coalesced and CPU loops vectorizable.
#include <cstdint>
#include <type_traits>

#include "core/hd.h"
#include "core/vec.h"

namespace svgf {

// Three planes of an RGB (or XYZ) quantity. T is float or const float.
template <class T>
struct Rgb {
  T* r = nullptr;
  T* g = nullptr;
  T* b = nullptr;
  Rgb() = default;
  SVGF_HD Rgb(T* r_, T* g_, T* b_) : r(r_), g(g_), b(b_) {}
  // A writable view converts to a read-only one.
  template <class U, class = std::enable_if_t<std::is_same<const U, T>::value &&
                                              !std::is_same<U, T>::value>>
  SVGF_HD Rgb(const Rgb<U>& o) : r(o.r), g(o.g), b(o.b) {}
  SVGF_HD Vec3 load(int i) const { return make_vec3(r[i], g[i], b[i]); }
  SVGF_HD void store(int i, Vec3 v) const { r[i] = v.x; g[i] = v.y; b[i] = v.z; }
  // For optional inputs: a view without planes reads as 0.
  SVGF_HD Vec3 load_or_zero(int i) const { return r ? load(i) : Vec3(); }
};
using RgbView = Rgb<float>;
using ConstRgbView = Rgb<const float>;

// A color with its variance: one pixel of what flows between the variance estimate and the
// a-trous iterations (the variance is filtered alongside the color, paper Eq. 5).
struct ColorVar {
  Vec3 color;
  float variance = 0.f;
};
SVGF_HD ColorVar make_color_var(Vec3 c, float v) { ColorVar cv; cv.color = c; cv.variance = v; return cv; }

// Storage layout 1: color and variance in four separate planes.
template <class T>
struct IllumVar {
  Rgb<T> color;
  T* variance = nullptr;
  IllumVar() = default;
  SVGF_HD IllumVar(Rgb<T> c, T* v) : color(c), variance(v) {}
  template <class U, class = std::enable_if_t<std::is_same<const U, T>::value &&
                                              !std::is_same<U, T>::value>>
  SVGF_HD IllumVar(const IllumVar<U>& o) : color(o.color), variance(o.variance) {}
  SVGF_HD ColorVar load(int i) const { return make_color_var(color.load(i), variance[i]); }
  SVGF_HD void store(int i, ColorVar v) const { color.store(i, v.color); variance[i] = v.variance; }
};
using IllumVarView = IllumVar<float>;
using ConstIllumVarView = IllumVar<const float>;

// Four floats loaded and stored as one 16-byte access.
struct alignas(16) Packed4 {
  float x, y, z, w;
};
SVGF_HD Packed4 load_packed(const Packed4* p, int i) {
#if defined(__CUDA_ARCH__)
  const float4 v = reinterpret_cast<const float4*>(p)[i];
  Packed4 r; r.x = v.x; r.y = v.y; r.z = v.z; r.w = v.w;
  return r;
#else
  return p[i];
#endif
}

// Storage layout 2: color and variance packed as r, g, b, variance in one Packed4 per pixel
// (fast mode: one 16-byte load per a-trous tap instead of four). T is Packed4 or const Packed4.
template <class T>
struct PackedIllumVar {
  T* data = nullptr;
  PackedIllumVar() = default;
  SVGF_HD explicit PackedIllumVar(T* d) : data(d) {}
  template <class U, class = std::enable_if_t<std::is_same<const U, T>::value &&
                                              !std::is_same<U, T>::value>>
  SVGF_HD PackedIllumVar(const PackedIllumVar<U>& o) : data(o.data) {}
  SVGF_HD ColorVar load(int i) const {
    const Packed4 p = load_packed(data, i);
    return make_color_var(make_vec3(p.x, p.y, p.z), p.w);
  }
  SVGF_HD void store(int i, ColorVar v) const {
    Packed4 p; p.x = v.color.x; p.y = v.color.y; p.z = v.color.z; p.w = v.variance;
    data[i] = p;
  }
};

// What the edge-stopping tests read of a pixel's guides.
struct DepthNormal {
  float depth;
  Vec3 normal;
};

// A pixel has a surface where its depth is > 0 (background <= 0; NaN is no surface either).
SVGF_HD bool has_surface(float depth) { return depth > 0.f; }
// Largest absolute screen-space depth derivative (HLSL max(|ddx|,|ddy|), as Falcor stores it).
SVGF_HD float depth_fwidth_of(float depth_dx, float depth_dy) {
  return max_f(abs_f(depth_dx), abs_f(depth_dy));
}

// The G-buffer of one frame as the filters read it. Background pixels (no surface) have
// depth <= 0; every test below treats them, and NaN depth, as "no surface".
struct GuideView {
  int width = 0;
  int height = 0;
  const float* depth = nullptr;     // linear view depth, > 0 on surfaces
  const float* depth_dx = nullptr;  // d depth / d x, per pixel
  const float* depth_dy = nullptr;  // d depth / d y
  Rgb<const float> normal;          // world-space unit shading normal
  const uint32_t* mesh_id = nullptr;
  const float* motion_x = nullptr;  // pixels to the previous frame: prev = (x, y) + motion
  const float* motion_y = nullptr;

  SVGF_HD int index(int x, int y) const { return y * width + x; }
  SVGF_HD bool inside(int x, int y) const { return x >= 0 && y >= 0 && x < width && y < height; }
  SVGF_HD float depth_fwidth(int i) const { return depth_fwidth_of(depth_dx[i], depth_dy[i]); }
  SVGF_HD bool is_surface(int i) const { return has_surface(depth[i]); }
  SVGF_HD DepthNormal depth_normal(int i) const { return DepthNormal{depth[i], normal.load(i)}; }
};

// The guides the filters read, with depth and normal packed as one Packed4 per pixel (the
// packed flavors' storage; the same members as GuideView where the filters use them). The
// previous frame's, as SVGF's reprojection reads them there, carry the mesh ids and no depth
// gradient.
struct PackedGuides {
  int width = 0;
  int height = 0;
  const Packed4* depth_normal_data = nullptr;  // depth, normal x, y, z
  const float* depth_dx = nullptr;
  const float* depth_dy = nullptr;
  const uint32_t* mesh_id = nullptr;

  SVGF_HD int index(int x, int y) const { return y * width + x; }
  SVGF_HD bool inside(int x, int y) const { return x >= 0 && y >= 0 && x < width && y < height; }
  SVGF_HD float depth_fwidth(int i) const { return depth_fwidth_of(depth_dx[i], depth_dy[i]); }
  SVGF_HD DepthNormal depth_normal(int i) const {
    const Packed4 p = load_packed(depth_normal_data, i);
    return DepthNormal{p.x, make_vec3(p.y, p.z, p.w)};
  }
  SVGF_HD bool is_surface(int i) const { return has_surface(depth_normal(i).depth); }
};

}  // namespace svgf

// LDR-FLIP from the paper (Andersson et al. 2020). Two pipelines per pixel:
//  color:   RGB -> YCxCz, contrast-sensitivity (CSF) filtering per opponent channel, back to RGB
//           (clamped to the gamut), CIELAB with the Hunt adjustment, HyAB distance, compressed
//           by ^0.7 and remapped against the largest difference in the gamut (green vs blue);
//  feature: edges (first Gaussian derivative) and points (second derivative) of the achromatic
//           channel, compared by magnitude;
// combined as color_error ^ (1 - feature_error). docs/metrics.md lists the constants.
#include "metrics/flip.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "metrics/display_range.h"
#include "metrics/separable_filter.h"

namespace svgf::metrics {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Color pipeline constants (paper Sec. 4.1 and 4.2).
constexpr double kColorExponent = 0.7;  // q_c: compression of the HyAB distance
constexpr double kRemapBreak = 0.4;     // p_c: knee of the remapping, as a fraction of c_max
constexpr double kRemapValue = 0.95;    // p_t: error value at the knee
// Feature pipeline constants (paper Sec. 4.3).
constexpr double kFeatureWidth = 0.082;   // w: feature width in degrees; sigma = w/2 * ppd
constexpr double kFeatureExponent = 0.5;  // q_f

// CSF of each opponent channel as a sum of Gaussians in frequency, a * exp(-b f^2), whose
// spatial form is a * sqrt(pi/b) * exp(-pi^2 x^2 / b) with x in degrees (paper Eq. 2).
struct CsfTerm {
  double a, b;
};
const std::vector<CsfTerm>& csf(int channel) {
  static const std::array<std::vector<CsfTerm>, 3> terms = {{
      {{1.0, 0.0047}},                // achromatic (Y)
      {{1.0, 0.0053}},                // red-green (Cx)
      {{34.1, 0.04}, {13.5, 0.025}},  // blue-yellow (Cz)
  }};
  return terms[channel];
}
constexpr double kCsfWidestB = 0.04;  // sets the filter radius for all channels

// Linear sRGB (D65) <-> CIE XYZ.
constexpr double kRgbToXyz[3][3] = {{0.4124564, 0.3575761, 0.1804375},
                                    {0.2126729, 0.7151522, 0.0721750},
                                    {0.0193339, 0.1191920, 0.9503041}};
constexpr double kXyzToRgb[3][3] = {{3.2404542, -1.5371385, -0.4985314},
                                    {-0.9692660, 1.8760108, 0.0415560},
                                    {0.0556434, -0.2040259, 1.0572252}};
// Reference white: XYZ of RGB (1, 1, 1), so white has L* = 100 and no chroma.
constexpr double kWhite[3] = {0.4124564 + 0.3575761 + 0.1804375, 0.2126729 + 0.7151522 + 0.0721750,
                              0.0193339 + 0.1191920 + 0.9503041};

using Planes = std::array<std::vector<double>, 3>;

void mul3(const double m[3][3], const double in[3], double out[3]) {
  for (int r = 0; r < 3; ++r) out[r] = m[r][0] * in[0] + m[r][1] * in[1] + m[r][2] * in[2];
}

// YCxCz: the linearized CIELAB opponent space (no cube root), where filtering is meaningful.
void rgb_to_ycxcz(const double rgb[3], double out[3]) {
  double xyz[3];
  mul3(kRgbToXyz, rgb, xyz);
  const double x = xyz[0] / kWhite[0], y = xyz[1] / kWhite[1], z = xyz[2] / kWhite[2];
  out[0] = 116.0 * y - 16.0;
  out[1] = 500.0 * (x - y);
  out[2] = 200.0 * (y - z);
}

void ycxcz_to_rgb(const double ycc[3], double rgb[3]) {
  const double y = (ycc[0] + 16.0) / 116.0;
  const double xyz[3] = {(ycc[1] / 500.0 + y) * kWhite[0], y * kWhite[1],
                         (y - ycc[2] / 200.0) * kWhite[2]};
  mul3(kXyzToRgb, xyz, rgb);
}

double lab_f(double t) {
  constexpr double d = 6.0 / 29.0;
  return t > d * d * d ? std::cbrt(t) : t / (3.0 * d * d) + 4.0 / 29.0;
}

// CIELAB with the Hunt adjustment (chroma scaled by 0.01 L*: colors look less saturated dark).
void rgb_to_hunt_lab(const double rgb[3], double out[3]) {
  double xyz[3];
  mul3(kRgbToXyz, rgb, xyz);
  const double fx = lab_f(xyz[0] / kWhite[0]), fy = lab_f(xyz[1] / kWhite[1]),
               fz = lab_f(xyz[2] / kWhite[2]);
  const double l = 116.0 * fy - 16.0;
  out[0] = l;
  out[1] = 0.01 * l * 500.0 * (fx - fy);
  out[2] = 0.01 * l * 200.0 * (fy - fz);
}

// HyAB: city-block in lightness, Euclidean in chroma.
double hyab(const double a[3], const double b[3]) {
  const double da = a[1] - b[1], db = a[2] - b[2];
  return std::abs(a[0] - b[0]) + std::sqrt(da * da + db * db);
}

// CSF filtering of one opponent channel: the sum of its Gaussian terms, each separable, with the
// 2-D kernel normalized to sum to 1.
std::vector<double> csf_filter(const std::vector<double>& src, int w, int h, int channel,
                               double ppd) {
  const int r = static_cast<int>(std::ceil(3.0 * std::sqrt(kCsfWidestB / (2.0 * kPi * kPi)) * ppd));
  std::vector<std::vector<double>> g;
  std::vector<double> scale;
  double total = 0;
  for (const CsfTerm& t : csf(channel)) {
    std::vector<double> k(2 * r + 1);
    double sum = 0;
    for (int i = -r; i <= r; ++i) {
      const double x = i / ppd;  // degrees
      sum += k[i + r] = std::exp(-kPi * kPi * x * x / t.b);
    }
    const double amplitude = t.a * std::sqrt(kPi / t.b);
    g.push_back(k);
    scale.push_back(amplitude);
    total += amplitude * sum * sum;  // this term's 2-D kernel sum
  }
  std::vector<double> out(src.size(), 0.0);
  thread_local std::vector<double> part;  // reused: a fresh plane per call is page-faulted anew
  for (size_t t = 0; t < g.size(); ++t) {
    separable_convolve(src, w, h, g[t], g[t], FilterBorder::clamp, part);
    const double s = scale[t] / total;
    for (size_t i = 0; i < out.size(); ++i) out[i] += s * part[i];
  }
  return out;
}

// Feature kernels (1-D factors): the 2-D edge kernel is d(x) g(y), the point kernel h(x) g(y).
// Positive and negative weights of each 2-D kernel are normalized separately to sum to +1 and -1
// (paper Sec. 4.3), which scales the derivative factor and leaves g as is.
struct FeatureKernels {
  std::vector<double> g, edge, point;
};

FeatureKernels feature_kernels(double ppd) {
  const double sigma = 0.5 * kFeatureWidth * ppd;
  const int r = static_cast<int>(std::ceil(3.0 * sigma));
  FeatureKernels k;
  k.g.resize(2 * r + 1);
  k.edge.resize(2 * r + 1);
  k.point.resize(2 * r + 1);
  double g_sum = 0;
  for (int i = -r; i <= r; ++i) {
    const double x = i;
    const double g = std::exp(-x * x / (2.0 * sigma * sigma));
    k.g[i + r] = g;
    k.edge[i + r] = -x * g;
    k.point[i + r] = (x * x / (sigma * sigma) - 1.0) * g;
    g_sum += g;
  }
  auto normalize = [&](std::vector<double>& d) {
    double pos = 0, neg = 0;
    for (double v : d) (v > 0 ? pos : neg) += std::abs(v);
    for (double& v : d) v /= (v > 0 ? pos : neg) * g_sum;
  };
  normalize(k.edge);
  normalize(k.point);
  return k;
}

// Achromatic channel normalized to [0, 1] (Y / Y_white), input of the feature pipeline.
struct Prepared {
  Planes ycxcz;
  std::vector<double> y_norm;
};

Prepared prepare(const Image& im) {
  const size_t n = im.pixel_count();
  Prepared p;
  for (auto& c : p.ycxcz) c.resize(n);
  p.y_norm.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const double rgb[3] = {clamp01(im.plane(0)[i]), clamp01(im.plane(1)[i]),
                           clamp01(im.plane(2)[i])};
    double ycc[3];
    rgb_to_ycxcz(rgb, ycc);
    for (int c = 0; c < 3; ++c) p.ycxcz[c][i] = ycc[c];
    p.y_norm[i] = (ycc[0] + 16.0) / 116.0;
  }
  return p;
}

// Edge and point magnitudes of the normalized achromatic channel.
void features(const std::vector<double>& y, int w, int h, const FeatureKernels& k,
              std::vector<double>& edge, std::vector<double>& point) {
  // Reused per thread: fresh planes per call would be page-faulted anew.
  thread_local std::vector<double> ex, ey, px, py;
  separable_convolve(y, w, h, k.edge, k.g, FilterBorder::clamp, ex);
  separable_convolve(y, w, h, k.g, k.edge, FilterBorder::clamp, ey);
  separable_convolve(y, w, h, k.point, k.g, FilterBorder::clamp, px);
  separable_convolve(y, w, h, k.g, k.point, FilterBorder::clamp, py);
  edge.resize(y.size());
  point.resize(y.size());
  for (size_t i = 0; i < y.size(); ++i) {
    edge[i] = std::sqrt(ex[i] * ex[i] + ey[i] * ey[i]);
    point[i] = std::sqrt(px[i] * px[i] + py[i] * py[i]);
  }
}

}  // namespace

Image flip_map(const Image& test, const Image& reference, const FlipOptions& options) {
  if (test.width() != reference.width() || test.height() != reference.height() ||
      test.channels() < 3 || reference.channels() < 3)
    throw std::invalid_argument("flip: images differ in size or have fewer than 3 channels");
  if (!(options.pixels_per_degree > 0))
    throw std::invalid_argument("flip: pixels_per_degree must be positive");
  const int w = test.width(), h = test.height();
  const size_t n = test.pixel_count();
  const double ppd = options.pixels_per_degree;
  Image out(w, h, 1);
  if (n == 0) return out;

  const Prepared t = prepare(test), r = prepare(reference);

  // Color pipeline.
  Planes tf, rf;
  for (int c = 0; c < 3; ++c) {
    tf[c] = csf_filter(t.ycxcz[c], w, h, c, ppd);
    rf[c] = csf_filter(r.ycxcz[c], w, h, c, ppd);
  }
  // c_max: the HyAB distance between the gamut's most different pair, green and blue.
  double green[3], blue[3];
  {
    const double g_rgb[3] = {0, 1, 0}, b_rgb[3] = {0, 0, 1};
    rgb_to_hunt_lab(g_rgb, green);
    rgb_to_hunt_lab(b_rgb, blue);
  }
  const double c_max = std::pow(hyab(green, blue), kColorExponent);
  const double knee = kRemapBreak * c_max;

  // Feature pipeline.
  const FeatureKernels k = feature_kernels(ppd);
  std::vector<double> t_edge, t_point, r_edge, r_point;
  features(t.y_norm, w, h, k, t_edge, t_point);
  features(r.y_norm, w, h, k, r_edge, r_point);

  float* e = out.plane(0);
  for (size_t i = 0; i < n; ++i) {
    double t_rgb[3], r_rgb[3], t_lab[3], r_lab[3];
    const double t_ycc[3] = {tf[0][i], tf[1][i], tf[2][i]};
    const double r_ycc[3] = {rf[0][i], rf[1][i], rf[2][i]};
    ycxcz_to_rgb(t_ycc, t_rgb);
    ycxcz_to_rgb(r_ycc, r_rgb);
    for (int c = 0; c < 3; ++c) {  // filtering can leave the gamut: clamp before CIELAB
      t_rgb[c] = clamp01(t_rgb[c]);
      r_rgb[c] = clamp01(r_rgb[c]);
    }
    rgb_to_hunt_lab(t_rgb, t_lab);
    rgb_to_hunt_lab(r_rgb, r_lab);
    const double d = std::pow(hyab(t_lab, r_lab), kColorExponent);
    const double color_error =
        d < knee ? kRemapValue / knee * d
                 : std::min(1.0, kRemapValue + (d - knee) / (c_max - knee) * (1.0 - kRemapValue));

    const double feature_difference =
        std::max(std::abs(r_edge[i] - t_edge[i]), std::abs(r_point[i] - t_point[i]));
    const double feature_error =
        std::min(1.0, std::pow(feature_difference / std::sqrt(2.0), kFeatureExponent));
    e[i] =
        static_cast<float>(color_error == 0.0 ? 0.0 : std::pow(color_error, 1.0 - feature_error));
  }
  return out;
}

double flip_mean(const Image& m) {
  if (m.pixel_count() == 0) return 0.0;
  double sum = 0;
  for (size_t i = 0; i < m.pixel_count(); ++i) sum += m.plane(0)[i];
  return sum / static_cast<double>(m.pixel_count());
}

double flip(const Image& test, const Image& reference, const FlipOptions& options) {
  return flip_mean(flip_map(test, reference, options));
}

}  // namespace svgf::metrics

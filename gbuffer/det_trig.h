#pragma once
// sin and cos without libm: libm's last bits differ between platforms, and the fixtures should
// not. Argument in turns (1 turn = 360 degrees) so the reduction to an octant is exact.
#include <cmath>
#include <cstdint>

namespace svgf::gbuffer {

// sin(2 pi t) and cos(2 pi t), error well below 1e-16 (Taylor series to degree 21 on |a| <= pi/4).
inline void sincos_turns(double t, double& s, double& c) {
  const double q = std::floor(t * 4.0 + 0.5);  // nearest quarter turn
  const double a = (t * 4.0 - q) * 1.5707963267948966;
  const double a2 = a * a;
  double ps = 1.0 / 51090942171709440000.0;  // 1/21!
  double pc = 1.0 / 2432902008176640000.0;   // 1/20!
  const double inv_fact_s[] = {-1.0 / 121645100408832000.0, 1.0 / 355687428096000.0,
                               -1.0 / 1307674368000.0,      1.0 / 6227020800.0,
                               -1.0 / 39916800.0,           1.0 / 362880.0,
                               -1.0 / 5040.0,               1.0 / 120.0,
                               -1.0 / 6.0,                  1.0};
  const double inv_fact_c[] = {-1.0 / 6402373705728000.0, 1.0 / 20922789888000.0,
                               -1.0 / 87178291200.0,      1.0 / 479001600.0,
                               -1.0 / 3628800.0,          1.0 / 40320.0,
                               -1.0 / 720.0,              1.0 / 24.0,
                               -1.0 / 2.0,                1.0};
  for (int k = 0; k < 10; ++k) {
    ps = ps * a2 + inv_fact_s[k];
    pc = pc * a2 + inv_fact_c[k];
  }
  const double sa = ps * a;
  const double ca = pc;
  const int64_t quadrant = ((static_cast<int64_t>(q) % 4) + 4) % 4;
  switch (quadrant) {
    case 0: s = sa; c = ca; break;
    case 1: s = ca; c = -sa; break;
    case 2: s = -sa; c = -ca; break;
    default: s = -ca; c = sa; break;
  }
}

// Float-accuracy variant for sampling directions: Taylor series to degree 13 (error < 1e-13).
inline void sincos_turns_coarse(double t, double& s, double& c) {
  const double q = std::floor(t * 4.0 + 0.5);
  const double a = (t * 4.0 - q) * 1.5707963267948966;
  const double a2 = a * a;
  const double ps = (((((1.0 / 6227020800.0 * a2 - 1.0 / 39916800.0) * a2 + 1.0 / 362880.0) * a2 -
                       1.0 / 5040.0) * a2 + 1.0 / 120.0) * a2 - 1.0 / 6.0) * a2 + 1.0;
  const double pc = (((((1.0 / 479001600.0 * a2 - 1.0 / 3628800.0) * a2 + 1.0 / 40320.0) * a2 -
                       1.0 / 720.0) * a2 + 1.0 / 24.0) * a2 - 0.5) * a2 + 1.0;
  const double sa = ps * a;
  const int64_t quadrant = ((static_cast<int64_t>(q) % 4) + 4) % 4;
  switch (quadrant) {
    case 0: s = sa; c = pc; break;
    case 1: s = pc; c = -sa; break;
    case 2: s = -sa; c = -pc; break;
    default: s = -pc; c = sa; break;
  }
}

inline double tan_turns(double t) {
  double s, c;
  sincos_turns(t, s, c);
  return s / c;
}

}  // namespace svgf::gbuffer

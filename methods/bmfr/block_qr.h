#pragma once
// Least squares on one block of rows by a Householder QR (Golub & Van Loan, Alg. 5.2.1; the
// BMFR authors' fitter): min_w || F w - c || for each right-hand side c, F: kRows x F columns.
// The columns live in a block's scratch (core/block_reduce.h), column k at a + k * kRows, the
// right-hand sides after the F columns. Reflections zero each column below its pivot and are
// applied to the later columns and the right-hand sides, leaving R on top (R's diagonal
// written into the pivot rows) and Q^T c beside it; back-substitution gives the weights.
// A column whose norm left on the pivot rows is at most sqrt(keep2) times the largest column
// norm is numerically dependent on the columns before it (the numerical-rank rule
// |R_ii| <= tol max_j |a_j|, Golub & Van Loan Sec. 5.4): it is skipped (weight 0) and the next
// column takes its pivot row, so R stays triangular on the kept columns and max/min |R_ii| stays
// under about 1 / tol. Every sum runs the block's fixed tree.
#include "core/block_reduce.h"
#include "core/hd.h"
#include "core/vec.h"

namespace svgf {

// What a fit found: the columns kept, and max |R_ii| / min |R_ii| over them (a lower bound of
// R's condition number in the 2-norm; 0 when nothing was kept).
struct BlockFit {
  int rank = 0;
  float condition = 0.f;
};

template <int kF, int kC>
struct BlockLeastSquares {
  static constexpr int kColumns = kF + kC;

  // Factors and solves; weights[k * kC + c] (written by one thread) for column k and right-hand
  // side c. Returns the rank and the condition estimate, on every thread.
  SVGF_HD_TEMPLATE
  template <class Arith, class Block>
  SVGF_HD static BlockFit solve(const Block& blk, float* a, float keep2, float* weights) {
    // Every column's squared norm in one reduction; the largest sets the numerical-rank floor.
    float norm2[kF];
    blk.template reduce<kF>(block::SumOp{}, kF, [&](int r, int k) {
      const float x = a[k * block::kRows + r];
      return x * x;
    }, norm2);
    float largest2 = 0.f;
    for (int k = 0; k < kF; ++k) largest2 = max_f(largest2, norm2[k]);
    const float floor2 = keep2 * largest2;
    int kept[kF];
    int rank = 0;
    for (int j = 0; j < kF; ++j) {
      const int p = rank;  // the pivot row
      float* const v = a + j * block::kRows;
      const float below = blk.sum([&](int r) { return r > p ? v[r] * v[r] : 0.f; });
      const float x0 = v[p];
      const float left2 = below + x0 * x0;
      if (!(left2 > floor2) || !(left2 > kTiny)) continue;  // skipped
      const float norm = Arith::sqrt(left2);
      const float alpha = x0 > 0.f ? -norm : norm;  // the sign that avoids cancellation in u0
      const float u0 = x0 - alpha;  // u = (u0, v[p + 1], ...): H = I - 2 u u^T / |u|^2
      const auto per_u2 = Arith::divide_by(below + u0 * u0);
      // u . w for every later column w in one reduction (H acts on each column alone, so all
      // are taken before any changes), then w -= (2 u . w / |u|^2) u on the pivot rows.
      constexpr int kLater = kColumns - 1;
      const int later = kColumns - 1 - j;
      float f[kLater];
      blk.template reduce<kLater>(block::SumOp{}, later, [&](int r, int m) {
        const float* w = a + (j + 1 + m) * block::kRows;
        return r < p ? 0.f : (r == p ? u0 : v[r]) * w[r];
      }, f);
      SVGF_UNROLL
      for (int m = 0; m < kLater; ++m)
        if (m < later) f[m] = per_u2(f[m] + f[m]);
      blk.rows([&](int r) {
        if (r < p) return;
        const float u = r == p ? u0 : v[r];
        SVGF_UNROLL
        for (int m = 0; m < kLater; ++m) {
          if (m >= later) break;
          float* const w = a + (j + 1 + m) * block::kRows;
          w[r] = Arith::mad(-u, f[m], w[r]);
        }
        if (r == p) v[p] = alpha;  // R's diagonal (v below p keeps u, unused from here)
      });
      kept[rank++] = j;
    }
    BlockFit fit;
    fit.rank = rank;
    if (rank > 0) {
      float lo = abs_f(a[kept[0] * block::kRows]), hi = lo;
      for (int i = 1; i < rank; ++i) {
        const float d = abs_f(a[kept[i] * block::kRows + i]);
        lo = min_f(lo, d);
        hi = max_f(hi, d);
      }
      fit.condition = hi / lo;
    }
    // R w = (Q^T c) on the kept columns: R[i][k] = a[k][i], (Q^T c)[i] = a[kF + c][i].
    blk.once([&] {
      for (int k = 0; k < kF * kC; ++k) weights[k] = 0.f;
      for (int i = rank - 1; i >= 0; --i) {
        const int j = kept[i];
        for (int c = 0; c < kC; ++c) {
          float s = a[(kF + c) * block::kRows + i];
          for (int m = i + 1; m < rank; ++m)
            s = s - a[kept[m] * block::kRows + i] * weights[kept[m] * kC + c];
          weights[j * kC + c] = s / a[j * block::kRows + i];
        }
      }
    });
    return fit;
  }

  // Under this a column's squared norm is zero for the reflection (|u|^2 would underflow).
  static constexpr float kTiny = 1e-30f;
};

}  // namespace svgf

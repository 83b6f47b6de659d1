// BMFR (methods/bmfr/, Koskela et al. 2019): the block reductions' fixed tree, the block least
// squares against a known factorization and a float64 solution (well-conditioned, exactly
// explained and rank-deficient matrices), the moving block grid, the pipeline on a block its
// features explain exactly and on flat walls, determinism and the interface. Every device body
// runs on the CPU, CUDA exact (bitwise against the CPU) and CUDA fast (tests/test_device.h).
#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/block_reduce.h"
#include "methods/bmfr/block_qr.h"
#include "methods/bmfr/blocks.h"
#include "methods/bmfr/denoiser.h"
#include "metrics/image_metrics.h"
#include "pipeline/make_denoiser.h"
#include "synthetic_sequence.h"
#include "test_device.h"
#include "test_support.h"

using namespace svgf;
using svgf::test::StageRunner;
using svgf::test::TestDevice;
using svgf::test::with_arith;

// The test's block kernels: in a named namespace, since nvcc cannot instantiate a __global__
// template on a type with internal linkage.
namespace svgf::bmfr_test {

constexpr int kRows = block::kRows;

// sum, min and max of each block's 1024 values; then three sums at once (reduce<4> with 3
// values: v, v * v and v - 1).
struct ReduceKernel {
  static constexpr int kScratchFloats = 1;
  static constexpr int kOut = 6;
  const float* in = nullptr;  // kRows per block
  float* out = nullptr;       // kOut per block
  SVGF_HD static float value(float v, int k) { return k == 0 ? v : (k == 1 ? v * v : v - 1.f); }
  SVGF_HD_TEMPLATE
  template <class Block>
  SVGF_HD void operator()(const Block& blk, int b) const {
    const float* v = in + b * kRows;
    const float s = blk.sum([&](int r) { return v[r]; });
    const float lo = blk.min([&](int r) { return v[r]; });
    const float hi = blk.max([&](int r) { return v[r]; });
    float many[4];
    blk.template reduce<4>(block::SumOp{}, 3, [&](int r, int k) { return value(v[r], k); }, many);
    blk.once([&] {
      out[kOut * b] = s;
      out[kOut * b + 1] = lo;
      out[kOut * b + 2] = hi;
      for (int k = 0; k < 3; ++k) out[kOut * b + 3 + k] = many[k];
    });
  }
};

void block_reductions_follow_the_tree(const TestDevice& d) {
  const int blocks = 5;
  Image in(kRows, blocks, 1), out(ReduceKernel::kOut, blocks, 1);
  test::fill_uniform(in, -1000.f, 1000.f, 7);
  in.at(17, 2, 0) = 1e-30f;  // magnitudes far apart: the order shows in the bits
  in.at(900, 3, 0) = 3e7f;
  StageRunner r(d);
  r.run_blocks(ReduceKernel{r.plane(in), r.plane(out)}, blocks, "block reductions");
  for (int b = 0; b < blocks; ++b) {
    const float* v = in.plane(0) + b * kRows;
    auto at = [&](int i) { return v[i]; };
    const float tree = block::reduce_rows(at, block::SumOp{});
    double exact = 0;
    for (int i = 0; i < kRows; ++i) exact += v[i];
    INFO("block " << b << ": tree " << tree << ", float64 " << exact);
    REQUIRE(std::memcmp(&tree, &out.at(0, b, 0), 4) == 0);
    REQUIRE(std::fabs(tree - exact) <= 1e-5 * 1000 * kRows);
    REQUIRE(out.at(1, b, 0) == *std::min_element(v, v + kRows));
    REQUIRE(out.at(2, b, 0) == *std::max_element(v, v + kRows));
    // Several values in one reduction: each is its own tree, the bits of a sum of its own.
    for (int k = 0; k < 3; ++k) {
      const float one = block::reduce_rows([&](int i) { return ReduceKernel::value(v[i], k); },
                                           block::SumOp{});
      INFO("value " << k);
      REQUIRE(std::memcmp(&one, &out.at(3 + k, b, 0), 4) == 0);
    }
  }
}

// The block least squares on a matrix given column by column: in holds kF + kC rows of kRows
// (row k of the image is column k of the matrix); out gets the weights, the rank and R's rows.
template <int kF, int kC, class ArithT>
struct LeastSquaresKernel {
  using Arith = ArithT;
  static constexpr int kScratchFloats = (kF + kC) * kRows;
  const float* in = nullptr;
  float* out = nullptr;  // weights (kF * kC), rank, condition, then R: kF rows of kF + kC
  float keep2 = 0.f;
  SVGF_HD_TEMPLATE
  template <class Block>
  SVGF_HD void operator()(const Block& blk, int) const {
    float* a = blk.scratch();
    blk.rows([&](int r) {
      for (int k = 0; k < kF + kC; ++k) a[k * kRows + r] = in[k * kRows + r];
    });
    const BlockFit fit = BlockLeastSquares<kF, kC>::template solve<Arith>(blk, a, keep2, out);
    blk.once([&] {
      out[kF * kC] = static_cast<float>(fit.rank);
      out[kF * kC + 1] = fit.condition;
      for (int i = 0; i < kF; ++i)
        for (int k = 0; k < kF + kC; ++k)
          out[kF * kC + 2 + i * (kF + kC) + k] = k < i ? 0.f : a[k * kRows + i];
    });
  }
};

}  // namespace svgf::bmfr_test

namespace {

using svgf::bmfr_test::block_reductions_follow_the_tree;
using svgf::bmfr_test::ReduceKernel;
using svgf::bmfr_test::kRows;
using svgf::bmfr_test::LeastSquaresKernel;

template <int kF, int kC>
struct Solved {
  std::vector<double> w;  // kF x kC
  int rank = 0;
  double condition = 0;
  std::vector<double> r;  // kF x (kF + kC)
};

template <int kF, int kC>
Solved<kF, kC> solve_on(const TestDevice& d, const std::vector<std::vector<double>>& cols,
                        float keep2) {
  Image in(kRows, kF + kC, 1), out(kF * kC + 2 + kF * (kF + kC), 1, 1);
  for (int k = 0; k < kF + kC; ++k)
    for (int i = 0; i < kRows; ++i) in.at(i, k, 0) = static_cast<float>(cols[k][i]);
  StageRunner run(d);
  with_arith(d, [&](auto arith) {
    using A = decltype(arith);
    run.run_blocks(LeastSquaresKernel<kF, kC, A>{run.plane(in), run.plane(out), keep2}, 1,
                   "block least squares");
  });
  Solved<kF, kC> s;
  for (int k = 0; k < kF * kC; ++k) s.w.push_back(out.at(k, 0, 0));
  s.rank = static_cast<int>(out.at(kF * kC, 0, 0));
  s.condition = out.at(kF * kC + 1, 0, 0);
  for (int k = 0; k < kF * (kF + kC); ++k) s.r.push_back(out.at(kF * kC + 2 + k, 0, 0));
  return s;
}

// Least squares in float64 through the normal equations (Cholesky), on the columns `use`.
std::vector<double> float64_least_squares(const std::vector<std::vector<double>>& cols,
                                          const std::vector<int>& use, int rhs) {
  const int n = static_cast<int>(use.size());
  std::vector<double> g(n * n), b(n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j)
      for (int r = 0; r < kRows; ++r) g[i * n + j] += cols[use[i]][r] * cols[use[j]][r];
    for (int r = 0; r < kRows; ++r) b[i] += cols[use[i]][r] * cols[rhs][r];
  }
  for (int j = 0; j < n; ++j) {  // G = L L^T in place
    for (int k = 0; k < j; ++k) g[j * n + j] -= g[j * n + k] * g[j * n + k];
    g[j * n + j] = std::sqrt(g[j * n + j]);
    for (int i = j + 1; i < n; ++i) {
      for (int k = 0; k < j; ++k) g[i * n + j] -= g[i * n + k] * g[j * n + k];
      g[i * n + j] /= g[j * n + j];
    }
  }
  for (int i = 0; i < n; ++i) {
    for (int k = 0; k < i; ++k) b[i] -= g[i * n + k] * b[k];
    b[i] /= g[i * n + i];
  }
  for (int i = n - 1; i >= 0; --i) {
    for (int k = i + 1; k < n; ++k) b[i] -= g[k * n + i] * b[k];
    b[i] /= g[i * n + i];
  }
  return b;
}

// |F^T (c - F w)| / (|F| |c|): 0 at the least-squares optimum.
double optimality(const std::vector<std::vector<double>>& cols, int features, int rhs,
                  const std::vector<double>& w, int kc, int c) {
  std::vector<double> res(kRows);
  double fn = 0, cn = 0;
  for (int r = 0; r < kRows; ++r) {
    double fit = 0;
    for (int k = 0; k < features; ++k) fit += cols[k][r] * w[k * kc + c];
    res[r] = cols[rhs][r] - fit;
    cn += cols[rhs][r] * cols[rhs][r];
  }
  double worst = 0;
  for (int k = 0; k < features; ++k) {
    double dot = 0, kn = 0;
    for (int r = 0; r < kRows; ++r) dot += cols[k][r] * res[r], kn += cols[k][r] * cols[k][r];
    fn = std::max(fn, kn);
    worst = std::max(worst, std::fabs(dot));
  }
  return worst / std::sqrt(fn * cn);
}

// Walsh function k on the 1024 rows, normalized: columns exactly orthonormal.
double walsh(int k, int r) { return (__builtin_popcount(k & r) % 2 ? -1.0 : 1.0) / 32.0; }

void least_squares_known_factorization(const TestDevice& d) {
  // A = Q R with Q orthonormal (Walsh columns) and R given: the QR finds R up to the sign of
  // each row, and the weights of c = A w_true.
  const double r_true[3][3] = {{2.0, 1.0, -1.0}, {0.0, 3.0, 0.5}, {0.0, 0.0, -1.5}};
  const double w_true[3] = {0.5, -2.0, 1.25};
  std::vector<std::vector<double>> cols(4, std::vector<double>(kRows));
  for (int r = 0; r < kRows; ++r) {
    for (int k = 0; k < 3; ++k)
      for (int i = 0; i <= k; ++i) cols[k][r] += walsh(3 * i + 1, r) * r_true[i][k];
    for (int k = 0; k < 3; ++k) cols[3][r] += cols[k][r] * w_true[k];
  }
  const auto s = solve_on<3, 1>(d, cols, 0.f);
  REQUIRE(s.rank == 3);
  for (int i = 0; i < 3; ++i) {
    const double sign = s.r[i * 4 + i] * r_true[i][i] > 0 ? 1.0 : -1.0;
    for (int k = i; k < 3; ++k) {
      INFO("R[" << i << "][" << k << "] " << s.r[i * 4 + k] << ", expected " << sign * r_true[i][k]);
      REQUIRE(std::fabs(s.r[i * 4 + k] - sign * r_true[i][k]) <= d.tolerance(2e-6) * 3);
    }
  }
  for (int k = 0; k < 3; ++k) REQUIRE(std::fabs(s.w[k] - w_true[k]) <= d.tolerance(1e-5) * 2);
  REQUIRE(s.condition == Approx(3.0 / 1.5).epsilon(1e-5));  // max |R_ii| / min |R_ii|
}

void least_squares_against_float64(const TestDevice& d) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  constexpr int kF = 10, kC = 3;
  for (int trial = 0; trial < 3; ++trial) {
    INFO("trial " << trial);
    // Random features (the first constant), right-hand sides a combination plus noise.
    std::vector<std::vector<double>> cols(kF + kC, std::vector<double>(kRows));
    for (int r = 0; r < kRows; ++r) {
      cols[0][r] = 1.0;
      for (int k = 1; k < kF; ++k) cols[k][r] = static_cast<float>(u(rng) + 0.3 * cols[k - 1][r]);
      for (int c = 0; c < kC; ++c) {
        double v = 0.2 * u(rng);
        for (int k = 0; k < kF; ++k) v += cols[k][r] * (0.1 * (k + 1) * (c + 1) - 0.4);
        cols[kF + c][r] = static_cast<float>(v);
      }
    }
    const auto s = solve_on<kF, kC>(d, cols, 0.f);
    REQUIRE(s.rank == kF);
    std::vector<int> all(kF);
    for (int k = 0; k < kF; ++k) all[k] = k;
    for (int c = 0; c < kC; ++c) {
      const std::vector<double> ref = float64_least_squares(cols, all, kF + c);
      for (int k = 0; k < kF; ++k) {
        INFO("channel " << c << ", weight " << k << ": " << s.w[k * kC + c] << " vs float64 "
                        << ref[k]);
        REQUIRE(std::fabs(s.w[k * kC + c] - ref[k]) <= d.tolerance(2e-5) * 5 * (1 + std::fabs(ref[k])));
      }
      REQUIRE(optimality(cols, kF, kF + c, s.w, kC, c) <= d.tolerance(1e-5) * 5);
    }
  }
}

void least_squares_exact_and_rank_deficient(const TestDevice& d) {
  constexpr int kF = 10, kC = 1;
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<std::vector<double>> cols(kF + kC, std::vector<double>(kRows));
  for (int r = 0; r < kRows; ++r) {
    cols[0][r] = 1.0;
    for (int k = 1; k < kF; ++k) cols[k][r] = static_cast<float>(u(rng));
  }
  SECTION("a right-hand side the features explain exactly is reproduced to rounding") {
    const double w_true[kF] = {0.3, -0.2, 0.5, 0.1, 0.7, -0.4, 0.25, 0.05, -0.15, 0.6};
    double cn = 0;
    for (int r = 0; r < kRows; ++r) {
      double v = 0;
      for (int k = 0; k < kF; ++k) v += cols[k][r] * w_true[k];
      cols[kF][r] = static_cast<float>(v);
      cn += v * v;
    }
    const auto s = solve_on<kF, kC>(d, cols, 0.f);
    double worst = 0;
    for (int r = 0; r < kRows; ++r) {
      double fit = 0;
      for (int k = 0; k < kF; ++k) fit += cols[k][r] * s.w[k];
      worst = std::max(worst, std::fabs(fit - cols[kF][r]));
    }
    INFO("largest residual " << worst << " against values of rms " << std::sqrt(cn / kRows));
    REQUIRE(worst <= d.tolerance(1e-5) * 10);
  }
  SECTION("dependent and zero columns are skipped with weight 0, the fit stays optimal") {
    for (int r = 0; r < kRows; ++r) {
      cols[3][r] = cols[1][r];                            // a repeat
      cols[6][r] = 0.0;                                   // a zero column
      cols[8][r] = static_cast<float>(2 * cols[2][r] - cols[0][r]);  // a combination
      cols[kF][r] = static_cast<float>(0.4 + 0.9 * cols[1][r] - 0.3 * cols[5][r] + 0.05 * u(rng));
    }
    const auto s = solve_on<kF, kC>(d, cols, 1e-6f);
    REQUIRE(s.rank == 7);
    REQUIRE(std::isfinite(s.condition));
    REQUIRE(s.condition >= 1.0);
    REQUIRE(s.w[3] == 0.f);
    REQUIRE(s.w[6] == 0.f);
    REQUIRE(s.w[8] == 0.f);
    for (double w : s.w) REQUIRE(std::isfinite(w));
    REQUIRE(optimality(cols, kF, kF, s.w, kC, 0) <= d.tolerance(1e-5) * 5);
  }
}

TEST_CASE("bmfr: the block grid moves every frame and covers the image", "[bmfr]") {
  std::set<std::pair<int, int>> origins;
  for (int frame = 0; frame < 16; ++frame) {
    for (const auto& size : {std::pair<int, int>{128, 48}, {33, 70}, {5, 3}, {1920, 1080}}) {
      const BmfrGrid g = BmfrGrid::of(size.first, size.second, frame);
      INFO("frame " << frame << ", " << size.first << "x" << size.second);
      REQUIRE(g.origin_x <= 0);
      REQUIRE(g.origin_y <= 0);
      REQUIRE(g.origin_x >= -bmfr::kBlockSize);
      // Every pixel is row `r` of exactly one block, and that row maps back to it.
      for (int y = 0; y < size.second; y += (size.second > 100 ? 37 : 1))
        for (int x = 0; x < size.first; x += (size.first > 100 ? 41 : 1)) {
          const int b = g.block_of(x, y);
          REQUIRE(b >= 0);
          REQUIRE(b < g.blocks());
          const int r = (y - g.origin_y) % bmfr::kBlockSize * bmfr::kBlockSize +
                        (x - g.origin_x) % bmfr::kBlockSize;
          REQUIRE(g.row_inside(b, r));
          REQUIRE(g.pixel_of(b, r) == y * size.first + x);
        }
      // Rows outside the image are mirrored in.
      for (int b = 0; b < g.blocks(); ++b)
        for (int r = 0; r < kRows; r += 31) {
          const int i = g.pixel_of(b, r);
          REQUIRE(i >= 0);
          REQUIRE(i < size.first * size.second);
        }
    }
    const BmfrGrid g = BmfrGrid::of(128, 48, frame);
    origins.insert({g.origin_x, g.origin_y});
  }
  REQUIRE(origins.size() == 16);  // 16 different grids: the seams move
  REQUIRE(BmfrGrid::of(64, 64, 3).origin_x == BmfrGrid::of(64, 64, 19).origin_x);
  REQUIRE(BmfrGrid::mirror(-1, 5) == 0);
  REQUIRE(BmfrGrid::mirror(-2, 5) == 1);
  REQUIRE(BmfrGrid::mirror(5, 5) == 4);
  REQUIRE(BmfrGrid::mirror(-7, 3) == 0);  // twice reflected
}

std::unique_ptr<Denoiser> bmfr_on(const TestDevice& d, const BmfrParams& p, int threads = 2) {
  DenoiserConfig c = d.config(DenoiserConfig());
  c.method = Method::Bmfr;
  c.threads = threads;
  c.bmfr = p;
  return make_denoiser(c);
}

// A tilted, bumpy wall whose color (albedo 1, no emission) is a combination of its features.
Frame explained_frame(int w, int h) {
  Frame f = test::flat_frame(w, h, 2.f, 1.f);
  f.position = Image(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float px = 0.05f * x, py = 0.04f * y, pz = 0.3f * std::sin(0.2f * x) + 0.01f * y;
      const float nx = 0.3f * std::cos(0.3f * y), ny = 0.2f * std::sin(0.25f * x);
      const float len = std::sqrt(nx * nx + ny * ny + 1.f);
      f.position.at(x, y, 0) = px;
      f.position.at(x, y, 1) = py;
      f.position.at(x, y, 2) = pz;
      f.normal.at(x, y, 0) = nx / len;
      f.normal.at(x, y, 1) = ny / len;
      f.normal.at(x, y, 2) = 1.f / len;
      const float v = 0.3f + 0.2f * f.normal.at(x, y, 0) + 0.1f * px + 0.05f * pz * pz;
      for (int c = 0; c < 3; ++c) f.color.at(x, y, c) = v * (1.f + 0.2f * c);
    }
  return f;
}

void explained_block_reproduced(const TestDevice& d) {
  BmfrParams p;
  p.rank_strategy = BmfrRankStrategy::Skip;
  p.skip_threshold = 1e-5f;
  const Frame f = explained_frame(70, 40);
  auto den = bmfr_on(d, p);
  Image out;
  den->denoise(f, out);
  const Image filtered = den->read_buffer(bmfr_buffer::kFiltered);
  const double worst = test::max_relative_difference(filtered, f.color, 1e-2);
  INFO("worst relative difference of the fit " << worst);
  REQUIRE(worst <= d.tolerance(2e-4) * 5);
  // The paper's noise keeps it close too (features moved by +-0.01).
  auto noisy = bmfr_on(d, BmfrParams());
  noisy->denoise(f, out);
  REQUIRE(metrics::psnr(noisy->read_buffer(bmfr_buffer::kFiltered), f.color) > 40.0);
}

void flat_walls_stay_finite(const TestDevice& d) {
  // One normal, one depth plane: n.xyz repeat the constant feature, p.z and p.z^2 are constant.
  Frame f = test::flat_frame(80, 50, 2.f, 0.5f);
  f.position = Image(80, 50, 3);
  for (int y = 0; y < 50; ++y)
    for (int x = 0; x < 80; ++x) {
      f.position.at(x, y, 0) = 0.02f * x;
      f.position.at(x, y, 1) = 0.02f * y;
      f.position.at(x, y, 2) = 3.f;
    }
  test::fill_uniform(f.color, 0.f, 1.f, 4);
  for (int y = 20; y < 30; ++y)  // and a hole without a surface
    for (int x = 10; x < 40; ++x) f.depth.at(x, y, 0) = 0.f;
  for (BmfrRankStrategy s : {BmfrRankStrategy::Noise, BmfrRankStrategy::Skip}) {
    BmfrParams p;
    p.rank_strategy = s;
    auto den = bmfr_on(d, p);
    for (int k = 0; k < 3; ++k) {
      Image out;
      den->denoise(f, out);
      INFO(to_string(s) << ", frame " << k);
      for (float v : out.data()) REQUIRE(std::isfinite(v));
      // The fit of uniform noise on a flat wall is close to its mean, 0.5 (demodulated 1, times
      // the albedo 0.5).
      REQUIRE(std::fabs(out.at(70, 5, 0) - 0.5f) < 0.05f);
      const Image rank = den->read_buffer(bmfr_buffer::kRank);
      const float most = *std::max_element(rank.data().begin(), rank.data().end());
      // Skip keeps 1, p.x, p.y, p.x^2, p.y^2: the normals repeat the constant, p.z is constant.
      REQUIRE(most == (s == BmfrRankStrategy::Noise ? 10.f : 5.f));
      const Image condition = den->read_buffer(bmfr_buffer::kCondition);
      for (float c : condition.data()) {
        REQUIRE(std::isfinite(c));
        REQUIRE(c >= 1.f);
      }
    }
  }
}

// A block with no sample (every surface pixel's albedo under the epsilon) has nothing to fit:
// its surface pixels keep the pre-accumulated color and are counted as fallback pixels, the
// count the grid predicts (a block has a sample when any of its rows, mirrored in, is one).
void empty_blocks_fall_back_and_are_counted(const TestDevice& d) {
  const int w = 100, h = 70;
  Frame f = explained_frame(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (x < 60 || y < 20)
        for (int c = 0; c < 3; ++c) f.albedo.at(x, y, c) = 0.f;
  for (int y = 40; y < 50; ++y)  // some background among them
    for (int x = 5; x < 25; ++x) f.depth.at(x, y, 0) = 0.f;
  const auto is_sample = [&](int i) {
    return f.depth.plane(0)[i] > 0.f && f.albedo.plane(0)[i] > 0.f;
  };
  auto den = bmfr_on(d, BmfrParams());
  for (int frame = 0; frame < 3; ++frame) {
    Image out;
    den->denoise(f, out);
    const BmfrGrid grid = BmfrGrid::of(w, h, frame);
    std::vector<bool> has_sample(static_cast<size_t>(grid.blocks()), false);
    for (int b = 0; b < grid.blocks(); ++b)
      for (int r = 0; r < block::kRows; ++r)
        if (is_sample(grid.pixel_of(b, r))) has_sample[static_cast<size_t>(b)] = true;
    const Image noisy = den->read_buffer(bmfr_buffer::kNoisy);
    const Image filtered = den->read_buffer(bmfr_buffer::kFiltered);
    int64_t expected = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        if (!(f.depth.at(x, y, 0) > 0.f) || has_sample[static_cast<size_t>(grid.block_of(x, y))])
          continue;
        ++expected;
        for (int c = 0; c < 3; ++c) REQUIRE(filtered.at(x, y, c) == noisy.at(x, y, c));
      }
    INFO("frame " << frame);
    REQUIRE(expected > 500);  // the test means something: several empty blocks
    REQUIRE(den->last_report().fallback_pixels == expected);
    for (float v : out.data()) REQUIRE(std::isfinite(v));
  }
  auto clean = bmfr_on(d, BmfrParams());
  Image out;
  clean->denoise(explained_frame(w, h), out);
  REQUIRE(clean->last_report().fallback_pixels == 0);
}

// With TAA the frame's output is the TAA stage's: the first frame (and the first after a reset)
// passes through it, so it is the output without TAA bit for bit; later frames differ from it
// and stay finite, and the post-accumulation history (accumulated) is TAA's input, not its
// output, so it stays the one without TAA.
void taa_is_the_last_stage(const TestDevice& d) {
  test::SyntheticScene scene;
  BmfrParams with;
  with.taa = true;
  auto plain = bmfr_on(d, BmfrParams()), taa = bmfr_on(d, with);
  REQUIRE(taa->stages().back() == "taa");
  for (int k = 0; k < 5; ++k) {
    if (k == 3) {
      plain->reset();
      taa->reset();
    }
    const Frame f = scene.frame(k);
    Image a, b;
    plain->denoise(f, a);
    taa->denoise(f, b);
    INFO("frame " << k);
    for (float v : b.data()) REQUIRE(std::isfinite(v));
    test::require_identical(plain->read_buffer(bmfr_buffer::kAccumulated),
                            taa->read_buffer(bmfr_buffer::kAccumulated), "accumulated");
    if (k == 0 || k == 3)
      test::require_identical(a, b, "the first frame of a history passes through TAA");
    else
      REQUIRE(test::max_relative_difference(a, b, 1e-3) > 1e-4);
  }
}

}  // namespace

SVGF_DEVICE_TEST("bmfr: block sums, minima and maxima follow the fixed tree", "[bmfr]",
                 block_reductions_follow_the_tree)
SVGF_DEVICE_TEST("bmfr: least squares finds a known QR factorization", "[bmfr]",
                 least_squares_known_factorization)
SVGF_DEVICE_TEST("bmfr: least squares against float64 on well-conditioned matrices", "[bmfr]",
                 least_squares_against_float64)
SVGF_DEVICE_TEST("bmfr: least squares, exactly explained and rank-deficient", "[bmfr]",
                 least_squares_exact_and_rank_deficient)
SVGF_DEVICE_TEST("bmfr: a block whose color its features explain is reproduced", "[bmfr]",
                 explained_block_reproduced)
SVGF_DEVICE_TEST("bmfr: flat walls (rank-deficient blocks) give finite output", "[bmfr]",
                 flat_walls_stay_finite)
SVGF_DEVICE_TEST("bmfr: TAA (--bmfr-taa) is the last stage; the first frame passes through",
                 "[bmfr][taa]", taa_is_the_last_stage)
SVGF_DEVICE_TEST("bmfr: blocks with nothing to fit keep the accumulated color and are counted",
                 "[bmfr]", empty_blocks_fall_back_and_are_counted)

TEST_CASE("bmfr: same bits on 1 and 2 threads; stages, defaults and errors", "[bmfr]") {
  test::SyntheticScene scene;
  auto one = bmfr_on(test::kCpu, BmfrParams(), 1), two = bmfr_on(test::kCpu, BmfrParams(), 2);
  for (int k = 0; k < 4; ++k) {
    const Frame f = scene.frame(k);
    Image a, b;
    one->denoise(f, a);
    two->denoise(f, b);
    test::require_identical(a, b, "1 vs 2 threads, frame " + std::to_string(k));
    test::require_identical(one->read_buffer(bmfr_buffer::kRank),
                            two->read_buffer(bmfr_buffer::kRank), "block ranks");
    test::require_identical(one->read_buffer(bmfr_buffer::kCondition),
                            two->read_buffer(bmfr_buffer::kCondition), "block conditions");
  }
  REQUIRE(two->stages() == std::vector<std::string>{"sanitize", "accumulate", "regression",
                                                    "weighted_sum", "post"});
  // The authors' defaults (bmfr.cpp, docs/bmfr.md).
  const BmfrParams p;
  REQUIRE(p.pre_alpha == 0.2f);
  REQUIRE(p.post_alpha == 0.1f);
  REQUIRE(p.position_limit_sq == 0.01f);
  REQUIRE(p.normal_limit_sq == 1.f);
  REQUIRE(p.noise_amount == 0.01f);
  REQUIRE(p.rank_strategy == BmfrRankStrategy::Noise);
  REQUIRE(parse_method("bmfr") == Method::Bmfr);
  REQUIRE(parse_bmfr_rank_strategy("skip") == BmfrRankStrategy::Skip);
  REQUIRE_THROWS_WITH(parse_bmfr_rank_strategy("qr"), Catch::Contains("--bmfr-rank"));
  auto bad = [](auto change) {
    BmfrParams q;
    change(q);
    return bmfr_on(test::kCpu, q);
  };
  REQUIRE_THROWS_WITH(bad([](BmfrParams& q) { q.pre_alpha = 0.f; }), Catch::Contains("--bmfr-pre-alpha"));
  REQUIRE_THROWS_WITH(bad([](BmfrParams& q) { q.post_alpha = 2.f; }), Catch::Contains("--bmfr-post-alpha"));
  REQUIRE_THROWS_WITH(bad([](BmfrParams& q) { q.position_limit_sq = NAN; }), Catch::Contains("--bmfr-position-limit"));
  REQUIRE_THROWS_WITH(bad([](BmfrParams& q) { q.normal_limit_sq = -1.f; }), Catch::Contains("--bmfr-normal-limit"));
  REQUIRE_THROWS_WITH(bad([](BmfrParams& q) { q.noise_amount = -0.1f; }), Catch::Contains("--bmfr-noise"));
  REQUIRE_THROWS_WITH(bad([](BmfrParams& q) { q.skip_threshold = 1.f; }), Catch::Contains("--bmfr-skip-threshold"));
  REQUIRE_THROWS_WITH(bad([](BmfrParams& q) { q.taa_alpha = 0.f; }), Catch::Contains("--bmfr-taa-alpha"));
  REQUIRE(p.taa == false);
  REQUIRE(p.taa_alpha == 0.2f);  // TAA_BLEND_ALPHA
  Frame no_position = scene.frame(0);
  no_position.position = Image();
  Image out;
  REQUIRE_THROWS_WITH(bmfr_on(test::kCpu, p)->denoise(no_position, out), Catch::Contains("position"));
  REQUIRE_THROWS_WITH(two->read_buffer("weights"), Catch::Contains("block_rank"));
}

TEST_CASE("bmfr: the history follows motion and is dropped where positions disagree",
          "[bmfr]") {
  // A static wall: the history length grows by one a frame (capped at 255); after reset() it
  // starts again; a pixel whose world position jumps loses its history.
  Frame f = explained_frame(48, 40);
  auto den = bmfr_on(test::kCpu, BmfrParams());
  Image out;
  for (int k = 0; k < 3; ++k) den->denoise(f, out);
  REQUIRE(den->read_buffer(bmfr_buffer::kLength).at(20, 20, 0) == 3.f);
  f.position.at(20, 20, 2) += 1.f;
  den->denoise(f, out);
  const Image length = den->read_buffer(bmfr_buffer::kLength);
  REQUIRE(length.at(20, 20, 0) == 1.f);
  REQUIRE(length.at(30, 20, 0) == 4.f);
  den->reset();
  den->denoise(f, out);
  REQUIRE(den->read_buffer(bmfr_buffer::kLength).at(30, 20, 0) == 1.f);
}

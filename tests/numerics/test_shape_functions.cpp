#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <type_traits>
#include <vector>

#include "numerics/shape_functions.hpp"

namespace unsatmpm::numerics {
namespace test_shape_functions {

template <int D>
Grid<D> test_grid() {
  Vec<D> origin = Vec<D>::Constant(-0.3), spacing;
  std::array<int, D> cells;
  for (int d = 0; d < D; ++d) spacing[d] = 0.1 + 0.05 * d, cells[d] = 6 + d;
  return Grid<D>(origin, spacing, cells);
}

/// A random point whose GIMP support stays inside the grid.
template <int D>
Vec<D> random_point(const Grid<D>& g, const Vec<D>& half, std::mt19937& rng) {
  Vec<D> x;
  for (int d = 0; d < D; ++d) {
    std::uniform_real_distribution<double> u(g.origin[d] + half[d], g.upper()[d] - half[d]);
    x[d] = u(rng);
  }
  return x;
}

template <int D, class K>
void check_partition_of_unity_and_gradients() {
  const auto g = test_grid<D>();
  const Vec<D> half = g.spacing / 4.0;  // 2 points per cell
  std::mt19937 rng(42);
  PointStencil<D, K> st, plus, minus;
  for (int trial = 0; trial < 200; ++trial) {
    const Vec<D> x = random_point<D>(g, half, rng);
    st.evaluate(g, x, half);
    double sum_w = 0.0;
    Vec<D> sum_grad = Vec<D>::Zero(), first_moment = Vec<D>::Zero();
    Eigen::Matrix<double, D, D> grad_moment = Eigen::Matrix<double, D, D>::Zero();
    for (int a = 0; a < st.n; ++a) {
      EXPECT_GE(st.w[a], -1e-14);
      sum_w += st.w[a];
      sum_grad += st.grad[a];
      first_moment += st.w[a] * g.node_position(st.node[a]);
      grad_moment += g.node_position(st.node[a]) * st.grad[a].transpose();
    }
    EXPECT_NEAR(sum_w, 1.0, 1e-12);               // partition of unity
    EXPECT_LT(sum_grad.norm(), 1e-10);            // gradients sum to zero
    EXPECT_LT((first_moment - x).norm(), 1e-12);  // linear fields are reproduced
    EXPECT_LT((grad_moment - Eigen::Matrix<double, D, D>::Identity()).norm(), 1e-10);
    // Gradients against central differences of the weights.
    for (int d = 0; d < D; ++d) {
      const double eps = 1e-7 * g.spacing[d];
      Vec<D> xp = x, xm = x;
      xp[d] += eps, xm[d] -= eps;
      plus.evaluate(g, xp, half);
      minus.evaluate(g, xm, half);
      for (int a = 0; a < st.n; ++a) {
        if (plus.node[a] != st.node[a] || minus.node[a] != st.node[a]) continue;  // crossed a cell
        EXPECT_NEAR((plus.w[a] - minus.w[a]) / (2 * eps), st.grad[a][d], 1e-5 / g.spacing[d]);
      }
    }
  }
}

TEST(ShapeFunctions, LinearPartitionOfUnityAndGradients1D) {
  check_partition_of_unity_and_gradients<1, LinearKernel>();
}
TEST(ShapeFunctions, LinearPartitionOfUnityAndGradients2D) {
  check_partition_of_unity_and_gradients<2, LinearKernel>();
}
TEST(ShapeFunctions, LinearPartitionOfUnityAndGradients3D) {
  check_partition_of_unity_and_gradients<3, LinearKernel>();
}
TEST(ShapeFunctions, GimpPartitionOfUnityAndGradients1D) {
  check_partition_of_unity_and_gradients<1, GimpKernel>();
}
TEST(ShapeFunctions, GimpPartitionOfUnityAndGradients2D) {
  check_partition_of_unity_and_gradients<2, GimpKernel>();
}
TEST(ShapeFunctions, GimpPartitionOfUnityAndGradients3D) {
  check_partition_of_unity_and_gradients<3, GimpKernel>();
}

// GIMP's point of existence: weights are C1 across a cell face, where linear gradients jump.
TEST(ShapeFunctions, GimpIsContinuousAcrossCellFaces) {
  const double h = 0.1, lp = 0.025;
  for (double r : {0.0, lp, h - lp, h, h + lp}) {
    double w1, dw1, w2, dw2;
    GimpKernel::node_weight(r - 1e-10, h, lp, w1, dw1);
    GimpKernel::node_weight(r + 1e-10, h, lp, w2, dw2);
    EXPECT_NEAR(w1, w2, 1e-8) << "r = " << r;
    EXPECT_NEAR(dw1, dw2, 1e-6 / h) << "r = " << r;
  }
  double w_lin_left = LinearKernel::eval(0.1 - 1e-10, 0.0, h, 5, 0.0).dw[1];
  double w_lin_right = LinearKernel::eval(0.1 + 1e-10, 0.0, h, 5, 0.0).dw[0];
  EXPECT_GT(std::abs(w_lin_left - w_lin_right), 1.0 / h);  // the linear gradient jumps
}

// eval's written-out regions against node_weight, node by node, for half-sizes from a sliver to
// half a cell, over positions inside the grid and clamped at its ends, and past the ends by up to
// a cell. A node beyond an end (none exist) counts at the end node: each in-grid node's expected
// weight sums node_weight over every node position j that clamps to it, so that the weights sum
// to 1 and the gradients to 0 wherever the point is.
TEST(ShapeFunctions, GimpEvalAgreesWithNodeWeights) {
  const double h = 0.3, origin = -0.1;
  const int cells = 10;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(origin - h, origin + (cells + 1) * h);
  for (const double lp : {1e-4 * h, h / 6.0, h / 4.0, 0.4 * h, 0.5 * h}) {
    for (int trial = 0; trial < 20000; ++trial) {
      const double x = trial < 4 ? origin + (trial % 2 ? cells * h - lp : lp) : u(rng);
      const auto k = GimpKernel::eval(x, origin, h, cells, lp);
      double sum_w = 0.0, sum_dw = 0.0;
      for (int a = 0; a < 3; ++a) {
        const int node = k.first + a;
        double w = 0.0, dw = 0.0;
        for (int j = -4; j <= cells + 4; ++j) {
          if (std::clamp(j, 0, cells) != node) continue;
          double wj, dwj;
          GimpKernel::node_weight(x - (origin + j * h), h, lp, wj, dwj);
          w += wj, dw += dwj;
        }
        ASSERT_NEAR(k.w[a], w, 1e-12) << "x = " << x << ", lp = " << lp << ", node " << a;
        ASSERT_NEAR(k.dw[a] * h, dw * h, 1e-12 * h / lp) << "x = " << x << ", lp = " << lp;
        sum_w += k.w[a], sum_dw += k.dw[a];
      }
      ASSERT_NEAR(sum_w, 1.0, 1e-12) << "x = " << x << ", lp = " << lp;
      ASSERT_NEAR(sum_dw * h, 0.0, 1e-12 * h / lp) << "x = " << x << ", lp = " << lp;
    }
  }
}

TEST(ShapeFunctions, LinearAtGridEndStaysInsideTheGrid) {
  const auto k = LinearKernel::eval(0.5, 0.0, 0.1, 5, 0.0);  // exactly on the last node
  EXPECT_EQ(k.first, 4);
  EXPECT_NEAR(k.w[1], 1.0, 1e-12);
}

/// The stencil through the memo is the direct evaluation's, bit for bit.
template <int D>
void expect_same_stencil(const PointStencil<D, GimpKernel>& a,
                         const PointStencil<D, GimpKernel>& b) {
  for (int k = 0; k < a.n; ++k) {
    EXPECT_EQ(a.node[k], b.node[k]);
    EXPECT_EQ(a.w[k], b.w[k]);
    EXPECT_TRUE(a.grad[k] == b.grad[k]);
  }
}

// The memo serves a point only at the position, half-size and grid it was made for: moved, resized
// or on another grid, the point gets its new stencil; unmoved, the remembered one, bit for bit.
TEST(KernelMemo, ServesOnlyTheSamePositionHalfSizeAndGrid) {
  struct Points {
    std::vector<Vec<2>> position, half_size;
    mutable KernelMemo<2> kernel_memo;
  } mp;
  const auto g = test_grid<2>();
  std::mt19937 rng(7);
  const Vec<2> half = g.spacing / 4.0;
  for (int p = 0; p < 50; ++p) mp.position.push_back(random_point<2>(g, half, rng));
  mp.half_size.assign(50, half);
  mp.kernel_memo.prepare(g, 50);
  PointStencil<2, GimpKernel> via_memo, direct;
  const auto check = [&](const Grid<2>& grid) {
    for (std::int64_t p = 0; p < 50; ++p) {
      evaluate_stencil<2, GimpKernel>(via_memo, grid, mp, p);
      direct.evaluate(grid, mp.position[p], mp.half_size[p]);
      expect_same_stencil<2>(via_memo, direct);
    }
  };
  check(g);                                     // filled
  check(g);                                     // served
  for (auto& x : mp.position) x += 0.3 * half;  // moved
  check(g);
  for (auto& h : mp.half_size) h *= 0.5;  // resized
  check(g);
  const Grid<2> finer(g.origin, 0.5 * g.spacing, {2 * g.n_cells[0], 2 * g.n_cells[1]});
  mp.kernel_memo.prepare(finer, 50);  // another grid: everything forgotten
  check(finer);
  mp.position.push_back(mp.position[0]);  // a point added
  mp.half_size.push_back(mp.half_size[0]);
  mp.kernel_memo.prepare(finer, 51);
  evaluate_stencil<2, GimpKernel>(via_memo, finer, mp, 50);
  direct.evaluate(finer, mp.position[50], mp.half_size[50]);
  expect_same_stencil<2>(via_memo, direct);
}

/// Points as the transfers read them (positions, half-sizes, the kernel memo): n random points of
/// a quarter cell's half-size on grid g, the memo prepared.
template <int D>
struct MemoPoints {
  std::vector<Vec<D>> position, half_size;
  mutable KernelMemo<D> kernel_memo;
};
template <int D>
MemoPoints<D> random_memo_points(const Grid<D>& g, int n, std::mt19937& rng) {
  MemoPoints<D> mp;
  const Vec<D> half = g.spacing / 4.0;
  for (int p = 0; p < n; ++p) mp.position.push_back(random_point<D>(g, half, rng));
  mp.half_size.assign(static_cast<std::size_t>(n), half);
  mp.kernel_memo.prepare(g, static_cast<std::size_t>(n));
  return mp;
}

// Without gradients a stencil has the same nodes and weights, bit for bit, in 1D, 2D and 3D, with
// both kernels, through the memo or not.
template <int D, class K>
void expect_weights_alone_match() {
  const auto g = test_grid<D>();
  std::mt19937 rng(11);
  auto mp = random_memo_points<D>(g, 40, rng);
  PointStencil<D, K> full;
  PointStencil<D, K, false> weights;
  for (std::int64_t p = 0; p < 40; ++p) {
    evaluate_stencil<D, K>(full, g, mp, p);
    evaluate_stencil<D, K>(weights, g, mp, p);
    for (int a = 0; a < full.n; ++a) {
      EXPECT_EQ(weights.node[a], full.node[a]);
      EXPECT_TRUE(weights.w[a] == full.w[a]) << D << "D, point " << p << ", node " << a;
    }
  }
}

TEST(PointStencil, WeightsAloneMatchTheFullStencil) {
  expect_weights_alone_match<1, LinearKernel>();
  expect_weights_alone_match<2, LinearKernel>();
  expect_weights_alone_match<3, LinearKernel>();
  expect_weights_alone_match<1, GimpKernel>();
  expect_weights_alone_match<2, GimpKernel>();
  expect_weights_alone_match<3, GimpKernel>();
}

// The compact stencil (StencilEntries) holds the full stencil's entries that may be nonzero, in
// the full stencil's order, bit for bit, and every entry it leaves out is exactly 0; so a sum over
// it is the full one's to the last bit. Random points (on a lattice of quarter cells too, where
// GIMP's supports start within one cell, and half a GIMP point's width off it, where they
// straddle a node line), with and without gradients, through the memo.
template <int D, bool Gradients>
void expect_compact_matches_full() {
  const auto g = test_grid<D>();
  std::mt19937 rng(13);
  auto mp = random_memo_points<D>(g, 60, rng);
  const Vec<D> half = mp.half_size[0];
  for (int p = 0; p < 20; ++p) {  // at quarter cells, and a GIMP half-width past them
    Vec<D> x;
    for (int d = 0; d < D; ++d)
      x[d] = g.origin[d] + g.spacing[d] * (1.25 + 0.5 * ((p >> d) & 1)) + (p >= 10 ? half[d] : 0);
    mp.position.push_back(x);
  }
  const auto n_mp = static_cast<std::int64_t>(mp.position.size());
  mp.half_size.assign(mp.position.size(), half);
  mp.kernel_memo.prepare(g, mp.position.size());
  PointStencil<D, GimpKernel, Gradients> full;
  PointStencil<D, GimpKernel, Gradients, true> compact;
  std::vector<double> values(static_cast<std::size_t>(g.n_nodes()));
  for (auto& v : values) v = std::uniform_real_distribution<double>(-1.0, 1.0)(rng);
  int fewer = 0;
  for (std::int64_t p = 0; p < n_mp; ++p) {
    evaluate_stencil<D, GimpKernel>(full, g, mp, p);
    evaluate_stencil<D, GimpKernel>(compact, g, mp, p);
    ASSERT_GE(compact.n, 1 << D);
    ASSERT_LE(compact.n, full.n);
    fewer += compact.n < full.n;
    std::vector<bool> kept(full.n, false);
    double sum_full = 0.0, sum_compact = 0.0;
    for (int a = 0; a < compact.n; ++a) {
      const int k = compact.slot(a);
      ASSERT_TRUE(k >= 0 && k < full.n && (a == 0 || k > compact.slot(a - 1)));
      kept[k] = true;
      EXPECT_EQ(compact.node[a], full.node[k]);
      EXPECT_TRUE(compact.w[a] == full.w[k]) << D << "D, point " << p << ", entry " << a;
      if constexpr (Gradients) {
        EXPECT_TRUE(compact.grad[a] == full.grad[k]);
      }
      sum_compact += compact.w[a] * values[compact.node[a]];
    }
    for (int k = 0; k < full.n; ++k) {
      sum_full += full.w[k] * values[full.node[k]];
      if (kept[k]) continue;
      EXPECT_EQ(full.w[k], 0.0) << D << "D, point " << p << ", entry " << k;
      if constexpr (Gradients) {
        EXPECT_TRUE(full.grad[k] == Vec<D>::Zero());
      }
    }
    EXPECT_EQ(sum_compact, sum_full) << D << "D, point " << p;
  }
  EXPECT_GE(fewer, 10) << "the compact stencil left nothing out";
}

TEST(PointStencil, CompactHoldsTheFullStencilsNonzeroEntries) {
  expect_compact_matches_full<1, true>();
  expect_compact_matches_full<2, true>();
  expect_compact_matches_full<3, true>();
  expect_compact_matches_full<2, false>();
  expect_compact_matches_full<3, false>();
  // Linear kernels reach all their nodes: the transfers keep their full, fixed-size stencil.
  static_assert(TransferStencil<2, LinearKernel>::n == 4);
  static_assert(!std::is_same_v<TransferStencil<2, GimpKernel>, PointStencil<2, GimpKernel>>);
}

}  // namespace test_shape_functions
}  // namespace unsatmpm::numerics

#include <gtest/gtest.h>

#include <random>

#include "numerics/shape_functions.hpp"

namespace unsatmpm::numerics {
namespace {

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

TEST(ShapeFunctions, LinearAtGridEndStaysInsideTheGrid) {
  const auto k = LinearKernel::eval(0.5, 0.0, 0.1, 5, 0.0);  // exactly on the last node
  EXPECT_EQ(k.first, 4);
  EXPECT_NEAR(k.w[1], 1.0, 1e-12);
}

}  // namespace
}  // namespace unsatmpm::numerics

// Shape functions of the background grid, evaluated as tensor products of 1D kernels.
//
// LinearKernel: standard MPM hat functions, 2 nodes per direction.
// GimpKernel: uniform GIMP (Bardenhagen & Kober 2004), the hat convolved with the particle's
//   characteristic function of half-length lp <= h/2; 3 nodes per direction. It removes the force
//   jumps of cell crossing. lp is the point's half-size at generation (not updated: "uGIMP").
// Both kernels are partitions of unity inside the grid. A point whose support pokes out of the grid
// keeps only the in-grid nodes (the lost weight is zero for linear, and only the sliver outside the
// grid for GIMP); callers check that points stay inside the grid.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>

#include "numerics/grid.hpp"

namespace unsatmpm::numerics {

/// One direction of a kernel: first node and weights/derivatives of the supported nodes.
template <int N>
struct Kernel1D {
  int first;                 // index of the first supported node along the direction
  std::array<double, N> w;   // weights
  std::array<double, N> dw;  // derivatives along the direction [1/m]
};

/// floor(xi) clamped to [lo, hi] without a libm call (x86-64's baseline has no SSE4.1 round).
/// Positions are finite and inside the grid (checked every step), so xi is small and finite.
inline int clamped_floor(double xi, int lo, int hi) {
  int i = static_cast<int>(xi);  // truncation; equals floor for xi >= 0, and xi < 0 clamps to lo
  if (xi < 0.0) i = lo;
  return i < lo ? lo : (i > hi ? hi : i);
}

struct LinearKernel {
  static constexpr int n_support = 2;
  static Kernel1D<2> eval(double x, double origin, double h, int n_cells, double /*lp*/) {
    const double xi = (x - origin) / h;
    const int i = clamped_floor(xi, 0, n_cells - 1);
    const double f = xi - i;
    return {i, {1.0 - f, f}, {-1.0 / h, 1.0 / h}};
  }
};

struct GimpKernel {
  static constexpr int n_support = 3;
  /// uGIMP weight of a node at signed distance r = x - x_node, and its derivative d/dx.
  static void node_weight(double r, double h, double lp, double& w, double& dw) {
    const double a = std::abs(r), sgn = r < 0.0 ? -1.0 : 1.0;
    if (a < lp) {
      w = 1.0 - (r * r + lp * lp) / (2.0 * h * lp);
      dw = -r / (h * lp);
    } else if (a < h - lp) {
      w = 1.0 - a / h;
      dw = -sgn / h;
    } else if (a < h + lp) {
      const double g = h + lp - a;
      w = g * g / (4.0 * h * lp);
      dw = -sgn * g / (2.0 * h * lp);
    } else {
      w = 0.0;
      dw = 0.0;
    }
  }
  static Kernel1D<3> eval(double x, double origin, double h, int n_cells, double lp) {
    // Nodes run 0..n_cells; three of them from i. Clamp to the grid (see header comment).
    const int i = clamped_floor((x - lp - origin) / h, 0, n_cells - 2);
    Kernel1D<3> k;
    k.first = i;
    for (int a = 0; a < 3; ++a) node_weight(x - (origin + (i + a) * h), h, lp, k.w[a], k.dw[a]);
    return k;
  }
};

/// Tensor-product shape functions of one point: node indices, weights and gradients.
template <int D, class K>
struct PointStencil {
  static constexpr int n = [] {
    int m = 1;
    for (int d = 0; d < D; ++d) m *= K::n_support;
    return m;
  }();
  std::array<std::int64_t, n> node;
  std::array<double, n> w;
  std::array<Vec<D>, n> grad;  // [1/m]

  void evaluate(const Grid<D>& g, const Vec<D>& x, const Vec<D>& half_size) {
    std::array<Kernel1D<K::n_support>, D> k;
    for (int d = 0; d < D; ++d)
      k[d] = K::eval(x[d], g.origin[d], g.spacing[d], g.n_cells[d], half_size[d]);
    constexpr int s = K::n_support;
    // Loop nests written per dimension so that every product is formed once (x fastest).
    if constexpr (D == 1) {
      for (int i = 0; i < s; ++i) {
        node[i] = k[0].first + i;
        w[i] = k[0].w[i];
        grad[i][0] = k[0].dw[i];
      }
    } else if constexpr (D == 2) {
      int a = 0;
      for (int j = 0; j < s; ++j) {
        const std::int64_t row = (k[1].first + j) * g.stride[1] + k[0].first;
        for (int i = 0; i < s; ++i, ++a) {
          node[a] = row + i;
          w[a] = k[0].w[i] * k[1].w[j];
          grad[a][0] = k[0].dw[i] * k[1].w[j];
          grad[a][1] = k[0].w[i] * k[1].dw[j];
        }
      }
    } else {
      int a = 0;
      for (int l = 0; l < s; ++l) {
        for (int j = 0; j < s; ++j) {
          const std::int64_t row =
              (k[2].first + l) * g.stride[2] + (k[1].first + j) * g.stride[1] + k[0].first;
          const double wjl = k[1].w[j] * k[2].w[l], dj = k[1].dw[j] * k[2].w[l],
                       dl = k[1].w[j] * k[2].dw[l];
          for (int i = 0; i < s; ++i, ++a) {
            node[a] = row + i;
            w[a] = k[0].w[i] * wjl;
            grad[a][0] = k[0].dw[i] * wjl;
            grad[a][1] = k[0].w[i] * dj;
            grad[a][2] = k[0].w[i] * dl;
          }
        }
      }
    }
  }
};

}  // namespace unsatmpm::numerics

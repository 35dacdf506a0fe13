// Shape functions of the background grid, evaluated as tensor products of 1D kernels.
//
// LinearKernel: standard MPM hat functions, 2 nodes per direction.
// GimpKernel: uniform GIMP (Bardenhagen & Kober 2004), the hat convolved with the particle's
//   characteristic function of half-length lp <= h/2; 3 nodes per direction. It removes the force
//   jumps of cell crossing. lp is the point's half-size at generation (not updated: "uGIMP").
// Both kernels are partitions of unity wherever the point is: the weights sum to 1 and the
// gradients to 0. A linear kernel past the grid's last cell extrapolates that cell's two nodes. A
// GIMP point whose support pokes out of the grid (a point that has moved to within its half-size
// of the grid's edge) gives the weight and gradient of each node beyond the edge to the edge node.
// Dropping them instead broke the flux's conservation: each point's Darcy flux reaches the nodes
// through sum_i grad N_i . J = 0, and the points of a settling embankment that had sunk below
// their half-size over its rigid base sent water to the missing nodes (docs/balance_laws.md, "The
// implicit cycle: mass balances in Darcy form at the nodes"). Callers check that points stay
// inside the grid.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <vector>

#include "numerics/grid.hpp"

namespace unsatmpm::numerics {

/// One direction of a kernel: first node and weights/derivatives of the supported nodes. The
/// nodes from `count` on have weight and derivative exactly 0 (a GIMP point whose support lies
/// within one cell reaches two of its three nodes).
template <int N>
struct Kernel1D {
  int first;                 // index of the first supported node along the direction
  std::array<double, N> w;   // weights
  std::array<double, N> dw;  // derivatives along the direction [1/m]
  int count = N;             // the nodes first .. first + count - 1 may have a nonzero weight
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
  // The one-phase cycle takes the strain from MUSL's remapped velocities (numerics/
  // velocity_remap.hpp: a node just reached has a vanishing mass but a full gradient).
  static constexpr bool remap_velocity = true;
  static Kernel1D<2> eval(double x, double origin, double h, int n_cells, double /*lp*/) {
    const double xi = (x - origin) / h;
    const int i = clamped_floor(xi, 0, n_cells - 1);
    const double f = xi - i;
    return {i, {1.0 - f, f}, {-1.0 / h, 1.0 / h}};
  }
};

struct GimpKernel {
  static constexpr int n_support = 3;
  static constexpr bool remap_velocity = false;  // weights and gradients vanish together
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
    const double inv_h = 1.0 / h;
    const int i = clamped_floor((x - lp - origin) * inv_h, 0, n_cells - 2);
    Kernel1D<3> k;
    k.first = i;
    // Unclamped, the first node lies at r0 in [lp, h + lp) behind x, and node_weight's regions
    // are known: with r0 < h - lp the support lies within one cell (two hat weights), else it
    // straddles node i + 1 (the outer nodes in their quadratic tails, node i + 1 in its cap).
    // Written out, without node_weight's branches and divisions (the one kernel evaluation per
    // point and mechanics step, KernelMemo; docs/performance.md).
    const double r0 = x - (origin + i * h);
    if (r0 >= lp && r0 < h + lp && lp <= 0.5 * h) {
      if (r0 < h - lp) {
        k.w = {1.0 - r0 * inv_h, r0 * inv_h, 0.0};
        k.dw = {-inv_h, inv_h, 0.0};
        k.count = 2;
      } else {
        const double inv_hlp = inv_h / lp, r1 = r0 - h, g0 = lp - r1, g2 = lp + r1;
        k.w = {0.25 * g0 * g0 * inv_hlp, 1.0 - 0.5 * (r1 * r1 + lp * lp) * inv_hlp,
               0.25 * g2 * g2 * inv_hlp};
        k.dw = {-0.5 * g0 * inv_hlp, -r1 * inv_hlp, 0.5 * g2 * inv_hlp};
      }
      return k;
    }
    for (int a = 0; a < 3; ++a) node_weight(x - (origin + (i + a) * h), h, lp, k.w[a], k.dw[a]);
    // The support's nodes beyond the grid's ends (at most the three from the unclamped first
    // node) give their weights and gradients to the end node: k.w[0] at node 0 (i = 0 there),
    // k.w[2] at node n_cells (i = n_cells - 2).
    const int unclamped = static_cast<int>(std::floor((x - lp - origin) * inv_h));
    for (int j = unclamped; j < unclamped + 3; ++j) {
      if (j >= 0 && j <= n_cells) continue;
      double w = 0.0, dw = 0.0;
      node_weight(x - (origin + j * h), h, lp, w, dw);
      const int end = j < 0 ? 0 : n_cells - i;
      k.w[end] += w, k.dw[end] += dw;
    }
    return k;
  }
};

/// The number of entries of a PointStencil: all of the kernel's tensor product (`n`, a constant,
/// entry a in the product's layout, x fastest), or with `Compact` only the nodes that the 1D
/// kernels reach with a possibly nonzero weight (`n` counted at each evaluation, and `slot(a)` the
/// entry's place in the full layout). A GIMP point whose support lies within a cell along a
/// direction reaches 2 of the 3 nodes there, so a compact 2D stencil has 4, 6 or 9 entries (on
/// the embankment 6.25 on average against 9). The entries left out have weight and gradient
/// exactly 0: a sum over the compact stencil is the full one's to the last bit, the same nonzero
/// terms in the same order. Transfers that only add the weighted values of nodes take it; the
/// flow's quadrature, whose sparsity pattern follows the stencil's nodes, keeps the full layout.
template <int N, bool Compact>
struct StencilEntries {
  static constexpr int n = N;
  static constexpr int slot(int a) { return a; }
};
template <int N>
struct StencilEntries<N, true> {
  int n = N;
  std::array<std::int8_t, N> slots{};
  int slot(int a) const { return slots[a]; }
};

template <int D, class K>
inline constexpr int stencil_capacity = [] {
  int m = 1;
  for (int d = 0; d < D; ++d) m *= K::n_support;
  return m;
}();

/// Tensor-product shape functions of one point: node indices, weights and, with `Gradients`,
/// their gradients (without, `grad` is left unset: the transfers that only weigh, such as the
/// nodal pressure solve's, skip two thirds of the products). `Compact`: StencilEntries.
template <int D, class K, bool Gradients = true, bool Compact = false>
struct PointStencil : StencilEntries<stencil_capacity<D, K>, Compact> {
  static constexpr int capacity = stencil_capacity<D, K>;
  std::array<std::int64_t, capacity> node;
  std::array<double, capacity> w;
  std::array<Vec<D>, capacity> grad;  // [1/m]

  void evaluate(const Grid<D>& g, const Vec<D>& x, const Vec<D>& half_size) {
    std::array<Kernel1D<K::n_support>, D> k;
    for (int d = 0; d < D; ++d)
      k[d] = K::eval(x[d], g.origin[d], g.spacing[d], g.n_cells[d], half_size[d]);
    assemble(g, k);
  }

  /// The same, with the 1D kernels taken from `memo` when it holds those of x and half_size
  /// (KernelMemo), else evaluated and left there.
  template <class Entry>
  void evaluate(const Grid<D>& g, const Vec<D>& x, const Vec<D>& half_size, Entry& memo) {
    if (!(memo.position == x && memo.half_size == half_size)) {
      for (int d = 0; d < D; ++d)
        memo.kernels[d] = K::eval(x[d], g.origin[d], g.spacing[d], g.n_cells[d], half_size[d]);
      memo.position = x, memo.half_size = half_size;
    }
    assemble(g, memo.kernels);
  }

 private:
  void assemble(const Grid<D>& g, const std::array<Kernel1D<K::n_support>, D>& k) {
    constexpr int s = K::n_support;
    // The nodes reached along each direction: all s, or with Compact those of count.
    std::array<int, D> c;
    for (int d = 0; d < D; ++d) c[d] = Compact ? k[d].count : s;
    // Loop nests written per dimension so that every product is formed once (x fastest).
    if constexpr (D == 1) {
      for (int i = 0; i < c[0]; ++i) {
        node[i] = k[0].first + i;
        w[i] = k[0].w[i];
        if constexpr (Gradients) grad[i][0] = k[0].dw[i];
        if constexpr (Compact) this->slots[i] = static_cast<std::int8_t>(i);
      }
      if constexpr (Compact) this->n = c[0];
    } else if constexpr (D == 2) {
      int a = 0;
      for (int j = 0; j < c[1]; ++j) {
        const std::int64_t row = (k[1].first + j) * g.stride[1] + k[0].first;
        for (int i = 0; i < c[0]; ++i, ++a) {
          node[a] = row + i;
          w[a] = k[0].w[i] * k[1].w[j];
          if constexpr (Gradients) {
            grad[a][0] = k[0].dw[i] * k[1].w[j];
            grad[a][1] = k[0].w[i] * k[1].dw[j];
          }
          if constexpr (Compact) this->slots[a] = static_cast<std::int8_t>(i + s * j);
        }
      }
      if constexpr (Compact) this->n = a;
    } else {
      int a = 0;
      for (int l = 0; l < c[2]; ++l) {
        for (int j = 0; j < c[1]; ++j) {
          const std::int64_t row =
              (k[2].first + l) * g.stride[2] + (k[1].first + j) * g.stride[1] + k[0].first;
          const double wjl = k[1].w[j] * k[2].w[l], dj = k[1].dw[j] * k[2].w[l],
                       dl = k[1].w[j] * k[2].dw[l];
          for (int i = 0; i < c[0]; ++i, ++a) {
            if constexpr (Compact) this->slots[a] = static_cast<std::int8_t>(i + s * (j + s * l));
            node[a] = row + i;
            w[a] = k[0].w[i] * wjl;
            if constexpr (Gradients) {
              grad[a][0] = k[0].dw[i] * wjl;
              grad[a][1] = k[0].w[i] * dj;
              grad[a][2] = k[0].w[i] * dl;
            }
          }
        }
      }
      if constexpr (Compact) this->n = a;
    }
  }
};

/// The stencil of the transfers that only add weighted nodal values (p2g, g2p, the nodal pressure
/// solve, the offsets' relaxation): compact with GIMP, where it leaves out a third of the entries
/// on average; full with linear kernels, whose stencil is always full and whose fixed trip count
/// the compiler unrolls.
template <int D, class K, bool Gradients = true>
using TransferStencil = PointStencil<D, K, Gradients, (K::n_support > 2)>;

/// Each point's 1D GIMP kernels, kept with the position and half-size they were evaluated at.
/// One mechanics step of the coupled cycles transfers a point at the same place up to four
/// times (p2g, g2p, the nodal pressure solve's two passes), and evaluating uGIMP's kernels (their
/// branches and divisions) was the largest single cost of those transfers (docs/performance.md):
/// with the memo a point's kernels are evaluated once per position. An entry serves only the
/// exact position and half-size it was made for, so it can never be stale, whoever moved the
/// point; prepare() forgets everything when the grid changes. Entries are written by the thread
/// that transfers the point, one thread per point in every loop.
template <int D>
class KernelMemo {
 public:
  struct Entry {
    Vec<D> position = Vec<D>::Constant(std::numeric_limits<double>::quiet_NaN());
    Vec<D> half_size = Vec<D>::Constant(std::numeric_limits<double>::quiet_NaN());
    std::array<Kernel1D<GimpKernel::n_support>, D> kernels{};
  };

  /// Sizes the memo for n points on grid g, outside any parallel region.
  void prepare(const Grid<D>& g, std::size_t n) {
    if (!(g.origin == origin_ && g.spacing == spacing_ && g.n_cells == n_cells_)) {
      entries_.assign(n, Entry{});
      origin_ = g.origin, spacing_ = g.spacing, n_cells_ = g.n_cells;
    }
    entries_.resize(n);
  }
  Entry& operator[](std::size_t p) { return entries_[p]; }

 private:
  std::vector<Entry> entries_;
  Vec<D> origin_ = Vec<D>::Constant(std::numeric_limits<double>::quiet_NaN()), spacing_ = origin_;
  std::array<int, D> n_cells_{};
};

/// Evaluates `st` for point p of `mp`, through the points' kernel memo with GIMP (linear kernels
/// are cheaper to evaluate than to look up). The memo must have been prepared for the grid.
template <int D, class K, class Points, bool Gradients, bool Compact>
void evaluate_stencil(PointStencil<D, K, Gradients, Compact>& st, const Grid<D>& g,
                      const Points& mp, std::int64_t p) {
  if constexpr (std::is_same_v<K, GimpKernel>)
    st.evaluate(g, mp.position[p], mp.half_size[p], mp.kernel_memo[p]);
  else
    st.evaluate(g, mp.position[p], mp.half_size[p]);
}

}  // namespace unsatmpm::numerics

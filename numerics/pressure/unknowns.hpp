// The numbering of the pressure system's unknowns, and the sparsity pattern of its Jacobian.
//
// For each active node (sum_p N_i V_p > 0) in node order, P_l then P_g, each unless prescribed;
// then the two inflow integrals, one per fluid (numerics/pressure/pressure_system.hpp).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "numerics/pressure/face_trace.hpp"
#include "numerics/pressure/quadrature.hpp"
#include "numerics/sparse_pattern.hpp"

namespace unsatmpm::numerics {

/// The flags a numbering comes from, which a PressureSystem's prepare carries over to the next:
/// the active and free-surface nodes, and each fluid's prescribed nodes and surface exemptions
/// (one flag per node; empty before the first prepare).
struct PrepareCarry {
  std::vector<std::uint8_t> active, surface;
  std::array<std::vector<std::uint8_t>, 2> prescribed, exempt;
};

class PressureUnknowns {
 public:
  explicit PressureUnknowns(std::int64_t n_nodes) {
    for (auto& u : index_) u.assign(n_nodes, -1);
  }

  /// Numbers the unknowns: `active` says which nodes are, `prescribed[a][i]` where fluid a is
  /// prescribed.
  template <class Active>
  void number(Active&& active, const std::array<std::vector<std::uint8_t>, 2>& prescribed) {
    std::int64_t k = 0;
    nodes_.clear();
    for (std::int64_t i = 0; i < static_cast<std::int64_t>(index_[0].size()); ++i) {
      bool any = false;
      for (int a = 0; a < 2; ++a) {
        index_[a][i] = active(i) && !prescribed[a][i] ? k++ : -1;
        any = any || index_[a][i] >= 0;
      }
      if (any) nodes_.push_back(i);
    }
    n_pressures_ = k;
  }

  /// Index of fluid a's pressure at node i, or -1 if it is not an unknown.
  std::int64_t operator()(int a, std::int64_t i) const { return index_[a][i]; }
  /// The nodes with at least one unknown, in node order.
  const std::vector<std::int64_t>& nodes() const { return nodes_; }
  std::int64_t n_pressures() const { return n_pressures_; }
  std::int64_t size() const { return n_pressures_ + 2; }
  /// Index of the inflow integral of fluid a.
  std::int64_t inflow(int a) const { return n_pressures_ + a; }

  /// Node and fluid of unknown k (for messages); (-1, a) for the inflow integral of fluid a.
  std::pair<std::int64_t, int> location(std::int64_t k) const {
    if (k >= n_pressures_) return {-1, static_cast<int>(k - n_pressures_)};
    for (const auto i : nodes_)
      for (int a = 0; a < 2; ++a)
        if (index_[a][i] == k) return {i, a};
    return {-1, 0};
  }

  /// The Jacobian's pattern: each point couples the unknowns of the stencil nodes it keeps
  /// (PointQuadrature::jacobian_nodes); the balance of a prescribed active node (fluid a) feeds
  /// the row of fluid a's inflow integral, and every gas balance also feeds the gas inflow's row
  /// (a node whose gas storage vanishes during the integration is held and its balance counted as
  /// inflow: PressureOperator::node_inflow). Every diagonal entry is present.
  template <int D, class K, class PrescribedActive>
  SparsePattern jacobian_pattern(const PointQuadrature<D, K>& q,
                                 PrescribedActive&& prescribed_active,
                                 const std::array<FaceTrace, 2>& penalty = {}) const {
    const std::int64_t n = size();
    std::vector<std::vector<std::int64_t>> rows(n);
    for (int a = 0; a < 2; ++a)  // a surface penalty couples its pairs, and feeds the inflow
      for (std::size_t k = 0; k < penalty[a].value.size(); ++k)
        if (const auto r = index_[a][penalty[a].row[k]], c = index_[a][penalty[a].col[k]];
            r >= 0 && c >= 0)
          rows[r].push_back(c), rows[inflow(a)].push_back(c);
    for (std::size_t p = 0; p < q.size(); ++p) {
      const auto& st = q.stencil[p];
      const auto kept = q.jacobian_nodes[p];
      for (int a = 0; a < st.n; ++a)
        for (int al = 0; al < 2; ++al) {
          const auto i = st.node[a];
          const auto r = prescribed_active(al, i) ? inflow(al) : index_[al][i];
          if (r < 0 || !(kept >> a & 1u)) continue;
          const bool gas_unknown = al == 1 && r == index_[al][i];
          for (int b = 0; b < st.n; ++b)
            for (int be = 0; be < 2; ++be)
              if (const auto c = index_[be][st.node[b]]; c >= 0 && (kept >> b & 1u)) {
                rows[r].push_back(c);
                if (gas_unknown) rows[inflow(1)].push_back(c);
              }
        }
    }
    return pattern_from_rows(rows);
  }

 private:
  std::array<std::vector<std::int64_t>, 2> index_;
  std::vector<std::int64_t> nodes_;
  std::int64_t n_pressures_ = 0;
};

}  // namespace unsatmpm::numerics

// The liquid pressure that decides when the main cycle's surface nodes pond under rain
// (cycles/flow_prescription.hpp): at a node that carries points of a column's top row (the points
// that take the rain, cycles/rainfall.hpp), the highest liquid pressure among those points,
// interpolated from the nodes; elsewhere the node's own. The explicit cycle's test takes its
// points' highest in the same way (cycles/explicit_rain.hpp).
//
// Why not the node's own pressure: a node that a top point barely reaches holds a fraction of a
// full node's storage, so under rain its pressure reaches the gas pressure long before the soil
// around it is wet. A flat top half a cell past a node line has only such a node beyond it (an
// eighth of a full node's volume): V16's column on 1/128 m cells ponded at 0.05 s, was held at
// zero suction over still dry points and took in 0.156 kg/m^2 of the 7.36 Richards' equation
// gives by 3 s (verification/rain/README.md). With the top on the node line the top node holds
// half a node's volume and ponded at 0.35 s against the reference's 1.65 s.
#pragma once

#include <algorithm>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "numerics/grid.hpp"
#include "numerics/material_points.hpp"
#include "numerics/shape_functions.hpp"

namespace unsatmpm {

template <int D, class K>
class TopRowPressures {
 public:
  /// The stencils of the points `top_row` (pairs point, anything: RainfallSurface::top_row) at
  /// the points' current positions, and each node's points among them.
  void build(const numerics::Grid<D>& grid, const numerics::MaterialPoints<D>& mp,
             const std::vector<std::pair<std::int64_t, double>>& top_row) {
    const auto n_nodes = static_cast<std::size_t>(grid.n_nodes());
    offsets_.assign(1, 0), nodes_.clear(), weights_.clear();
    std::vector<std::int64_t> count(n_nodes + 1, 0);
    numerics::PointStencil<D, K> st;
    for (const auto& entry : top_row) {
      const auto p = entry.first;
      st.evaluate(grid, mp.position[p], mp.half_size[p]);
      for (int a = 0; a < st.n; ++a)
        if (st.w[a] > 0.0) {
          nodes_.push_back(st.node[a]), weights_.push_back(st.w[a]);
          ++count[st.node[a] + 1];
        }
      offsets_.push_back(static_cast<std::int64_t>(nodes_.size()));
    }
    // Each node's points, by a counting sort of the stencils' nodes.
    for (std::size_t i = 0; i < n_nodes; ++i) count[i + 1] += count[i];
    node_offsets_ = count;
    node_points_.assign(static_cast<std::size_t>(count[n_nodes]), 0);
    for (std::size_t q = 0; q + 1 < offsets_.size(); ++q)
      for (auto k = offsets_[q]; k < offsets_[q + 1]; ++k)
        node_points_[static_cast<std::size_t>(count[nodes_[k]]++)] = static_cast<std::int64_t>(q);
  }

  /// Node i's ponding pressure [Pa]: the highest of its top-row points' liquid pressures,
  /// sum_a N_a P_a with P_a = value(a) the nodes' liquid pressures, or own if it carries none.
  template <class Value>
  double at(std::int64_t i, double own, Value&& value) const {
    if (node_offsets_.empty() || node_offsets_[i] == node_offsets_[i + 1]) return own;
    double highest = -std::numeric_limits<double>::infinity();
    for (auto k = node_offsets_[i]; k < node_offsets_[i + 1]; ++k) {
      const auto q = node_points_[k];
      double p = 0.0;
      for (auto m = offsets_[q]; m < offsets_[q + 1]; ++m) p += weights_[m] * value(nodes_[m]);
      highest = std::max(highest, p);
    }
    return highest;
  }

 private:
  std::vector<std::int64_t> offsets_;       // point q's stencil: [offsets_[q], offsets_[q + 1])
  std::vector<std::int64_t> nodes_;         // the stencils' nodes
  std::vector<double> weights_;             // and weights
  std::vector<std::int64_t> node_offsets_;  // node i's points: [node_offsets_[i], ...[i + 1])
  std::vector<std::int64_t> node_points_;   // indices into the top row
};

}  // namespace unsatmpm

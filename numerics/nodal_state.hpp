// Grid-side state of the explicit cycle: scatter buffers, velocities and boundary masks.
//
// P2G is race-free without locks: every thread scatters into its own buffer (one interleaved
// record [mass, momentum(D), force(D)] per node, so a node's record is one cache line in 2D), and
// the buffers are summed node by node afterwards. The buffers are reused from step to step.
#pragma once

#include <cstdint>
#include <vector>

#include "numerics/grid.hpp"
#include "numerics/rigid_plates.hpp"

namespace unsatmpm::numerics {

template <int D>
struct NodalState {
  static constexpr int record = 1 + 2 * D;  // mass [kg], momentum [kg m/s], force [N]

  std::vector<std::vector<double>> scatter;  // one buffer per thread, n_nodes * record
  std::vector<Vec<D>> velocity;              // after the update [m/s]
  std::vector<Vec<D>> acceleration;          // [m/s^2]
  std::vector<std::uint8_t> fixed;           // bit d set: velocity component d held at zero
  std::vector<RigidPlate> plates;            // numerics/rigid_plates.hpp
  // MUSL's remap with linear shape functions (numerics/velocity_remap.hpp): one buffer per
  // thread, n_nodes * D momenta, and the velocities of the strain [m/s].
  std::vector<std::vector<double>> remap;
  std::vector<Vec<D>> remapped;

  void resize(std::int64_t n_nodes, int n_threads) {
    scatter.assign(n_threads, std::vector<double>(n_nodes * record, 0.0));
    velocity.assign(n_nodes, Vec<D>::Zero());
    acceleration.assign(n_nodes, Vec<D>::Zero());
    fixed.assign(n_nodes, 0);
  }
  std::int64_t n_nodes() const { return static_cast<std::int64_t>(velocity.size()); }

  // Accessors into the reduced buffer (thread 0's, after reduction).
  double mass(std::int64_t i) const { return scatter[0][i * record]; }
  Eigen::Map<const Vec<D>> momentum(std::int64_t i) const {
    return Eigen::Map<const Vec<D>>(&scatter[0][i * record + 1]);
  }
  Eigen::Map<const Vec<D>> force(std::int64_t i) const {
    return Eigen::Map<const Vec<D>>(&scatter[0][i * record + 1 + D]);
  }
};

/// An external force on one node [N per unit out-of-plane measure] (surface loads).
template <int D>
struct NodalForce {
  std::int64_t node;
  Vec<D> force;
};

/// Adds external nodal forces to the reduced buffer of the last p2g (before solve_grid).
template <int D>
void add_nodal_forces(const std::vector<NodalForce<D>>& forces, NodalState<D>& nodes) {
  constexpr int R = NodalState<D>::record;
  for (const NodalForce<D>& f : forces)
    for (int d = 0; d < D; ++d) nodes.scatter[0][f.node * R + 1 + D + d] += f.force[d];
}

}  // namespace unsatmpm::numerics

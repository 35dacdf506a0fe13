// Rigid, frictionless plates (a boundary's `mechanical: rigid_plate`, docs/input.md): the nodes of
// a grid plane that carry material share one velocity along the plane's normal; along the plane
// they are free. The plate is a Lagrange multiplier per node whose sum is zero: it moves load
// between its nodes but adds none of its own, so the plate's normal momentum changes by the sum of
// the nodal forces on it (the surface load included) and the nodes follow it:
//   one phase:    V = (sum_i m_i v_i + dt sum_i f_i) / sum_i m_i
//   three phases: the same with the solid's effective inertia and force of the node, the fluids'
//                 implicit drag eliminated (numerics/three_phase_transfers.hpp), so that the
//                 fluids' accelerations follow the plate's solid acceleration as at a free node.
// Each node's acceleration is then (V - v_i) / dt, so FLIP's increment and PIC's value agree.
// Damping acts on the plate's net force, -alpha |F| sign(V_old), as on one node: damping each
// node's share would oppose the plate's motion with alpha times the sum of the shares'
// magnitudes, which the load's redistribution makes far larger than the net force, and would hold
// the plate away from equilibrium like dry friction (measured: a plate chattering at 4 mm/s,
// its column's stresses 2 % off, after 75 periods).
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

namespace unsatmpm::numerics {

struct RigidPlate {
  int axis;                         // the plane's normal: the component the nodes share
  std::vector<std::int64_t> nodes;  // the nodes on the plane
};

/// The plate's damped net force F - alpha |F| sign(V) [N].
inline double damped_plate_force(double force, double velocity, double damping) {
  const double sign = velocity > 0.0 ? 1.0 : (velocity < 0.0 ? -1.0 : 0.0);
  return force - damping * std::abs(force) * sign;
}

/// Applies the plates at the end of solve_grid (numerics/explicit_transfers.hpp), over the
/// nodes' own accelerations, from their masses, momenta and (external included) forces;
/// `Nodes` is a NodalState.
template <class Nodes>
void apply_rigid_plates(const std::vector<RigidPlate>& plates, double dt, double damping,
                        double mass_floor, Nodes& nodes) {
  for (const RigidPlate& plate : plates) {
    const int d = plate.axis;
    double mass = 0.0, momentum = 0.0, force = 0.0;
    for (const std::int64_t i : plate.nodes) {
      const double m = nodes.mass(i);
      if (m <= mass_floor) continue;
      mass += m;
      momentum += nodes.momentum(i)[d];
      force += nodes.force(i)[d];
    }
    if (mass <= 0.0) continue;
    const double v = (momentum + dt * damped_plate_force(force, momentum / mass, damping)) / mass;
    for (const std::int64_t i : plate.nodes) {
      const double m = nodes.mass(i);
      if (m <= mass_floor) continue;
      nodes.acceleration[i][d] = (v - nodes.momentum(i)[d] / m) / dt;
      nodes.velocity[i][d] = v;
    }
  }
}

}  // namespace unsatmpm::numerics

// Grid-side state of the three-phase explicit cycle (docs/cycles.md).
//
// Every node gathers, in one interleaved record per thread buffer (see NodalState):
//   solid mass M_s and momentum; liquid and gas "per-fluid-volume" masses M_L = sum N rho_l V and
//   momenta (the fluid balances are divided by n S_a, as in the paper's single-point form);
//   the partial masses n S_a rho_a V that the fluids add to the mixture balance; the fluids'
//   conductivities sum N V rho_a kappa k_ra / mu_a of the points and, at a node that prescribes a
//   fluid's pressure, at that pressure (numerics/face_conductivity.hpp), from which the drag
//   coefficient is formed (three_phase_transfers.hpp, nodal_drag); the forces of the mixture, the
//   liquid and the gas; and the volume-weighted sums that project theta_a = n S_a rho_a to the
//   nodes for the advective term of the full mass balance; and the pore and gas volumes sum N V n
//   and sum N V n S_g, whose ratio tells the nodes free of gas (physics::gas_free_saturation).
#pragma once

#include <cstdint>
#include <vector>

#include "numerics/grid.hpp"
#include "numerics/offset_bounds.hpp"
#include "numerics/rigid_plates.hpp"

namespace unsatmpm::numerics {

template <int D>
struct ThreePhaseLayout {
  static constexpr int solid_mass = 0, solid_momentum = 1;
  static constexpr int liquid_mass = 1 + D, liquid_momentum = 2 + D;
  static constexpr int gas_mass = 2 + 2 * D, gas_momentum = 3 + 2 * D;
  static constexpr int liquid_partial_mass = 3 + 3 * D, gas_partial_mass = 4 + 3 * D;
  static constexpr int liquid_conductivity = 5 + 3 * D, gas_conductivity = 6 + 3 * D;
  static constexpr int mixture_force = 7 + 3 * D, liquid_force = 7 + 4 * D, gas_force = 7 + 5 * D;
  static constexpr int liquid_theta = 7 + 6 * D, gas_theta = 8 + 6 * D, volume = 9 + 6 * D;
  static constexpr int pore_volume = 10 + 6 * D, gas_volume = 11 + 6 * D;
  static constexpr int area = 12 + 6 * D;  // sum V grad N: the body's outward boundary area
  static constexpr int liquid_face_conductivity = 12 + 7 * D, gas_face_conductivity = 13 + 7 * D;
  static constexpr int record = 14 + 7 * D;
};

template <int D>
struct ThreePhaseNodes {
  using L = ThreePhaseLayout<D>;
  std::vector<std::vector<double>> scatter;  // one buffer per thread, n_nodes * record
  // Nodal mass balance: per thread, n_nodes * 6 sums of N V (A_ll, A_lg, A_gl, A_gg, r_l, r_g).
  std::vector<std::vector<double>> mass_balance;
  // The pressure offsets' relaxation's scratch (numerics/pressure_offsets.hpp; sized by its
  // passes).
  OffsetScratch pressure_offsets;
  std::vector<Vec<D>> solid_velocity, liquid_velocity, gas_velocity;              // updated
  std::vector<Vec<D>> solid_acceleration, liquid_acceleration, gas_acceleration;  // of the step
  std::vector<double> liquid_theta, gas_theta;  // n S_a rho_a projected to the nodes [kg/m^3]
  std::vector<std::uint8_t> gas_free;           // 1: no gas phase at the node this step
  std::vector<std::uint8_t> solid_fixed;        // bit d: solid velocity component d held at 0
  std::vector<RigidPlate> plates;               // numerics/rigid_plates.hpp (solid velocity)
  std::vector<std::uint8_t> liquid_locked, gas_locked;  // bit d: no relative flow along d
  // 1 at the free-surface nodes of the step where the fluid has no flux: no relative flow in any
  // direction (cycles/three_phase_solver.hpp, mark_free_surface).
  std::vector<std::uint8_t> liquid_surface, gas_surface;
  // 1 on a boundary face that prescribes the fluid's pressure (set once); elsewhere the flux
  // divergence is corrected so that no mass crosses the node: leak = (sum V grad N) / sum N V
  // (three_phase_g2p.hpp, interpolate), 0 on the faces.
  std::vector<std::uint8_t> liquid_prescribed, gas_prescribed;
  std::vector<Vec<D>> liquid_leak, gas_leak;
  std::vector<Vec<D>> liquid_traction, gas_traction;  // -P_prescribed n A at boundary nodes [N]
  // The prescribed pressures of the step at the nodes that prescribe them [Pa].
  std::vector<double> liquid_face_pressure, gas_face_pressure;
  // Each fluid's mean conductivity rho_a kappa k_ra / mu_a at the node in the step [s]
  // (nodal_conductivity, three_phase_transfers.hpp): the drag there is formed from it, and the
  // stable step of the points it reaches takes it (three_phase_g2p.hpp).
  std::vector<double> liquid_conductivity, gas_conductivity;

  void resize(std::int64_t n, int n_threads) {
    scatter.assign(n_threads, std::vector<double>(n * L::record, 0.0));
    mass_balance.assign(n_threads, std::vector<double>(n * 6, 0.0));
    pressure_offsets.resize(n_threads);
    for (auto* v : {&solid_velocity, &liquid_velocity, &gas_velocity, &solid_acceleration,
                    &liquid_acceleration, &gas_acceleration, &liquid_traction, &gas_traction,
                    &liquid_leak, &gas_leak})
      v->assign(n, Vec<D>::Zero());
    liquid_theta.assign(n, 0.0), gas_theta.assign(n, 0.0);
    liquid_face_pressure.assign(n, 0.0), gas_face_pressure.assign(n, 0.0);
    liquid_conductivity.assign(n, 0.0), gas_conductivity.assign(n, 0.0);
    gas_free.assign(n, 0), solid_fixed.assign(n, 0), liquid_locked.assign(n, 0),
        gas_locked.assign(n, 0), liquid_surface.assign(n, 0), gas_surface.assign(n, 0),
        liquid_prescribed.assign(n, 0), gas_prescribed.assign(n, 0);
  }
  std::int64_t n_nodes() const { return static_cast<std::int64_t>(solid_velocity.size()); }
  const double* record(std::int64_t i) const { return &scatter[0][i * L::record]; }
  double solid_mass(std::int64_t i) const { return record(i)[L::solid_mass]; }
};

/// Mass rate into the body at the nodes that prescribe a fluid's pressure (`prescribed`), those
/// heavier than `mass_floor` [kg]: -A_i . J_i with J_i = theta_i (v_a - v_s) (`theta`, `v` the
/// fluid's) and A_i = sum_p V_p grad N_i, the body's outward area at node i as the points sample
/// it. That is what the points' flux divergence takes in there (the divergence is corrected to
/// move no mass across any other node, numerics/three_phase_g2p.hpp), so what is counted is what
/// is stored, also where a face node lies on the body's free surface and A_i has a component
/// across the face (docs/balance_laws.md). `by_node`, if given, receives each node's part (zero
/// at the others) [kg/s per out-of-plane measure].
template <int D>
double prescribed_inflow(const ThreePhaseNodes<D>& nodes,
                         const std::vector<std::uint8_t>& prescribed, const std::vector<Vec<D>>& v,
                         const std::vector<double>& theta, double mass_floor,
                         std::vector<double>* by_node) {
  using L = ThreePhaseLayout<D>;
  const std::int64_t n = nodes.n_nodes();
  if (by_node) by_node->assign(n, 0.0);
  double q = 0.0;
  for (std::int64_t i = 0; i < n; ++i) {
    if (!prescribed[i] || nodes.solid_mass(i) <= mass_floor) continue;
    const double* r = nodes.record(i);
    double qi = 0.0;
    for (int d = 0; d < D; ++d)
      qi -= theta[i] * r[L::area + d] * (v[i][d] - nodes.solid_velocity[i][d]);
    q += qi;
    if (by_node) (*by_node)[i] = qi;
  }
  return q;
}

}  // namespace unsatmpm::numerics

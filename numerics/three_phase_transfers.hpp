// The phases of the paper's explicit dynamic three-phase step (docs/cycles.md), plain loops:
//   p2g_three_phase         masses, momenta, drag coefficients and forces of the three phases
//   solve_grid_three_phase  nodal accelerations with the drag implicit node by node, damping on
//                           every phase, boundary conditions, Euler-Cromer velocities
// (g2p and the mass balances are in three_phase_g2p.hpp.)
//
// Balances at a node, per component (lumped masses; docs/balance_laws.md divided by n S_a for the
// fluids):
//   liquid:   M_L a_l = F_L - Q_l (v_l - v_s)        F_L = sum N rho_l V g + sum V P_l grad N + t_L
//   gas:      M_G a_g = F_G - Q_g (v_g - v_s)        (alike)
//   mixture:  M_s a_s + M_l' a_l + M_g' a_g = F_mix  F_mix = sum N m g - sum V sigma . grad N
// Q_a is formed from the conductivities the node gathers (nodal_drag: their mean, not the mean
// of the points' drags). The drag is taken at the new velocities v = v_old + a dt:
// a_a = alpha_a + beta_a a_s, and the mixture balance then gives a_s in closed form. This removes
// the drag time-step limit. A node free of gas (sum N V n S_g <= physics::gas_free_saturation
// sum N V n) is flagged for the mass balances, and its gas moves with the solid.
#pragma once

#include <omp.h>

#include <algorithm>
#include <cmath>

#include "numerics/explicit_transfers.hpp"
#include "numerics/fluid_points.hpp"
#include "numerics/parallel.hpp"
#include "numerics/three_phase_nodes.hpp"
#include "physics/hydraulic_model.hpp"
#include "physics/scheme.hpp"

namespace unsatmpm::numerics {

using physics::MassBalance;  // physics/scheme.hpp
using physics::Skeleton;

/// Point p's state and the laws the explicit step uses more than once, at its porosity and
/// pressures: S_l and the densities (HydraulicModel::state, each law once), the storage matrix
/// (FluidPoints::storage), S_e and the drag coefficients. The values are those the laws give one
/// by one, to the bit; the explicit cycle calls this once per point and step
/// (apply_pressure_increments) where p2g, g2p and the wave speed each evaluated their own.
/// `f`: the fluid state at the point's pressures, hm.state(P_l, P_g).
template <int D>
void refresh_point_laws(const physics::HydraulicModel& hm, std::int64_t p,
                        const physics::LocalFluidState& f, FluidPoints<D>& fp) {
  const double n = fp.porosity[p];
  fp.saturation[p] = f.s_l, fp.liquid_density[p] = f.rho_l, fp.gas_density[p] = f.rho_g;
  fp.storage[p] = physics::storage_matrix(n, f);
  const double se = fp.effective_saturation[p] = f.se;
  fp.liquid_drag[p] = hm.liquid_drag(n, f.s_l, se);
  fp.gas_drag[p] = hm.gas_drag(n, f.s_l, se);
}

/// The same for the points [begin, end) of one material, their states evaluated here.
template <int D>
void refresh_point_laws(const physics::HydraulicModel& hm, std::int64_t begin, std::int64_t end,
                        FluidPoints<D>& fp) {
  for (std::int64_t p = begin; p < end; ++p)
    refresh_point_laws<D>(hm, p, hm.state(fp.liquid_pressure[p], fp.gas_pressure[p]), fp);
}

/// Requires each point's laws current (refresh_point_laws).
template <int D, class K>
void p2g_three_phase(const Grid<D>& grid, const MaterialPoints<D>& mp, const FluidPoints<D>& fp,
                     const Vec<D>& gravity, ThreePhaseNodes<D>& nodes) {
  using L = ThreePhaseLayout<D>;
  const std::int64_t n_mp = static_cast<std::int64_t>(mp.size());
  const int n_threads = static_cast<int>(nodes.scatter.size());
  mp.kernel_memo.prepare(grid, mp.size());
  parallel_region(n_threads, [&] {
    double* buf = cleared_thread_buffer(nodes.scatter);
    TransferStencil<D, K> st;
#pragma omp for schedule(static)
    for (std::int64_t p = 0; p < n_mp; ++p) {
      evaluate_stencil<D, K>(st, grid, mp, p);
      const double vol = mp.volume[p], n = fp.porosity[p], s_l = fp.saturation[p];
      const double p_l = fp.liquid_pressure[p], p_g = fp.gas_pressure[p];
      const double rho_l = fp.liquid_density[p], rho_g = fp.gas_density[p];
      const double m_s = mp.mass[p], m_l = n * s_l * rho_l * vol, m_g = n * (1 - s_l) * rho_g * vol;
      // Conductivities rho_a kappa k_ra / mu_a = rho_a n S_a / drag_a (0 where the fluid is
      // absent: no flux to carry) [s], times the volume.
      const double q_l = fp.liquid_drag[p], q_g = fp.gas_drag[p];
      const double k_l = q_l > 0.0 ? rho_l * n * s_l / q_l * vol : 0.0;
      const double k_g = q_g > 0.0 ? rho_g * n * (1.0 - s_l) / q_g * vol : 0.0;
      const physics::Vec6 vs = vol * physics::total_stress(mp.stress[p], p_l, p_g);
      const double m_mix = m_s + m_l + m_g;
      for (int a = 0; a < st.n; ++a) {
        double* r = buf + st.node[a] * L::record;
        const double w = st.w[a];
        const Vec<D> f_int = stress_dot_gradient<D>(vs, st.grad[a]);
        r[L::solid_mass] += w * m_s;
        r[L::liquid_mass] += w * rho_l * vol;
        r[L::gas_mass] += w * rho_g * vol;
        r[L::liquid_partial_mass] += w * m_l;
        r[L::gas_partial_mass] += w * m_g;
        r[L::liquid_conductivity] += w * k_l;
        r[L::gas_conductivity] += w * k_g;
        r[L::liquid_theta] += w * vol * n * s_l * rho_l;
        r[L::gas_theta] += w * vol * n * (1 - s_l) * rho_g;
        r[L::volume] += w * vol;
        r[L::pore_volume] += w * vol * n;
        r[L::gas_volume] += w * vol * n * (1 - s_l);
        for (int d = 0; d < D; ++d) {
          r[L::area + d] += vol * st.grad[a][d];
          r[L::solid_momentum + d] += w * m_s * mp.velocity[p][d];
          r[L::liquid_momentum + d] += w * rho_l * vol * fp.liquid_velocity[p][d];
          r[L::gas_momentum + d] += w * rho_g * vol * fp.gas_velocity[p][d];
          r[L::mixture_force + d] += w * m_mix * gravity[d] - f_int[d];
          r[L::liquid_force + d] += w * rho_l * vol * gravity[d] + vol * p_l * st.grad[a][d];
          r[L::gas_force + d] += w * rho_g * vol * gravity[d] + vol * p_g * st.grad[a][d];
        }
      }
    }
    reduce_thread_buffers(nodes.scatter);
  });
}

/// One fluid phase at a node, one component: its acceleration as alpha + beta a_s.
struct FluidResponse {
  double alpha, beta;
};

/// Implicit drag: M a = F_damped - Q (w_old + dt (a - a_s)), w = v_fluid - v_solid.
/// Damping acts on the force that drives the fluid (pressure gradient, gravity, boundary
/// pressure), not on the drag that resists it: -alpha |F| sign(v). In flow dominated by drag the
/// drag balances F, so damping F slows the flow by the factor 1 - alpha, as the paper observes
/// for alpha = 0.75 (V1: a damped run is the undamped one at (1 - alpha) T); damping F - Q w
/// instead left the flow unchanged (V1: alpha = 0.75 within 0.001 RMS of alpha = 0), because that
/// difference is the small inertial remainder. docs/balance_laws.md, "Damping".
inline FluidResponse fluid_response(double mass, double drag, double force, double v_fluid,
                                    double v_solid, double dt, double damping) {
  const double sign = v_fluid > 0.0 ? 1.0 : (v_fluid < 0.0 ? -1.0 : 0.0);
  const double damped = force - damping * std::abs(force) * sign;
  const double denom = mass + drag * dt;
  return {(damped - drag * (v_fluid - v_solid)) / denom, drag * dt / denom};
}

/// A fluid's mean conductivity at a node [s] from its record `r`: sum N V K_p / sum N V over the
/// points, and at a node that prescribes the fluid's pressure (`prescribed`) the mean of that and
/// the conductivity at the prescribed pressure (numerics/face_conductivity.hpp), as a finite
/// volume takes the arithmetic mean of a face's two sides. The paper lumps the drag instead,
/// Q = sum N V q_p: a mean of the points' resistances, so that one dry point beside wet ones
/// throttles the node's flux to about twice the dry conductivity. Water could then neither enter
/// a dry soil through a wetted face nor pass a wetting front on from point to point: a sand at
/// 50 kPa of suction took in 0.0020 to 0.0349 kg/m^2 by 2 s on 8 to 128 cells per metre, doubling
/// with each halving of the cells, where Richards' equation on fine cells gives 5.11
/// (docs/balance_laws.md, "Wetting a dry soil through a face"). The main cycle's conductance is a
/// mean of conductivities too (numerics/pressure/conductance.hpp).
template <int D>
double nodal_conductivity(const double* r, int points, int face, bool prescribed) {
  using L = ThreePhaseLayout<D>;
  const double k = prescribed ? 0.5 * (r[points] + r[face]) : r[points];
  return k / r[L::volume];
}

/// The drag coefficient at a node, sum N V times theta / K with K its mean conductivity
/// (nodal_conductivity) and `theta_sum` = sum N V n S_a rho_a, so that the drag-dominated flux
/// theta (v_a - v_s) is -K grad P_a; 0 where no point holds the fluid. Per unit volume of the
/// mixture it is the points' n S_a mu_a / (kappa k_ra) where they agree.
inline double nodal_drag(double theta_sum, double k) { return k > 0.0 ? theta_sum / k : 0.0; }

/// One node, one component, before the solid's boundary condition: the phases' old velocities,
/// the fluids' responses a_a = alpha_a + beta_a a_s, and the mixture balance reduced to
/// inertia a_s = force (the fluids' implicit drag eliminated).
struct NodeComponent {
  double vs, vl, vg;
  FluidResponse liq, gas;
  double inertia, force;
};

/// `solid_damping` damps the mixture's force (the fluids' driving forces take `damping`).
template <int D>
NodeComponent node_component(const ThreePhaseNodes<D>& nodes, std::int64_t i, int d, double dt,
                             double damping, double solid_damping, bool gas_free) {
  using L = ThreePhaseLayout<D>;
  const double* r = nodes.record(i);
  NodeComponent c;
  c.vs = r[L::solid_momentum + d] / r[L::solid_mass];
  c.vl = r[L::liquid_momentum + d] / r[L::liquid_mass];
  c.vg = r[L::gas_momentum + d] / r[L::gas_mass];
  const double q_l = nodal_drag(r[L::liquid_theta], nodes.liquid_conductivity[i]);
  const double q_g = nodal_drag(r[L::gas_theta], nodes.gas_conductivity[i]);
  c.liq =
      fluid_response(r[L::liquid_mass], q_l, r[L::liquid_force + d] + nodes.liquid_traction[i][d],
                     c.vl, c.vs, dt, damping);
  c.gas = fluid_response(r[L::gas_mass], q_g, r[L::gas_force + d] + nodes.gas_traction[i][d], c.vg,
                         c.vs, dt, damping);
  // No flow across an impervious boundary: the fluid keeps the solid's normal velocity. Where
  // there is no gas, the gas has nothing to move: it keeps the solid's velocity (its drag
  // n S_g mu_g / (kappa k_rg) vanishes there, and it would otherwise fall freely).
  // A free-surface node holds each fluid the same way (no flux out of the body's surface).
  if ((nodes.liquid_locked[i] & (1u << d)) || nodes.liquid_surface[i])
    c.liq = {(c.vs - c.vl) / dt, 1.0};
  if (gas_free || (nodes.gas_locked[i] & (1u << d)) || nodes.gas_surface[i])
    c.gas = {(c.vs - c.vg) / dt, 1.0};
  const double f = r[L::mixture_force + d];
  const double sign = c.vs > 0.0 ? 1.0 : (c.vs < 0.0 ? -1.0 : 0.0);
  const double damped = f - solid_damping * std::abs(f) * sign;
  c.force = damped - r[L::liquid_partial_mass] * c.liq.alpha - r[L::gas_partial_mass] * c.gas.alpha;
  c.inertia = r[L::solid_mass] + r[L::liquid_partial_mass] * c.liq.beta +
              r[L::gas_partial_mass] * c.gas.beta;
  return c;
}

/// Stores the accelerations and Euler-Cromer velocities of the three phases for the solid
/// acceleration `as`.
template <int D>
void set_node_component(ThreePhaseNodes<D>& nodes, std::int64_t i, int d, const NodeComponent& c,
                        double as, double dt) {
  const double al = c.liq.alpha + c.liq.beta * as, ag = c.gas.alpha + c.gas.beta * as;
  nodes.solid_acceleration[i][d] = as;
  nodes.liquid_acceleration[i][d] = al;
  nodes.gas_acceleration[i][d] = ag;
  nodes.solid_velocity[i][d] = c.vs + dt * as;
  nodes.liquid_velocity[i][d] = c.vl + dt * al;
  nodes.gas_velocity[i][d] = c.vg + dt * ag;
}

/// Rigid plates in the three-phase step (numerics/rigid_plates.hpp), at the end of
/// solve_grid_three_phase: the plate's solid velocity V = (sum_i I_i vs_i + dt F) / sum I_i with
/// each node's effective inertia I, F the damped sum of the nodes' undamped forces; every node's
/// fluids then respond to the solid acceleration (V - vs_i) / dt as at a free node.
template <int D>
void apply_rigid_plates_three_phase(const std::vector<RigidPlate>& plates, double dt,
                                    double damping, double mass_floor, ThreePhaseNodes<D>& nodes) {
  for (const RigidPlate& plate : plates) {
    const int d = plate.axis;
    double inertia = 0.0, momentum = 0.0, force = 0.0;
    for (const std::int64_t i : plate.nodes) {
      if (nodes.solid_mass(i) <= mass_floor) continue;
      const NodeComponent c = node_component(nodes, i, d, dt, damping, 0.0, nodes.gas_free[i] != 0);
      inertia += c.inertia, momentum += c.inertia * c.vs, force += c.force;
    }
    if (inertia <= 0.0) continue;
    const double v =
        (momentum + dt * damped_plate_force(force, momentum / inertia, damping)) / inertia;
    for (const std::int64_t i : plate.nodes) {
      if (nodes.solid_mass(i) <= mass_floor) continue;
      const NodeComponent c = node_component(nodes, i, d, dt, damping, 0.0, nodes.gas_free[i] != 0);
      set_node_component(nodes, i, d, c, (v - c.vs) / dt, dt);
    }
  }
}

template <int D, Skeleton S>
void solve_grid_three_phase(double dt, double damping, double mass_floor,
                            ThreePhaseNodes<D>& nodes) {
  using L = ThreePhaseLayout<D>;
  const std::int64_t n = nodes.n_nodes();
  parallel_region(static_cast<int>(nodes.scatter.size()), [&] {
#pragma omp for schedule(static)
    for (std::int64_t i = 0; i < n; ++i) {
      const double* r = nodes.record(i);
      if (r[L::solid_mass] <= mass_floor) {
        for (auto* v : {&nodes.solid_velocity, &nodes.liquid_velocity, &nodes.gas_velocity,
                        &nodes.solid_acceleration, &nodes.liquid_acceleration,
                        &nodes.gas_acceleration, &nodes.liquid_leak, &nodes.gas_leak})
          (*v)[i].setZero();
        nodes.gas_free[i] = 0;
        nodes.liquid_conductivity[i] = nodes.gas_conductivity[i] = 0.0;
        continue;
      }
      const bool gas_free = physics::free_of_gas(r[L::gas_volume], r[L::pore_volume]);
      nodes.gas_free[i] = gas_free;
      // Once per node: the components' drags (node_component) and the points' stable steps
      // (three_phase_g2p.hpp) take them.
      nodes.liquid_conductivity[i] = nodal_conductivity<D>(
          r, L::liquid_conductivity, L::liquid_face_conductivity, nodes.liquid_prescribed[i] != 0);
      nodes.gas_conductivity[i] = nodal_conductivity<D>(
          r, L::gas_conductivity, L::gas_face_conductivity, nodes.gas_prescribed[i] != 0);
      for (int d = 0; d < D; ++d) {
        const NodeComponent c = node_component(nodes, i, d, dt, damping, damping, gas_free);
        const bool held = S == Skeleton::rigid || (nodes.solid_fixed[i] & (1u << d));
        set_node_component(nodes, i, d, c, held ? -c.vs / dt : c.force / c.inertia, dt);
      }
      nodes.liquid_theta[i] = r[L::liquid_theta] / r[L::volume];
      nodes.gas_theta[i] = r[L::gas_theta] / r[L::volume];
      for (int d = 0; d < D; ++d) {
        const double leak = r[L::area + d] / r[L::volume];
        nodes.liquid_leak[i][d] = nodes.liquid_prescribed[i] ? 0.0 : leak;
        nodes.gas_leak[i][d] = nodes.gas_prescribed[i] ? 0.0 : leak;
      }
    }
  });
  if constexpr (S != Skeleton::rigid)
    apply_rigid_plates_three_phase(nodes.plates, dt, damping, mass_floor, nodes);
}

}  // namespace unsatmpm::numerics

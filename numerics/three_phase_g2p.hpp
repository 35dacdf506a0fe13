// Grid to points for the three-phase explicit step, then the point updates in the paper's order:
// velocities and position, strain and net stress, and the right-hand sides of the liquid and gas
// mass balances (g2p_three_phase); the mass balances solved for dP_l and
// dP_g at each point (point_pressure_increments, the paper's) or at the nodes
// (nodal_pressure_increments); then porosity (eq. 1), each fluid's mass and the pressures that hold
// it (apply_pressure_increments, numerics/three_phase_pressures.hpp).
//
// Mass balances at a point (docs/balance_laws.md; per unit volume of mixture, theta_a = n S_a
// rho_a):
//   full:        A [dP_l dP_g]^T / dt = -div(theta_a (v_a - v_s)) - S_a rho_a div v_s
//   simplified:  A [dP_l dP_g]^T / dt = -n S_a rho_a div v_a - (1 - n) S_a rho_a div v_s
//                (the advective term (v_a - v_s).grad theta_a of the full form dropped, eqs. 11-12)
// The full form's flux divergence is taken from the nodal fluxes theta_a,i (v_a,i - v_s,i), with
// theta projected to the nodes: sum_i grad N_i . J_i. The product-rule split
// theta_p div(v_a - v_s) + (v_a - v_s).grad theta is not conservative where theta changes within a
// cell: at a wetting front the gas could not leave, and the gas pressure rose to 200 kPa in V1
// (measured) where Darcy's law allows a few kPa.
// A is the storage matrix n d(rho_a S_a)/dP_b. Where there is no gas phase (a node or point free
// of gas, physics::gas_free_saturation, or no gas storage: A_gg = 0) the gas pressure is not an
// unknown: it is held, and the gas a desaturation needs is supplied there and counted as inflow
// (docs/balance_laws.md, "Saturated soil").
#pragma once

#include <array>
#include <limits>
#include <type_traits>
#include <vector>

#include "numerics/parallel.hpp"
#include "numerics/three_phase_transfers.hpp"

namespace unsatmpm::numerics {

/// Interpolated nodal quantities at one point.
template <int D>
struct PointKinematics {
  Vec<D> vs, vl, vg, as, al, ag;
  Eigen::Matrix<double, D, D> grad_vs;
  double div_vl, div_vg;
  double div_flux_l, div_flux_g;  // div(theta_a (v_a - v_s)) from nodal fluxes [kg/m^3/s]
  double reach_l, reach_g;        // the largest nodal conductivity of the stencil [s]
};

template <int D, class K>
PointKinematics<D> interpolate(const TransferStencil<D, K>& st, const ThreePhaseNodes<D>& nodes) {
  PointKinematics<D> k;
  k.vs = k.vl = k.vg = k.as = k.al = k.ag = Vec<D>::Zero();
  k.grad_vs.setZero();
  k.div_vl = k.div_vg = k.div_flux_l = k.div_flux_g = k.reach_l = k.reach_g = 0.0;
  for (int a = 0; a < st.n; ++a) {
    const auto i = st.node[a];
    const double w = st.w[a];
    if (w > 0.0) {
      k.reach_l = std::max(k.reach_l, nodes.liquid_conductivity[i]);
      k.reach_g = std::max(k.reach_g, nodes.gas_conductivity[i]);
    }
    const double* vs = nodes.solid_velocity[i].data();
    const double* vl = nodes.liquid_velocity[i].data();
    const double* vg = nodes.gas_velocity[i].data();
    for (int d = 0; d < D; ++d) {
      const double g = st.grad[a][d];
      k.vs[d] += w * vs[d], k.vl[d] += w * vl[d], k.vg[d] += w * vg[d];
      k.as[d] += w * nodes.solid_acceleration[i][d];
      k.al[d] += w * nodes.liquid_acceleration[i][d];
      k.ag[d] += w * nodes.gas_acceleration[i][d];
      k.div_vl += g * vl[d], k.div_vg += g * vg[d];
      k.div_flux_l += (g - w * nodes.liquid_leak[i][d]) * nodes.liquid_theta[i] * (vl[d] - vs[d]);
      k.div_flux_g += (g - w * nodes.gas_leak[i][d]) * nodes.gas_theta[i] * (vg[d] - vs[d]);
      for (int e = 0; e < D; ++e) k.grad_vs(d, e) += vs[d] * st.grad[a][e];
    }
  }
  return k;
}

/// Pressure increments at a node whose liquid pressure, gas pressure or both are held (prescribed):
/// the held ones do not move, the other row is solved alone, and the held rows' residuals, the
/// mass that enters there, are returned per fluid [kg per unit of A's volume]. With neither held
/// this is the 2 x 2 solve of pressure_increments below.
inline std::array<double, 2> held_pressure_increments(const physics::StorageMatrix& a, double r_l,
                                                      double r_g, double dt, bool hold_liquid,
                                                      bool hold_gas, double& dp_l, double& dp_g);

/// Pressure increments from the mass balances A [dP_l dP_g]^T = dt [r_l r_g]^T at one point or
/// node. With `hold_gas` (no gas phase there), or without gas storage (A_gg = 0), P_g is held and
/// the liquid row alone gives dP_l; the gas row's residual, the gas the desaturation needs, is
/// supplied at the held pressure. Returns that gas mass per unit of A's volume (0 when P_g is
/// solved) [kg/m^3].
inline double pressure_increments(const physics::StorageMatrix& a, double r_l, double r_g,
                                  double dt, bool hold_gas, double& dp_l, double& dp_g) {
  // Gas storage below this (per Pa) means no gas left to store: hold P_g.
  constexpr double no_gas = 1e-300;
  if (hold_gas || std::abs(a.gg) <= no_gas) {
    dp_g = 0.0;
    dp_l = dt * r_l / a.ll;
    return a.gl * dp_l - dt * r_g;
  }
  const double det = a.ll * a.gg - a.lg * a.gl;
  dp_l = dt * (r_l * a.gg - a.lg * r_g) / det;
  dp_g = dt * (a.ll * r_g - a.gl * r_l) / det;
  return 0.0;
}

inline std::array<double, 2> held_pressure_increments(const physics::StorageMatrix& a, double r_l,
                                                      double r_g, double dt, bool hold_liquid,
                                                      bool hold_gas, double& dp_l, double& dp_g) {
  if (!hold_liquid) return {0.0, pressure_increments(a, r_l, r_g, dt, hold_gas, dp_l, dp_g)};
  dp_l = 0.0;
  dp_g = !hold_gas && a.gg > 0.0 ? dt * r_g / a.gg : 0.0;
  return {a.lg * dp_g - dt * r_l, a.gg * dp_g - dt * r_g};
}

/// The speed h / dt_max [m/s] of a fluid's stable explicit step on cells of size h [m]: its waves
/// c^2 [m^2/s^2] against the implicit drag's rate gamma [1/s]. For the mode of frequency
/// w = 2 c / h, the update with the drag implicit and the pressure force explicit is stable for
/// w^2 dt^2 <= 4 + 2 gamma dt, dt_max = (gamma + sqrt(gamma^2 + 4 w^2)) / w^2: h / c without drag
/// (the wave limit), h^2 gamma / (2 c^2) = h^2 / (2 D) where the drag dominates (the explicit
/// diffusion limit of the fluid's Darcy flow, D = c^2 / gamma).
inline double damped_step_speed(double c2, double gamma, double h) {
  const double w2 = 4.0 * c2 / (h * h);
  if (!(w2 > 0.0)) return 0.0;
  return h * w2 / (gamma + std::sqrt(gamma * gamma + 4.0 * w2));
}

/// Largest squared speed [m^2/s^2] h / dt_max of a point's stable explicit step on cells of size
/// h [m]: of the solid's P wave with the fluids' stiffness added, (M + (K_l + K_g) / n) /
/// rho_solid_partial (an upper bound of the undrained wave speed), of each fluid's own wave,
/// c^2 = K_a / rho_a with K_a = n S_a rho_a / A_aa, and of the fluids' coupled waves. The
/// pressures answer the contents through the inverse of the storage matrix,
/// dP_a = sum_b (A^-1)_ab d(n S_b rho_b), so with dv_a/dt = -grad P_a / rho_a the fluids' squared
/// wave speeds are the eigenvalues of W = diag(1 / rho_a) A^-1 diag(n S_b rho_b); the larger one
/// is damped by the weaker of the two drags (damped_step_speed). A_aa alone misses the mode in
/// which both pressures move together at a steady suction: near saturation the retention terms
/// of A nearly cancel along it and only the fluids' compressibility resists. Measured on the
/// ponded block of tests/cycles/test_three_phase_surface.cpp (the gas mobile, k_rg = 1): a point
/// at S_l = 0.998 swung by +-30 kPa in both pressures at every step, at cfl_safety 0.5, with the
/// own waves alone; with the coupled one, 4.2 times as many steps and no swing. Where the gas is
/// held (A_gg = 0), the liquid's own wave alone.
/// This form takes the storage matrix `a` and the drag coefficients (refresh_point_laws).
template <Skeleton S>
double wave_speed_squared(const physics::StorageMatrix& a, double liquid_drag, double gas_drag,
                          double modulus, double n, double s_l, double rho_l, double rho_g,
                          double volume_per_solid_mass, double h) {
  const double cl = n * s_l * rho_l, cg = n * (1.0 - s_l) * rho_g;  // contents [kg/m^3]
  const double kl = cl / a.ll;
  const double kg = a.gg > 0.0 ? cg / a.gg : 0.0;
  double fluids = std::max(kl / rho_l, kg / rho_g);
  if (const double det = a.ll * a.gg - a.lg * a.gl; a.gg > 0.0 && det > 0.0) {
    // W = diag(1 / rho) A^-1 diag(contents): its larger eigenvalue.
    const double wll = a.gg * cl / det / rho_l, wlg = -a.lg * cg / det / rho_l;
    const double wgl = -a.gl * cl / det / rho_g, wgg = a.ll * cg / det / rho_g;
    const double half = 0.5 * (wll - wgg);
    const double top = 0.5 * (wll + wgg) + std::sqrt(std::max(half * half + wlg * wgl, 0.0));
    const double gamma = std::min(liquid_drag / rho_l, gas_drag / rho_g);
    const double v = damped_step_speed(top, gamma, h);
    fluids = std::max(fluids, v * v);
  }
  double solid = 0.0;
  if constexpr (S == Skeleton::deformable)
    solid = (modulus + (kl + kg) / n) * volume_per_solid_mass;
  return std::max(fluids, solid);
}

/// The same with the laws evaluated here, at porosity n and pressures (p_l, p_g).
template <Skeleton S>
double wave_speed_squared(const physics::HydraulicModel& hm, double modulus, double n, double p_l,
                          double p_g, double s_l, double rho_l, double rho_g,
                          double volume_per_solid_mass, double h) {
  const double se = hm.effective_saturation(physics::retention_suction(p_l, p_g));
  return wave_speed_squared<S>(hm.storage(n, p_l, p_g), hm.liquid_drag(n, s_l, se),
                               hm.gas_drag(n, s_l, se), modulus, n, s_l, rho_l, rho_g,
                               volume_per_solid_mass, h);
}

/// Grid to points, up to the mass balances: velocities, position, strain and net stress, the
/// right-hand sides r_l, r_g of the mass balances and div v_s dt, left in the scratch columns of
/// `fp` for point_pressure_increments or nodal_pressure_increments with the storage matrix of
/// the step's start (current, refresh_point_laws).
template <int D, class K, MassBalance Form, class Model>
void g2p_three_phase(const Grid<D>& grid, const ThreePhaseNodes<D>& nodes, const Model& model,
                     const physics::HydraulicModel& hm, double dt, double flip_fraction,
                     std::int64_t begin, std::int64_t end, MaterialPoints<D>& mp,
                     FluidPoints<D>& fp) {
  using MatD = Eigen::Matrix<double, D, D>;
  mp.kernel_memo.prepare(grid, mp.size());
  parallel_region(static_cast<int>(nodes.scatter.size()), [&] {
    TransferStencil<D, K> st;
#pragma omp for schedule(static)
    for (std::int64_t p = begin; p < end; ++p) {
      evaluate_stencil<D, K>(st, grid, mp, p);
      const PointKinematics<D> k = interpolate<D, K>(st, nodes);
      const double g = flip_fraction, pic = 1.0 - flip_fraction;
      mp.velocity[p] = g * (mp.velocity[p] + dt * k.as) + pic * k.vs;
      fp.liquid_velocity[p] = g * (fp.liquid_velocity[p] + dt * k.al) + pic * k.vl;
      fp.gas_velocity[p] = g * (fp.gas_velocity[p] + dt * k.ag) + pic * k.vg;
      mp.position[p] += dt * k.vs;
      mp.displacement[p] += dt * k.vs;

      // Solid: strain, volume, net stress (rotated, then the constitutive increment with the
      // strength of the suction at the start of the step).
      const double volume = mp.volume[p];
      update_solid<D>(model, MatD(dt * k.grad_vs),
                      physics::suction(fp.liquid_pressure[p], fp.gas_pressure[p]), p, mp);
      // The pores grow with div v_s, except where the volume reaches its bound: the opening
      // beyond it is outside the soil (docs/input.md, `maximum_porosity`), so the mass balances
      // take the volume change the point keeps, (V_bound / V - 1) / dt, or the fluids there would
      // see pores that never open, their pressures would fall and their mass n S rho V with them.
      const double field_div = k.grad_vs.trace();
      double div_vs = field_div;
      if (const double bound = hm.max_volume(mp.mass[p]); mp.volume[p] > bound)
        mp.volume[p] = bound, div_vs = (bound / volume - 1.0) / dt;
      const double held = div_vs - field_div;  // 0 below the bound

      // Fluids: the right-hand sides of the mass balances, with the last step's shortfall
      // (apply_pressure_increments) added back; the shortfall's column then keeps the masses at
      // the step's start for apply_pressure_increments.
      const double n = fp.porosity[p], s_l = fp.saturation[p], s_g = 1.0 - s_l;
      const double rho_l = fp.liquid_density[p], rho_g = fp.gas_density[p];
      const double back = 1.0 / (mp.volume[p] * dt);
      if constexpr (Form == MassBalance::full) {
        fp.liquid_rate[p] = -k.div_flux_l - s_l * rho_l * div_vs;
        fp.gas_rate[p] = -k.div_flux_g - s_g * rho_g * div_vs;
      } else {  // div v_a = div (v_a - v_s) + div v_s, the latter held as above
        fp.liquid_rate[p] = -n * s_l * rho_l * (k.div_vl + held) - (1.0 - n) * s_l * rho_l * div_vs;
        fp.gas_rate[p] = -n * s_g * rho_g * (k.div_vg + held) - (1.0 - n) * s_g * rho_g * div_vs;
      }
      fp.liquid_rate[p] += back * fp.liquid_shortfall[p];
      fp.gas_rate[p] += back * fp.gas_shortfall[p];
      fp.liquid_shortfall[p] = n * s_l * rho_l * volume;
      fp.gas_shortfall[p] = n * s_g * rho_g * volume;
      fp.volumetric_strain_increment[p] = div_vs * dt;
      fp.liquid_reach[p] = k.reach_l, fp.gas_reach[p] = k.reach_g;
    }
  });
}

/// The paper's update: each point solves its own mass balances, A_p dP_p = dt r_p, holding P_g
/// at the points free of gas (S_g <= physics::gas_free_saturation). Returns the gas mass supplied
/// at the held points [kg per unit out-of-plane measure in 2D].
template <int D>
double point_pressure_increments(double dt, std::int64_t begin, std::int64_t end,
                                 const MaterialPoints<D>& mp, FluidPoints<D>& fp) {
  double supplied = 0.0;
  for (std::int64_t p = begin; p < end; ++p)
    supplied +=
        mp.volume[p] * pressure_increments(fp.storage[p], fp.liquid_rate[p], fp.gas_rate[p], dt,
                                           1.0 - fp.saturation[p] <= physics::gas_free_saturation,
                                           fp.liquid_increment[p], fp.gas_increment[p]);
  return supplied;
}

/// The liquid's mass rate of a point's own volume change, -S_l rho_l div v_s [kg/m^3/s], where the
/// point holds no gas phase and `OwnVolumeChange` (nodal_pressure_increments); else 0.
template <bool OwnVolumeChange, int D>
double own_volume_rate(const FluidPoints<D>& fp, std::int64_t p, double dt) {
  if constexpr (!OwnVolumeChange) return 0.0;
  if (1.0 - fp.saturation[p] > physics::gas_free_saturation) return 0.0;
  return -fp.saturation[p] * fp.liquid_density[p] * fp.volumetric_strain_increment[p] / dt;
}

/// Masses of each fluid added at the nodes by nodal_pressure_increments [kg per out-of-plane
/// measure] (null: none). A source of its own (the main cycle's flow correction) has the same
/// members: n_columns values per point summed at the nodes with the storage and rates (columns,
/// called per point inside the parallel loop), and at_nodes(sums, stride), called once between
/// the sums and the solve, returning the masses.
struct NodalMasses {
  static constexpr int n_columns = 0;
  const std::array<std::vector<double>, 2>* masses = nullptr;
  void columns(std::int64_t /*p*/, double* /*q*/) const {}
  const std::array<std::vector<double>, 2>* at_nodes(const double* /*sums*/, int /*stride*/) const {
    return masses;
  }
};

/// The mass balances at the nodes (case key pressure_update: nodal). With linear shape
/// functions the flux divergence is constant in a cell, so in the pointwise update every point of
/// a cell gets the same increment and the pressure field is piecewise constant: a point off the
/// cell centre errs by the pressure slope times its offset (in V1 with 4 points per cell, 2.5 %
/// of s0 at T = 0.05). Here the storage and the mass rates are projected to the nodes,
///   M_i = sum_p N_i(x_p) V_p A_p,   R_i = sum_p N_i(x_p) V_p r_p,
/// each node solves M_i dP_i = dt R_i (holding P_g at the nodes free of gas, ThreePhaseNodes::
/// gas_free, and where M_i,gg = 0), and the points receive
/// dP_p = sum_i N_i(x_p) dP_i: a continuous, piecewise-linear increment. The first-order mass
/// change is unchanged, sum_p V_p A_p dP_p = sum_i M_i dP_i = dt sum_p V_p r_p (partition of
/// unity). Smoothing the points' increments or rates instead (tried in V1) left zero-mean patterns
/// within a cell, which the nodal forces cannot see and nothing removes, or handed gas mass to
/// nearly saturated points with A_gg ~ 0 (blow-up). Returns the gas mass supplied at the nodes
/// where P_g is held [kg per unit out-of-plane measure in 2D].
/// With `OwnVolumeChange` (the explicit cycle) a point free of gas takes the liquid of its own
/// volume change itself, at its own storage (own_volume_rate), and the nodes solve the rest of its
/// balance (the fluxes): the nodal form alone is unstable there with water's stiffness
/// (docs/balance_laws.md, "Saturated soil at the saturation kink"). The gas that increment asks
/// of the point's held gas is supplied (counted).
/// `mass_balance`: per-thread scratch, sized here (6 values per node and the source's columns);
/// `held[a]`: 1 at the nodes that hold fluid a's pressure (empty: none; the main cycle's mechanics
/// holds its prescribed nodes, cycles/undrained.hpp). `source`: masses added at the nodes
/// (NodalMasses; the main cycle's flow correction, cycles/flow_correction.hpp, whose projection
/// rides on this one's). With `HoldGasFree` the nodes free of gas at the points' current state
/// (gas volume sum_p N_i V_p n_p S_g,p at most physics::gas_free_saturation of the pore volume
/// around them, as ThreePhaseNodes::gas_free) hold their gas pressure too: the main cycle's held
/// nodes are the flow's, set at its interval's start, and a neighbourhood that loses its gas over
/// the interval would otherwise take a gas rate on a vanishing storage (on the embankment with the
/// occluded gas giving way the increments grew from -5 Pa a sub-step to -1e106 Pa within some 40;
/// docs/balance_laws.md, "Saturated soil").
/// Returns the mass of each fluid that enters at the held nodes.
template <int D, class K, bool OwnVolumeChange, class Source = NodalMasses,
          bool HoldGasFree = false>
std::array<double, 2> nodal_pressure_increments(
    const Grid<D>& grid, const MaterialPoints<D>& mp, double dt,
    std::vector<std::vector<double>>& mass_balance,
    const std::array<const std::vector<std::uint8_t>*, 2>& held, FluidPoints<D>& fp,
    Source&& source = Source{}) {
  constexpr int n_source = std::remove_reference_t<Source>::n_columns;
  constexpr int gas_at = 6 + n_source;  // with HoldGasFree: pore and gas volume around the node
  constexpr int stride = gas_at + (HoldGasFree ? 2 : 0);
  const std::int64_t n_mp = static_cast<std::int64_t>(mp.size());
  const std::int64_t n_nodes = grid.n_nodes();
  const int n_threads = static_cast<int>(mass_balance.size());
  for (auto& b : mass_balance) b.resize(static_cast<std::size_t>(stride * n_nodes));
  double supplied_l = 0.0, supplied_g = 0.0;
  const auto holds = [&](int a, std::int64_t i) {
    return held[a] != nullptr && !held[a]->empty() && (*held[a])[i] != 0;
  };
  mp.kernel_memo.prepare(grid, mp.size());
  parallel_region(n_threads, [&] {
    double* buf = cleared_thread_buffer(mass_balance);
    TransferStencil<D, K, false> st;  // weights alone
#pragma omp for schedule(static)
    for (std::int64_t p = 0; p < n_mp; ++p) {
      evaluate_stencil<D, K>(st, grid, mp, p);
      const double v = mp.volume[p];
      const physics::StorageMatrix& a = fp.storage[p];
      const double own = own_volume_rate<OwnVolumeChange>(fp, p, dt);
      double q[stride] = {
          v * a.ll,          v * a.lg, v * a.gl, v * a.gg, v * (fp.liquid_rate[p] - own),
          v * fp.gas_rate[p]};
      source.columns(p, q + 6);
      if constexpr (HoldGasFree) {
        q[gas_at] = v * fp.porosity[p];
        q[gas_at + 1] = q[gas_at] * (1.0 - fp.saturation[p]);
      }
      for (int k = 0; k < st.n; ++k) {
        double* r = buf + stride * st.node[k];
        for (int j = 0; j < stride; ++j) r[j] += st.w[k] * q[j];
      }
    }
    reduce_thread_buffers(mass_balance);
  });
  double* sums = mass_balance[0].data();
  const std::array<std::vector<double>, 2>* nodal_mass = source.at_nodes(sums, stride);
  parallel_region(n_threads, [&] {
    // Node by node: the increments overwrite the first two sums (the stencil: weights alone).
    TransferStencil<D, K, false> st;
#pragma omp for schedule(static) reduction(+ : supplied_l, supplied_g)
    for (std::int64_t i = 0; i < n_nodes; ++i) {
      double* r = sums + stride * i;
      double dl = 0.0, dg = 0.0;
      if (nodal_mass) r[4] += (*nodal_mass)[0][i] / dt, r[5] += (*nodal_mass)[1][i] / dt;
      if (r[0] > 0.0) {
        bool gas_free = false;
        if constexpr (HoldGasFree) gas_free = physics::free_of_gas(r[gas_at + 1], r[gas_at]);
        const auto in = held_pressure_increments({r[0], r[1], r[2], r[3]}, r[4], r[5], dt,
                                                 holds(0, i), holds(1, i) || gas_free, dl, dg);
        supplied_l += in[0], supplied_g += in[1];
      }
      r[0] = dl, r[1] = dg;
    }
#pragma omp for schedule(static) reduction(+ : supplied_g)
    for (std::int64_t p = 0; p < n_mp; ++p) {
      evaluate_stencil<D, K>(st, grid, mp, p);
      double dl = 0.0, dg = 0.0;
      for (int k = 0; k < st.n; ++k) {
        const double* r = sums + stride * st.node[k];
        dl += st.w[k] * r[0], dg += st.w[k] * r[1];
      }
      const physics::StorageMatrix& a = fp.storage[p];
      if (const double own = own_volume_rate<OwnVolumeChange>(fp, p, dt); own != 0.0) {
        const double own_dl = a.ll > 0.0 ? dt * own / a.ll : 0.0;
        dl += own_dl;
        supplied_g += mp.volume[p] * a.gl * own_dl;
      }
      fp.liquid_increment[p] = dl, fp.gas_increment[p] = dg;
    }
  });
  return {supplied_l, supplied_g};
}

/// The explicit cycle's call: its nodes' scratch and gas-free flags; each point free of gas takes
/// its own volume change.
template <int D, class K>
double nodal_pressure_increments(const Grid<D>& grid, const MaterialPoints<D>& mp, double dt,
                                 ThreePhaseNodes<D>& nodes, FluidPoints<D>& fp) {
  return nodal_pressure_increments<D, K, true>(grid, mp, dt, nodes.mass_balance,
                                               {nullptr, &nodes.gas_free}, fp)[1];
}

}  // namespace unsatmpm::numerics

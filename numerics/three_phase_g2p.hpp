// Grid to points for the three-phase explicit step, then the point updates in the paper's order:
// velocities and position, strain and net stress, the liquid and gas mass balances giving
// dP_l and dP_g, porosity (eq. 1), then saturation and densities from the new pressures.
//
// Mass balances at a point (SPEC §3; per unit volume of mixture, theta_a = n S_a rho_a):
//   full:        A [dP_l dP_g]^T / dt = -div(theta_a (v_a - v_s)) - S_a rho_a div v_s
//   simplified:  A [dP_l dP_g]^T / dt = -n S_a rho_a div v_a - (1 - n) S_a rho_a div v_s
//                (the advective term (v_a - v_s).grad theta_a of the full form dropped, eqs. 11-12)
// The full form's flux divergence is taken from the nodal fluxes theta_a,i (v_a,i - v_s,i), with
// theta projected to the nodes: sum_i grad N_i . J_i. The product-rule split
// theta_p div(v_a - v_s) + (v_a - v_s).grad theta is not conservative where theta changes within a
// cell: at a wetting front the gas could not leave, and the gas pressure rose to 200 kPa in V1
// (measured) where Darcy's law allows a few kPa.
// A is the storage matrix n d(rho_a S_a)/dP_b. Where there is no gas storage (saturated, no gas
// compressibility left: A_gg = 0) the gas pressure is not an unknown: it is held.
#pragma once

#include <limits>

#include "numerics/three_phase_transfers.hpp"

namespace unsatmpm::numerics {

struct ThreePhaseReport {
  double max_wave_speed = 0.0;  // over phases and points, plus the largest speed [m/s]
  std::int64_t first_bad = -1;
};

/// Interpolated nodal quantities at one point.
template <int D>
struct PointKinematics {
  Vec<D> vs, vl, vg, as, al, ag;
  Eigen::Matrix<double, D, D> grad_vs;
  double div_vl, div_vg;
  double div_flux_l, div_flux_g;  // div(theta_a (v_a - v_s)) from nodal fluxes [kg/m^3/s]
};

template <int D, class K>
PointKinematics<D> interpolate(const PointStencil<D, K>& st, const ThreePhaseNodes<D>& nodes) {
  PointKinematics<D> k;
  k.vs = k.vl = k.vg = k.as = k.al = k.ag = Vec<D>::Zero();
  k.grad_vs.setZero();
  k.div_vl = k.div_vg = k.div_flux_l = k.div_flux_g = 0.0;
  for (int a = 0; a < st.n; ++a) {
    const auto i = st.node[a];
    const double w = st.w[a];
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
      k.div_flux_l += g * nodes.liquid_theta[i] * (vl[d] - vs[d]);
      k.div_flux_g += g * nodes.gas_theta[i] * (vg[d] - vs[d]);
      for (int e = 0; e < D; ++e) k.grad_vs(d, e) += vs[d] * st.grad[a][e];
    }
  }
  return k;
}

/// Pressure increments from the mass balances at one point.
inline void pressure_increments(const physics::StorageMatrix& a, double r_l, double r_g, double dt,
                                double& dp_l, double& dp_g) {
  // Gas storage below this (per Pa) means no gas left to store: hold P_g.
  constexpr double no_gas = 1e-300;
  if (std::abs(a.gg) <= no_gas) {
    dp_g = 0.0;
    dp_l = dt * r_l / a.ll;
    return;
  }
  const double det = a.ll * a.gg - a.lg * a.gl;
  dp_l = dt * (r_l * a.gg - a.lg * r_g) / det;
  dp_g = dt * (a.ll * r_g - a.gl * r_l) / det;
}

/// Largest squared wave speed at a point [m^2/s^2]: each fluid c^2 = n S_a / A_aa (its bulk
/// stiffness n S_a rho_a / A_aa over rho_a), and the solid's P wave with the fluids' stiffness
/// added, (M + (K_l + K_g) / n) / rho_solid_partial: an upper bound of the undrained wave speed.
inline double wave_speed_squared(const HydraulicModel& hm, double modulus, Skeleton skeleton,
                                 double n, double p_l, double p_g, double s_l, double rho_l,
                                 double rho_g, double volume_per_solid_mass) {
  const physics::StorageMatrix a = hm.storage(n, p_l, p_g);
  const double kl = n * s_l * rho_l / a.ll;
  const double kg = a.gg > 0.0 ? n * (1.0 - s_l) * rho_g / a.gg : 0.0;
  const double solid =
      skeleton == Skeleton::rigid ? 0.0 : (modulus + (kl + kg) / n) * volume_per_solid_mass;
  return std::max({kl / rho_l, kg / rho_g, solid});
}

template <int D, class K, class Model>
ThreePhaseReport g2p_three_phase(const Grid<D>& grid, const ThreePhaseNodes<D>& nodes,
                                 const Model& model, const HydraulicModel& hm, MassBalance form,
                                 Skeleton skeleton, double dt, double flip_fraction,
                                 std::int64_t begin, std::int64_t end, MaterialPoints<D>& mp,
                                 FluidPoints<D>& fp) {
  using MatD = Eigen::Matrix<double, D, D>;
  const double modulus = wave_modulus(model);
  double max_c2 = 0.0, max_v2 = 0.0;
  std::int64_t bad = std::numeric_limits<std::int64_t>::max();
#pragma omp parallel num_threads(static_cast <int>(nodes.scatter.size())) \
    reduction(max                                                         \
              : max_c2, max_v2) reduction(min                             \
                                          : bad)
  {
    PointStencil<D, K> st;
#pragma omp for schedule(static)
    for (std::int64_t p = begin; p < end; ++p) {
      st.evaluate(grid, mp.position[p], mp.half_size[p]);
      const PointKinematics<D> k = interpolate<D, K>(st, nodes);
      const double g = flip_fraction, pic = 1.0 - flip_fraction;
      mp.velocity[p] = g * (mp.velocity[p] + dt * k.as) + pic * k.vs;
      fp.liquid_velocity[p] = g * (fp.liquid_velocity[p] + dt * k.al) + pic * k.vl;
      fp.gas_velocity[p] = g * (fp.gas_velocity[p] + dt * k.ag) + pic * k.vg;
      mp.position[p] += dt * k.vs;
      mp.displacement[p] += dt * k.vs;

      // Solid: strain, volume, net stress (rotated, then the constitutive increment).
      update_solid<D>(model, MatD(dt * k.grad_vs), p, mp);

      // Fluids: mass balances, then porosity, pressures and the state they determine.
      const double n = fp.porosity[p], s_l = fp.saturation[p], s_g = 1.0 - s_l;
      const double rho_l = fp.liquid_density[p], rho_g = fp.gas_density[p];
      const double div_vs = k.grad_vs.trace();
      double r_l, r_g;
      if (form == MassBalance::full) {
        r_l = -k.div_flux_l - s_l * rho_l * div_vs;
        r_g = -k.div_flux_g - s_g * rho_g * div_vs;
      } else {
        r_l = -n * s_l * rho_l * k.div_vl - (1.0 - n) * s_l * rho_l * div_vs;
        r_g = -n * s_g * rho_g * k.div_vg - (1.0 - n) * s_g * rho_g * div_vs;
      }
      const physics::StorageMatrix a = hm.storage(n, fp.liquid_pressure[p], fp.gas_pressure[p]);
      double dp_l, dp_g;
      pressure_increments(a, r_l, r_g, dt, dp_l, dp_g);
      fp.porosity[p] = n + (1.0 - n) * div_vs * dt;
      const double p_l = fp.liquid_pressure[p] += dp_l;
      const double p_g = fp.gas_pressure[p] += dp_g;
      fp.saturation[p] = hm.saturation(physics::suction(p_l, p_g));
      fp.liquid_density[p] = hm.liquid_density(p_l);
      fp.gas_density[p] = hm.gas_density(p_g);

      const double c2 =
          wave_speed_squared(hm, modulus, skeleton, fp.porosity[p], p_l, p_g, fp.saturation[p],
                             fp.liquid_density[p], fp.gas_density[p], mp.volume[p] / mp.mass[p]);
      max_c2 = std::max(max_c2, c2);
      max_v2 = std::max({max_v2, mp.velocity[p].squaredNorm(), fp.liquid_velocity[p].squaredNorm(),
                         fp.gas_velocity[p].squaredNorm()});
      if (!(std::isfinite(c2 + p_l + p_g + mp.stress[p].sum() + max_v2) &&
            grid.contains(mp.position[p])))
        bad = std::min(bad, p);
    }
  }
  return {std::sqrt(max_c2) + std::sqrt(max_v2),
          bad == std::numeric_limits<std::int64_t>::max() ? -1 : bad};
}

}  // namespace unsatmpm::numerics

// The explicit three-phase step's last phase (apply_pressure_increments): porosity, each fluid's
// mass at each point, and the pressures that hold it.
//
// The paper updates the pressures linearly, P += dP with A dP = dt r (A the storage matrix at the
// step's start). Its mass n S_a rho_a V then differs from the mass the balances assigned,
// m + V (A dP + S_a rho_a eps) (eps = div v_s dt), by the update's second-order remainder: where
// the storage changes fast with the pressures, near S_max and across the saturation kink, that
// remainder is not small and it does not average out. On the embankment in the explicit full form
// it was the whole of the water lost after the points held at their volume bound were fixed:
// -5.9e-4 of the water at 150 s, at moving points with S_l 0.9498-0.9500 and suction 1-7 kPa
// (measured), and a block dilating at zero suction (tests/cycles/test_three_phase_cycle.cpp) saw
// its saturation fall from 0.95 to 0.48 in one step. So here each point takes the mass assigned
// to it and its pressures are those that hold that mass in its pores (physics::
// pressures_from_contents, with the linear update as the start), as the main cycle's mechanics
// does (cycles/undrained.hpp). The inversion stops where its Newton step would move no pressure by
// more than explicit_pressure_tolerance; what the state then holds short of the assigned mass
// (FluidPoints::liquid_shortfall) is added to the point's next balance, so the masses telescope
// over the run instead of dropping a remainder at every step (docs/balance_laws.md, "The pressures
// that hold the masses").
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "numerics/parallel.hpp"
#include "numerics/three_phase_g2p.hpp"
#include "physics/fluid_contents.hpp"

namespace unsatmpm::numerics {

struct ThreePhaseReport {
  double max_wave_speed = 0.0;  // over phases and points, plus the largest speed [m/s]
  std::int64_t first_bad = -1;  // a point that left the grid, or whose state is not finite or
                                // holds no pressures for its masses
  double gas_supplied = 0.0;    // where P_g is held: the gas the state holds beyond the balance's
                                // [kg per unit out-of-plane measure in 2D]
};

/// The pressure accuracy [Pa] of the pressures that hold a point's masses. A millipascal is far
/// below any pressure the step resolves; the masses are kept whatever it is, through the
/// shortfall carried to the next step, which moves each pressure by about this much.
inline constexpr double explicit_pressure_tolerance = 1e-3;

/// The increments applied. Per point: the porosity 1 - V_s / V (eq. 1 with incompressible grains,
/// V_s = m_s / rho_s, integrated over the step's volume change), each fluid's mass m + V (A dP +
/// S_a rho_a eps) + the last shortfall (m the mass at the step's start, left by g2p_three_phase in
/// the shortfall's column), the pressures that hold it from P + dP, the laws there
/// (refresh_point_laws) and the new shortfall. Where the point holds no gas phase (P_g then keeps
/// its value, whatever its nodes' increment), or the linear update emptied its gas, P_g is held
/// and the gas its state holds is supplied (counted). Reports
/// the wave speed of the next step and the first point that failed.
template <int D, Skeleton S>
ThreePhaseReport apply_pressure_increments(const Grid<D>& grid, const physics::HydraulicModel& hm,
                                           double modulus, std::int64_t begin, std::int64_t end,
                                           const MaterialPoints<D>& mp, FluidPoints<D>& fp,
                                           int n_threads) {
  double max_c2 = 0.0, max_v2 = 0.0, supplied = 0.0;
  std::int64_t bad = std::numeric_limits<std::int64_t>::max();
  parallel_region(n_threads, [&] {
#pragma omp for schedule(static) reduction(max : max_c2, max_v2) reduction(min : bad) \
    reduction(+ : supplied)
    for (std::int64_t p = begin; p < end; ++p) {
      const double v = mp.volume[p], eps = fp.volumetric_strain_increment[p];
      const double dp_l = fp.liquid_increment[p], dp_g = fp.gas_increment[p];
      const physics::StorageMatrix& a = fp.storage[p];
      const double s_l0 = fp.saturation[p];
      // The shortfall's columns hold each fluid's mass at the step's start here (g2p_three_phase).
      const double m_l = fp.liquid_shortfall[p] +
                         v * (a.ll * dp_l + a.lg * dp_g + s_l0 * fp.liquid_density[p] * eps);
      const double m_g = fp.gas_shortfall[p] +
                         v * (a.gl * dp_l + a.gg * dp_g + (1.0 - s_l0) * fp.gas_density[p] * eps);
      const double n = 1.0 - mp.mass[p] / (hm.solid_density * v), pores = n * v;
      // A point free of gas holds its P_g against its nodes' gas increments too: it has no gas
      // for them to act on, and taken up there they dragged the gas pressure of the saturated
      // points beside a drained node to vacuum (docs/balance_laws.md, "A drained boundary in the
      // explicit cycle").
      const bool gas_free = 1.0 - s_l0 <= physics::gas_free_saturation;
      bool held = gas_free || !(m_g > 0.0);
      double p_l = fp.liquid_pressure[p] + dp_l, p_g = fp.gas_pressure[p] + (gas_free ? 0.0 : dp_g);
      physics::LocalFluidState f{};
      const double tol =
          physics::mass_keeping_tolerance(explicit_pressure_tolerance, a, m_l, m_g, v);
      bool found = pores > 0.0 && physics::pressures_from_contents(hm, m_l / pores, m_g / pores,
                                                                   held, p_l, p_g, &f, tol) >= 0;
      if (!found && !held && pores > 0.0) {  // a gas the linear step emptied: hold it instead
        p_l = fp.liquid_pressure[p] + dp_l, p_g = fp.gas_pressure[p] + dp_g;
        held = true;
        found =
            physics::pressures_from_contents(hm, m_l / pores, 0.0, true, p_l, p_g, &f, tol) >= 0;
      }
      // A density the law cannot give at a physical pressure is a failure too (as in the main
      // cycle's, cycles/undrained.hpp); the failure's state is kept for its report.
      if (!found || !std::isfinite(p_l + p_g) || !(f.rho_l > 0.0 && f.rho_g > 0.0)) {
        fp.porosity[p] = n, fp.liquid_pressure[p] = p_l, fp.gas_pressure[p] = p_g;
        bad = std::min(bad, p);
        continue;
      }
      fp.porosity[p] = n, fp.liquid_pressure[p] = p_l, fp.gas_pressure[p] = p_g;
      refresh_point_laws<D>(hm, p, f, fp);
      const double gas = pores * (1.0 - f.s_l) * f.rho_g;
      fp.liquid_shortfall[p] = m_l - pores * f.s_l * f.rho_l;
      fp.gas_shortfall[p] = held ? 0.0 : m_g - gas;
      if (held) supplied += gas - m_g;

      // The drags at the largest conductivity the point's fluxes came from, where that exceeds
      // its own (nodal_drag, numerics/three_phase_transfers.hpp: a dry point beside a wet node
      // takes the wet node's flux into its own storage).
      const auto drag = [&](double own, double content, double reach) {
        return reach > 0.0 ? std::min(own, content / reach) : own;
      };
      const double c2 = wave_speed_squared<S>(
          fp.storage[p], drag(fp.liquid_drag[p], f.rho_l * n * f.s_l, fp.liquid_reach[p]),
          drag(fp.gas_drag[p], f.rho_g * n * (1.0 - f.s_l), fp.gas_reach[p]), modulus, n, f.s_l,
          f.rho_l, f.rho_g, v / mp.mass[p], grid.min_spacing());
      max_c2 = std::max(max_c2, c2);
      max_v2 = std::max({max_v2, mp.velocity[p].squaredNorm(), fp.liquid_velocity[p].squaredNorm(),
                         fp.gas_velocity[p].squaredNorm()});
      if (!(std::isfinite(c2 + mp.stress[p].sum() + max_v2) && grid.contains(mp.position[p])))
        bad = std::min(bad, p);
    }
  });
  return {std::sqrt(max_c2) + std::sqrt(max_v2),
          bad == std::numeric_limits<std::int64_t>::max() ? -1 : bad, supplied};
}

}  // namespace unsatmpm::numerics

// The Darcy form of the fluid mass balances at one material point (docs/balance_laws.md, the
// implicit cycle), with the derivatives an analytic Jacobian needs.
//
// For each fluid a in {l, g}, with lambda_a = kappa k_ra(S_e) / mu_a [m^2/(Pa s)]:
//   mass flux     J_a = rho_a lambda_a (-grad P_a + rho_a g)          [kg/(m^2 s)]
//   solid source  sigma_a = S_a rho_a div v_s                          [kg/(m^3 s)]
//   storage       A = n d(rho_a S_a)/dP_b  (physics::storage_matrix)   [kg/(m^3 Pa)]
// and, for the simplified form only, the advective term that form drops, put back with the
// opposite sign: T_a = J_a . grad ln theta_a, theta_a = n S_a rho_a, so that
//   full:        A dP/dt = -div J - sigma
//   simplified:  A dP/dt = -div J - sigma + T       (since -theta div w = -div(theta w) + w.grad
//   theta)
// grad ln theta_a is taken from the point's own pressure gradients (and the porosity's gradient,
// fixed during an integration): grad ln theta_a = L_al grad P_l + L_ag grad P_g + grad ln n, with
// L the derivatives of ln(S_a rho_a) with respect to the pressures. Where S_a is below
// `min_phase_saturation` its saturation part is left out (ln S_a has no limit at S_a = 0).
//
// Suction s = max(P_g - P_l, 0): saturated points (s = 0) have no dependence on suction, so every
// d/ds term is zero there (one-sided at the kink, as the retention laws define it).
#pragma once

#include <array>

#include "numerics/fluid_points.hpp"  // liquid_phase, gas_phase
#include "numerics/grid.hpp"
#include "physics/hydraulic_model.hpp"
#include "physics/scheme.hpp"

namespace unsatmpm::numerics {

inline constexpr double min_phase_saturation = 1e-9;

/// Everything the assembly needs from one point for given pressures and gradients.
template <int D>
struct PointFlow {
  std::array<Vec<D>, 2> flux;       // J_a
  std::array<double, 2> source;     // sigma_a
  std::array<double, 2> advective;  // T_a (simplified form only, else 0)
  physics::StorageMatrix storage;   // A
  // Derivatives with respect to the point's pressure values P_b (columns b) ...
  std::array<std::array<Vec<D>, 2>, 2> d_flux;  // dJ_a/dP_b
  std::array<std::array<double, 2>, 2> d_source;
  std::array<std::array<double, 2>, 2> d_advective;
  std::array<physics::StorageMatrix, 2> d_storage;  // dA/dP_b
  // ... and with respect to the gradients grad P_b: dJ_a/d(grad P_b) = -c_a delta_ab I, and
  // dT_a/d(grad P_b), a vector.
  std::array<double, 2> conductivity;  // c_a = rho_a lambda_a
  std::array<std::array<Vec<D>, 2>, 2> d_advective_d_grad;
  // J_a per unit relative permeability, rho_a (kappa / mu_a) (-grad P_a + rho_a g), and (simplified
  // form only, else zero) grad ln theta_a: what a relative permeability taken from elsewhere than
  // the point's pressures (point_flow's `given`) multiplies in J_a and T_a.
  std::array<Vec<D>, 2> unit_flux;
  std::array<Vec<D>, 2> grad_ln_theta;
};

struct PointFlowInput {
  double porosity;  // n [-]
  double div_vs;    // div v_s over the interval [1/s]
};

/// Flow quantities at one point. p[a] and grad[a] are the interpolated pressure and gradient of
/// fluid a; grad_ln_n is grad(ln n) at the point (zero for uniform porosity). The simplified form
/// evaluates T and its derivatives; `Jacobian` evaluates dA/dP (the costliest part, which only the
/// Jacobian needs). Both are compile-time choices, made once per pass over the points. With
/// `given`, the relative permeabilities k_ra are those values (taken from the nodes, the caller's
/// business) instead of the laws at p, and the derivatives leave out their dependence.
template <int D, physics::MassBalance Form, bool Jacobian>
PointFlow<D> point_flow(const physics::HydraulicModel& hm, const PointFlowInput& in,
                        const std::array<double, 2>& p, const std::array<Vec<D>, 2>& grad,
                        const Vec<D>& gravity, const Vec<D>& grad_ln_n,
                        const std::array<double, 2>* given = nullptr) {
  PointFlow<D> f;
  const double s = physics::retention_suction(p[liquid_phase], p[gas_phase]);
  const double sat = hm.saturation(s);
  const double d_sat = hm.d_saturation(s);
  // Where S depends on the pressures: unsaturated, or an occluded gas giving way at s <= 0
  // (physics/retention.hpp). ds/dP_b: -1 for the liquid, +1 for the gas there.
  const bool unsaturated = s > 0.0 || d_sat != 0.0;
  const std::array<double, 2> ds_dp = unsaturated ? std::array{-1.0, 1.0} : std::array{0.0, 0.0};
  const double d2_sat = unsaturated ? hm.d2_saturation(s) : 0.0;
  const double se = hm.effective_saturation(s);
  const double d_se = unsaturated ? hm.d_effective_saturation(s) : 0.0;
  const std::array<double, 2> phase_sat{sat, 1.0 - sat};
  const std::array<double, 2> d_phase_sat{d_sat, -d_sat};  // dS_a/ds
  const std::array<double, 2> rho{hm.liquid_density(p[liquid_phase]), hm.gas_density(p[gas_phase])};
  const std::array<double, 2> d_rho{hm.liquid_d_density(p[liquid_phase]),
                                    hm.gas_d_density(p[gas_phase])};
  const std::array<double, 2> d2_rho{hm.liquid_d2_density(p[liquid_phase]),
                                     hm.gas_d2_density(p[gas_phase])};
  const std::array<double, 2> k = given ? *given
                                        : std::array{hm.liquid_relative_permeability_value(se),
                                                     hm.gas_relative_permeability_value(se)};
  const std::array<double, 2> d_k = given
                                        ? std::array{0.0, 0.0}
                                        : std::array{hm.liquid_relative_permeability_derivative(se),
                                                     hm.gas_relative_permeability_derivative(se)};
  const std::array<double, 2> mobility{hm.intrinsic_permeability / hm.liquid_viscosity,
                                       hm.intrinsic_permeability / hm.gas_viscosity};

  for (int a = 0; a < 2; ++a) {
    const double c = rho[a] * mobility[a] * k[a];
    f.conductivity[a] = c;
    const Vec<D> drive = -grad[a] + rho[a] * gravity;
    f.unit_flux[a] = rho[a] * mobility[a] * drive;
    f.grad_ln_theta[a] = Vec<D>::Zero();
    f.flux[a] = c * drive;
    f.source[a] = phase_sat[a] * rho[a] * in.div_vs;
    for (int b = 0; b < 2; ++b) {
      // dc/dP_b = delta_ab rho' mobility k + rho mobility k'(S_e) S_e'(s) ds/dP_b
      const double dc = (a == b ? d_rho[a] * mobility[a] * k[a] : 0.0) +
                        rho[a] * mobility[a] * d_k[a] * d_se * ds_dp[b];
      f.d_flux[a][b] = dc * drive;
      if (a == b) f.d_flux[a][b] += c * d_rho[a] * gravity;
      f.d_source[a][b] =
          (d_phase_sat[a] * ds_dp[b] * rho[a] + (a == b ? phase_sat[a] * d_rho[a] : 0.0)) *
          in.div_vs;
    }
  }
  f.storage = hm.storage(in.porosity, p[liquid_phase], p[gas_phase]);
  if constexpr (Jacobian) {
    const physics::StorageDerivatives ds =
        hm.storage_derivatives(in.porosity, p[liquid_phase], p[gas_phase]);
    f.d_storage = {ds.d_p_l, ds.d_p_g};
  }

  f.advective = {0.0, 0.0};
  for (auto& row : f.d_advective) row = {0.0, 0.0};
  for (auto& row : f.d_advective_d_grad) row = {Vec<D>::Zero(), Vec<D>::Zero()};
  if constexpr (Form == physics::MassBalance::full) return f;
  for (int a = 0; a < 2; ++a) {
    // ln(S_a rho_a): r = (dS_a/ds) / S_a, with r' = (d2S_a S_a - dS_a^2) / S_a^2.
    const bool keep = unsaturated && phase_sat[a] > min_phase_saturation;
    const double d2_phase_sat = a == 0 ? d2_sat : -d2_sat;
    const double r = keep ? d_phase_sat[a] / phase_sat[a] : 0.0;
    const double dr = keep ? (d2_phase_sat * phase_sat[a] - d_phase_sat[a] * d_phase_sat[a]) /
                                 (phase_sat[a] * phase_sat[a])
                           : 0.0;
    const double q = d_rho[a] / rho[a];  // d ln rho / dP_a
    const double dq = (d2_rho[a] * rho[a] - d_rho[a] * d_rho[a]) / (rho[a] * rho[a]);
    // L_ab = r ds/dP_b + delta_ab q
    std::array<double, 2> l{r * ds_dp[0] + (a == 0 ? q : 0.0), r * ds_dp[1] + (a == 1 ? q : 0.0)};
    const Vec<D> h = l[0] * grad[0] + l[1] * grad[1] + grad_ln_n;  // grad ln theta_a
    f.grad_ln_theta[a] = h;
    f.advective[a] = f.flux[a].dot(h);
    for (int b = 0; b < 2; ++b) {
      // dL_ac/dP_b = dr ds/dP_b ds/dP_c + delta_ab delta_ac dq
      Vec<D> dh = Vec<D>::Zero();
      for (int c = 0; c < 2; ++c) {
        const double dl = dr * ds_dp[b] * ds_dp[c] + (a == b && a == c ? dq : 0.0);
        dh += dl * grad[c];
      }
      f.d_advective[a][b] = f.d_flux[a][b].dot(h) + f.flux[a].dot(dh);
      // dT_a/d(grad P_b) = (dJ_a/d grad P_b)^T h + L_ab J_a = -c delta_ab h + L_ab J_a
      f.d_advective_d_grad[a][b] = l[b] * f.flux[a];
      if (a == b) f.d_advective_d_grad[a][b] -= f.conductivity[a] * h;
    }
  }
  return f;
}

}  // namespace unsatmpm::numerics

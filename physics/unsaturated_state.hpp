// Stress variables of unsaturated soil and the storage matrix of the fluid mass balances.
//
// Suction s = max(P_g - P_l, 0) (eq. 5). Net stress, tension positive (eq. 4 with SPEC's sign):
// sigma_bar = sigma + max(P_g, P_l) I; for P_l >= P_g it is Terzaghi's effective stress.
// Storage matrix (SPEC §3, docs/balance_laws.md): with S_l = S(s) and S_g = 1 - S_l,
//   ll = n (rho_l' S_l + rho_l dS_l/dP_l),  lg = n rho_l dS_l/dP_g,
//   gl = -n rho_g dS_l/dP_l,                 gg = n (rho_g' S_g - rho_g dS_l/dP_g),
// where dS_l/dP_l = -S'(s) and dS_l/dP_g = S'(s) (both 0 when saturated).
#pragma once

#include <algorithm>
#include <variant>

#include "physics/fluids.hpp"
#include "physics/retention.hpp"
#include "physics/voigt.hpp"

namespace unsatmpm::physics {

inline double suction(double p_l, double p_g) { return std::max(p_g - p_l, 0.0); }

inline Vec6 net_stress(const Vec6& sigma, double p_l, double p_g) {
  Vec6 s = sigma;
  const double p = std::max(p_l, p_g);
  s[0] += p, s[1] += p, s[2] += p;
  return s;
}

inline Vec6 total_stress(const Vec6& net, double p_l, double p_g) {
  Vec6 s = net;
  const double p = std::max(p_l, p_g);
  s[0] -= p, s[1] -= p, s[2] -= p;
  return s;
}

struct StorageMatrix {
  double ll, lg, gl, gg;
};

inline StorageMatrix storage_matrix(double n, double p_l, double p_g,
                                    const CompressibleFluid& liquid, const GasLaw& gas,
                                    const RetentionCurve& retention) {
  const double s = suction(p_l, p_g);
  const double s_l = std::visit([s](const auto& r) { return r.saturation(s); }, retention);
  const double ds = std::visit([s](const auto& r) { return r.d_saturation(s); }, retention);
  const double dsl_dpl = -ds, dsl_dpg = ds;
  const double rho_l = liquid.density(p_l), rho_g = gas_density(gas, p_g);
  return {n * (liquid.d_density(p_l) * s_l + rho_l * dsl_dpl), n * rho_l * dsl_dpg,
          -n * rho_g * dsl_dpl, n * (gas_d_density(gas, p_g) * (1.0 - s_l) - rho_g * dsl_dpg)};
}

}  // namespace unsatmpm::physics

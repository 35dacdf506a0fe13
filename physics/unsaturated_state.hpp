// Stress variables of an unsaturated soil and the storage matrix of its fluid mass balances
// (Yerro et al. 2015; SPEC §2-§3; docs/balance_laws.md).
//
// Pressures P_l, P_g gauge [Pa], compression positive; stresses [Pa], tension positive.
// Suction (eq. 5): s = max(P_g - P_l, 0) [Pa]; s = 0 is the saturated state (P_l >= P_g).
// Net stress (eq. 4, tension-positive form): sigma_bar = sigma + max(P_g, P_l) I on the normal
//   Voigt components; for P_l >= P_g it is Terzaghi's effective stress sigma + P_l I.
//   total_stress is its exact inverse.
//
// Storage matrix. The liquid mass balance (SPEC §3)
//   n d(rho_l S_l)/dP_l DP_l/Dt + n d(rho_l S_l)/dP_g DP_g/Dt = RHS_l
// and the gas balance (rho_g S_g, S_g = 1 - S_l, in place of rho_l S_l) give, at a point,
//   [ll lg; gl gg] [DP_l/Dt; DP_g/Dt] = [RHS_l; RHS_g]. With S_l = S(s(P_l, P_g)) and the chain
//   rule dS_l/dP_l = -S'(s), dS_l/dP_g = +S'(s) for s > 0, both 0 for s <= 0 (saturated, where
//   the retention law's slope is 0 by definition, see retention.hpp), and rho_l' = d rho_l/dP_l,
//   rho_g' = d rho_g/dP_g:
//     ll = n (rho_l' S_l + rho_l dS_l/dP_l) = n (rho_l' S_l - rho_l S'),
//     lg = n rho_l dS_l/dP_g                = n rho_l S',
//     gl = -n rho_g dS_l/dP_l               = n rho_g S',
//     gg = n (rho_g' S_g - rho_g dS_l/dP_g) = n (rho_g' S_g - rho_g S').
//   Saturated: ll = n rho_l' S_l, lg = gl = 0, gg = n rho_g' S_g (0 when S_l = 1: no gas left).
//   Units: [kg/m^3/Pa]; S' <= 0, so ll, gg >= 0 and lg, gl <= 0.
#pragma once

#include <algorithm>
#include <utility>
#include <variant>

#include "physics/fluids.hpp"
#include "physics/retention.hpp"
#include "physics/voigt.hpp"

namespace unsatmpm::physics {

/// s = max(P_g - P_l, 0) [Pa].
inline double suction(double p_l, double p_g) { return std::max(p_g - p_l, 0.0); }

/// sigma_bar = sigma + max(P_g, P_l) I (tension positive); shear components unchanged.
inline Vec6 net_stress(const Vec6& sigma, double p_l, double p_g) {
  Vec6 s = sigma;
  const double p = std::max(p_l, p_g);
  s[0] += p, s[1] += p, s[2] += p;
  return s;
}

/// sigma = sigma_bar - max(P_g, P_l) I: the inverse of net_stress.
inline Vec6 total_stress(const Vec6& net, double p_l, double p_g) {
  Vec6 s = net;
  const double p = std::max(p_l, p_g);
  s[0] -= p, s[1] -= p, s[2] -= p;
  return s;
}

/// n d(rho_a S_a)/dP_b [kg/m^3/Pa]; first index the balance (l, g), second the pressure.
struct StorageMatrix {
  double ll, lg, gl, gg;
};

/// The storage matrix at a point of porosity n and pressures (P_l, P_g); see the header comment.
inline StorageMatrix storage_matrix(double porosity, double p_l, double p_g,
                                    const CompressibleFluid& liquid, const GasLaw& gas,
                                    const RetentionCurve& retention) {
  const double s = suction(p_l, p_g);
  const auto [s_l, ds] = std::visit(
      [s](const auto& r) {
        return std::pair{r.saturation(s), r.d_saturation(s)};
      },
      retention);
  const double n = porosity;
  const double rho_l = liquid.density(p_l), rho_g = gas_density(gas, p_g);
  return {n * (liquid.d_density(p_l) * s_l - rho_l * ds), n * rho_l * ds, n * rho_g * ds,
          n * (gas_d_density(gas, p_g) * (1.0 - s_l) - rho_g * ds)};
}

}  // namespace unsatmpm::physics

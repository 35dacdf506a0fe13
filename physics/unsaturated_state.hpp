// Stress variables of an unsaturated soil and the storage matrix of its fluid mass balances
// (Yerro et al. 2015; docs/conventions.md, docs/balance_laws.md).
//
// Pressures P_l, P_g gauge [Pa], compression positive; stresses [Pa], tension positive.
// Suction (eq. 5): s = max(P_g - P_l, 0) [Pa]; s = 0 is the saturated state (P_l >= P_g).
// Net stress (eq. 4, tension-positive form): sigma_bar = sigma + max(P_g, P_l) I on the normal
//   Voigt components; for P_l >= P_g it is Terzaghi's effective stress sigma + P_l I.
//   total_stress is its exact inverse.
//
// Storage matrix. The liquid mass balance (docs/balance_laws.md)
//   n d(rho_l S_l)/dP_l DP_l/Dt + n d(rho_l S_l)/dP_g DP_g/Dt = RHS_l
// and the gas balance (rho_g S_g, S_g = 1 - S_l, in place of rho_l S_l) give, at a point,
//   [ll lg; gl gg] [DP_l/Dt; DP_g/Dt] = [RHS_l; RHS_g]. With S_l = S(P_g - P_l) (the signed
//   argument, retention_suction) and the chain rule dS_l/dP_l = -S', dS_l/dP_g = +S' on both
//   sides of 0 (at s <= 0 S' is 0 unless the law lets an occluded gas give way, retention.hpp),
//   and rho_l' = d rho_l/dP_l,
//   rho_g' = d rho_g/dP_g:
//     ll = n (rho_l' S_l + rho_l dS_l/dP_l) = n (rho_l' S_l - rho_l S'),
//     lg = n rho_l dS_l/dP_g                = n rho_l S',
//     gl = -n rho_g dS_l/dP_l               = n rho_g S',
//     gg = n (rho_g' S_g - rho_g dS_l/dP_g) = n (rho_g' S_g - rho_g S').
//   Saturated with S' = 0: ll = n rho_l' S_l, lg = gl = 0, gg = n rho_g' S_g (0 when S_l = 1: no
//   gas left).
//   Units: [kg/m^3/Pa]; S' <= 0, so ll, gg >= 0 and lg, gl <= 0.
//
// Storage derivatives (for the implicit solver's analytic Jacobian): the partial derivatives of
// the four entries with respect to P_l and to P_g at fixed porosity, [kg/m^3/Pa^2]. With
// s = P_g - P_l, ds/dP_l = -1 and ds/dP_g = +1, so dS_l/dP_l = -S', dS'/dP_l = -S'' and dS_l/dP_g =
// S', dS'/dP_g = S''; rho_l depends on P_l only and rho_g on P_g only. Differentiating the entries:
//     d/dP_l: ll = n (rho_l'' S_l - 2 rho_l' S' + rho_l S''),   lg = n (rho_l' S' - rho_l S''),
//             gl = -n rho_g S'',                                 gg = n (rho_g' S' + rho_g S''),
//     d/dP_g: ll = n (rho_l' S' - rho_l S''),                    lg = n rho_l S'',
//             gl = n (rho_g' S' + rho_g S''),
//             gg = n (rho_g'' (1 - S_l) - 2 rho_g' S' - rho_g S'').
//   The mixed partials agree (d ll/dP_g = d lg/dP_l, d gl/dP_g = d gg/dP_l), as they must for
//   derivatives of n rho_l S_l and n rho_g S_g. Saturated (s <= 0) with a flat law: S_l is
//   constant and S' = S'' = 0 (retention.hpp), so the same expressions give the exact derivatives
//   there, d ll/dP_l = n rho_l'' S_l and d gg/dP_g = n rho_g'' (1 - S_l), all others 0. At the
//   kink s = 0 itself they are the saturated side's (one-sided) values.
#pragma once

#include <algorithm>
#include <tuple>
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

/// What the contents and the storage matrix need at pressures (P_l, P_g), each law evaluated
/// once: S_l and S' = dS/ds [1/Pa], rho_l, rho_g [kg/m^3] and their slopes [kg/m^3/Pa], and S_e.
struct LocalFluidState {
  double s_l, ds, rho_l, d_rho_l, rho_g, d_rho_g, se;
};

inline LocalFluidState local_fluid_state(double p_l, double p_g, const CompressibleFluid& liquid,
                                         const GasLaw& gas, const RetentionCurve& retention) {
  const double s = retention_suction(p_l, p_g);
  const auto [s_l, ds, se] =
      std::visit([s](const auto& r) { return r.saturation_and_slope(s); }, retention);
  const auto [rho_l, d_rho_l] = liquid.density_and_slope(p_l);
  const auto [rho_g, d_rho_g] = gas_density_and_slope(gas, p_g);
  return {s_l, ds, rho_l, d_rho_l, rho_g, d_rho_g, se};
}

/// The storage matrix at porosity n and the state f; see the header comment.
inline StorageMatrix storage_matrix(double n, const LocalFluidState& f) {
  return {n * (f.d_rho_l * f.s_l - f.rho_l * f.ds), n * f.rho_l * f.ds, n * f.rho_g * f.ds,
          n * (f.d_rho_g * (1.0 - f.s_l) - f.rho_g * f.ds)};
}

/// The storage matrix at a point of porosity n and pressures (P_l, P_g).
inline StorageMatrix storage_matrix(double porosity, double p_l, double p_g,
                                    const CompressibleFluid& liquid, const GasLaw& gas,
                                    const RetentionCurve& retention) {
  return storage_matrix(porosity, local_fluid_state(p_l, p_g, liquid, gas, retention));
}

/// d(StorageMatrix)/dP_l and d(StorageMatrix)/dP_g at fixed porosity [kg/m^3/Pa^2].
struct StorageDerivatives {
  StorageMatrix d_p_l, d_p_g;
};

/// The partial derivatives of every entry of storage_matrix(porosity, p_l, p_g, ...) with respect
/// to P_l and P_g; see the header comment for the expressions.
inline StorageDerivatives storage_matrix_derivatives(double porosity, double p_l, double p_g,
                                                     const CompressibleFluid& liquid,
                                                     const GasLaw& gas,
                                                     const RetentionCurve& retention) {
  const double s = retention_suction(p_l, p_g);
  const auto [s_l, ds, d2s] = std::visit(
      [s](const auto& r) {
        return std::tuple{r.saturation(s), r.d_saturation(s), r.d2_saturation(s)};
      },
      retention);
  const double n = porosity;
  const double rho_l = liquid.density(p_l), d_rho_l = liquid.d_density(p_l),
               d2_rho_l = liquid.d2_density(p_l);
  const double rho_g = gas_density(gas, p_g), d_rho_g = gas_d_density(gas, p_g),
               d2_rho_g = gas_d2_density(gas, p_g);
  // The two mixed partials, shared by the rows.
  const double liquid_mixed = n * (d_rho_l * ds - rho_l * d2s);
  const double gas_mixed = n * (d_rho_g * ds + rho_g * d2s);
  return {{n * (d2_rho_l * s_l - 2.0 * d_rho_l * ds + rho_l * d2s), liquid_mixed, -n * rho_g * d2s,
           gas_mixed},
          {liquid_mixed, n * rho_l * d2s, gas_mixed,
           n * (d2_rho_g * (1.0 - s_l) - 2.0 * d_rho_g * ds - rho_g * d2s)}};
}

}  // namespace unsatmpm::physics

// The pore pressures of given fluid contents: the inverse of the state's content per unit pore
// volume, c_l = S_l(s) rho_l(P_l) and c_g = (1 - S_l(s)) rho_g(P_g) [kg/m^3], s = max(P_g - P_l,
// 0). The main cycle's mechanics keeps each point's fluid masses and finds its pressures from them
// and its pore volume at every sub-step (cycles/undrained.hpp, docs/balance_laws.md).
//
// Newton's method with the storage matrix at unit porosity as the Jacobian (dc/dP), each step
// cut back until the scaled residual decreases, and cut so that a suction stays positive where
// the law saturates the pores (the retention slope, and with it the gas rows, vanish at s <= 0)
// and an ideal gas's absolute pressure stays positive. Where the point holds no gas phase
// (`gas_held`) only c_l is matched and P_g stays: then c_l(P_l) increases monotonically and a
// bracketing Newton iteration converges from any start. Converged when each residual is below
// `content_tolerance` times its fluid's density (the masses are then kept to that fraction), or,
// with a `pressure_tolerance` [Pa], when the next Newton step would move no pressure by more than
// that: for a caller that keeps the masses itself (cycles/undrained.hpp), where the pressures need
// only be accurate, the start then stands without evaluating the laws again.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "physics/hydraulic_model.hpp"

namespace unsatmpm::physics {

/// Residual convergence of pressures_from_contents, relative to each fluid's density.
inline constexpr double content_tolerance = 1e-13;

/// A pressure tolerance [Pa] for pressures_from_contents at a point of masses (m_l, m_g) [kg],
/// volume [m^3] and storage a: `tolerance`, or less where the storage is so steep that that much
/// would move a fluid's mass by more than 1e-8 of it (an occluded gas giving way over a small
/// scale, OccludedGas: at 100 Pa, 1e-3 Pa is 1e-5 of the gas; verification/occluded_gas).
inline double mass_keeping_tolerance(double tolerance, const StorageMatrix& a, double m_l,
                                     double m_g, double volume) {
  constexpr double mass_fraction = 1e-8;
  const double per_pa_l = volume * (std::abs(a.ll) + std::abs(a.lg));
  const double per_pa_g = volume * (std::abs(a.gl) + std::abs(a.gg));
  if (per_pa_l * tolerance > mass_fraction * m_l) tolerance = mass_fraction * m_l / per_pa_l;
  if (m_g > 0.0 && per_pa_g * tolerance > mass_fraction * m_g)
    tolerance = mass_fraction * m_g / per_pa_g;
  return tolerance;
}

/// The contents (c_l, c_g) [kg/m^3 of pores] at pressures (p_l, p_g) [Pa].
inline std::pair<double, double> fluid_contents(const HydraulicModel& hm, double p_l, double p_g) {
  const double s_l = hm.saturation(retention_suction(p_l, p_g));
  return {s_l * hm.liquid_density(p_l), (1.0 - s_l) * hm.gas_density(p_g)};
}

/// Sets (p_l, p_g) [Pa] (the start on entry) to the pressures whose contents are c_l, c_g [kg/m^3];
/// with `gas_held`, p_g stays and c_g is not matched. Returns the Newton iterations taken, or -1
/// if 100 did not converge (the pressures are then the last iterate). `state`, if given, receives
/// the fluid state at the pressures returned (HydraulicModel::state). Each iterate's state is
/// evaluated once, for its contents, its scale and its Jacobian. `pressure_tolerance` [Pa]: also
/// converged where the Newton step is no larger (0: the contents' test alone).
inline int pressures_from_contents(const HydraulicModel& hm, double c_l, double c_g, bool gas_held,
                                   double& p_l, double& p_g, LocalFluidState* state = nullptr,
                                   double pressure_tolerance = 0.0) {
  constexpr int max_iterations = 100;
  LocalFluidState f = hm.state(p_l, p_g);
  const auto done = [&](int it) {
    if (state) *state = f;
    return it;
  };
  if (gas_held) {
    // Monotone scalar equation r(P_l) = S rho_l - c_l: Newton inside a bracket, bisection when a
    // step leaves it.
    double lo = -std::numeric_limits<double>::infinity(), hi = -lo;
    for (int it = 0; it < max_iterations; ++it) {
      const double r = f.s_l * f.rho_l - c_l;
      if (std::abs(r) <= content_tolerance * f.rho_l) return done(it);
      (r > 0.0 ? hi : lo) = p_l;
      const double dr = storage_matrix(1.0, f).ll;
      if (dr > 0.0 && std::abs(r) <= pressure_tolerance * dr) return done(it);
      double next = dr > 0.0 ? p_l - r / dr : std::numeric_limits<double>::quiet_NaN();
      if (!(next > lo && next < hi)) {
        if (std::isfinite(lo) && std::isfinite(hi)) {
          next = 0.5 * (lo + hi);
        } else {  // no bracket yet: step outward by a growing amount
          const double reach = std::max(1.0, std::abs(p_l)) * 2.0;
          next = r > 0.0 ? p_l - reach : p_l + reach;
        }
      }
      if (next == p_l) return done(it);  // the bracket has shrunk to round-off
      p_l = next;
      f = hm.state(p_l, p_g);
    }
    return -1;
  }
  // Where the law saturates the pores (S(0) within gas_free_saturation of 1) the gas rows vanish
  // at s <= 0, so with both fluids present the suction is positive: a start at s <= 0 moves to 1
  // Pa of suction, and no step crosses to s <= 0. Where it leaves an occluded gas (S(0) = s_max <
  // 1) the gas rows keep the gas's own compressibility there, and the two fluids decouple (S =
  // S(0), dS/ds = 0) unless the gas gives way (retention.hpp, OccludedGas): both sides of s = 0
  // are open to the iteration. (Kept positive, contents whose liquid is compressed past S(0)
  // rho_l(P_g) could not be reached: the iteration crept to s = 0+ and gave up, and the point lost
  // its gas balance to the gas-free fallback.)
  const bool gas_vanishes = 1.0 - hm.saturation(0.0) <= gas_free_saturation;
  const bool gives_way = hm.d_saturation(0.0) != 0.0;  // an occluded gas's branch at s <= 0
  if (gas_vanishes && !(p_g - p_l > 0.0)) {
    p_l = p_g - 1.0;
    f = hm.state(p_l, p_g);
  }
  // The residuals at state g, and their norm scaled by each fluid's density.
  const auto residual = [&](const LocalFluidState& g, double& rl, double& rg) {
    rl = g.s_l * g.rho_l - c_l, rg = (1.0 - g.s_l) * g.rho_g - c_g;
    const double a = rl / g.rho_l, b = rg / g.rho_g;
    return std::sqrt(a * a + b * b);
  };
  double rl = 0.0, rg = 0.0;
  double norm = residual(f, rl, rg);
  for (int it = 0; it < max_iterations; ++it) {
    if (std::abs(rl) <= content_tolerance * f.rho_l && std::abs(rg) <= content_tolerance * f.rho_g)
      return done(it);
    const StorageMatrix j = storage_matrix(1.0, f);
    const double det = j.ll * j.gg - j.lg * j.gl;
    if (!(std::abs(det) > 0.0) || !std::isfinite(det)) return -1;
    double dl = -(j.gg * rl - j.lg * rg) / det;
    double dg = -(j.ll * rg - j.gl * rl) / det;
    if (std::max(std::abs(dl), std::abs(dg)) <= pressure_tolerance) return done(it);
    // Keep a positive suction positive where the gas rows vanish at s <= 0. Where an occluded
    // gas gives way, a step from s > 0 (the curve flat near 0, so the step is the water's
    // stiffness's and far too long) stops at s = 0, where the next takes the branch's slope.
    const double s = p_g - p_l, ds = dg - dl;
    double lambda = 1.0;
    if (gas_vanishes && s > 0.0 && s + ds <= 0.0) lambda = 0.5 * s / -ds;
    const bool to_zero = gives_way && s > 0.0 && s + ds < 0.0;
    if (to_zero) lambda = s / -ds;
    double next_rl = 0.0, next_rg = 0.0, next = std::numeric_limits<double>::infinity();
    for (int cut = 0; cut < 60; ++cut, lambda *= 0.5) {
      const double pg = p_g + lambda * dg;
      const double pl = to_zero && cut == 0 ? pg : p_l + lambda * dl;  // s = 0 exactly
      const LocalFluidState trial = hm.state(pl, pg);
      if (!(trial.rho_g > 0.0)) continue;  // an ideal gas's absolute pressure stays positive
      next = residual(trial, next_rl, next_rg);
      if (next < norm) {
        p_l = pl, p_g = pg, f = trial;
        break;
      }
    }
    if (!(next < norm)) return -1;  // no decrease along the Newton direction
    norm = next, rl = next_rl, rg = next_rg;
  }
  return -1;
}

}  // namespace unsatmpm::physics

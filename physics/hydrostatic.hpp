// Pore fluids at rest under gravity: the initial pressures of a water table (docs/input.md,
// "three-phase bodies").
//
// Elevation z [m] is measured against gravity: z = -g.x / |g|. A fluid at rest has
// dP/dz = -rho(P) |g|, integrated exactly for each density law (fluids.hpp):
//   CompressibleFluid, rho = rho0 exp((P - P0)/K): u = exp(-(P - P0)/K) is linear in z,
//     u(z) = u(z_ref) + rho0 |g| (z - z_ref) / K, so P(z) = P0 - K ln u(z)
//     = P(z_ref) - K ln(1 + rho(P(z_ref)) |g| (z - z_ref) / K). Defined down to
//     K / (rho(P(z_ref)) |g|) below z_ref (about 200 km for water): deeper, NaN.
//   IdealGas, rho = rho0 (P + P_atm)/P_atm: P(z) + P_atm = (P(z_ref) + P_atm)
//     exp(-rho0 |g| (z - z_ref) / P_atm).
// The water table at z_w: the gas is at rest with P_g(z_w) given; the liquid is at rest with
// P_l(z_w) = P_g(z_w) (zero suction at the table), saturated below and under suction above,
// the suction s = P_g - P_l capped at a stated maximum s_max (above the capped height the liquid
// is not at rest: field practice for the suction of a slope's crust).
// Units: pressures gauge [Pa], elevations [m], |g| [m/s^2].
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <variant>

#include "physics/fluids.hpp"

namespace unsatmpm::physics {

/// P(z) of a compressible fluid at rest, from P(z_ref) = p_ref.
inline double hydrostatic_pressure(const CompressibleFluid& f, double p_ref, double z_ref, double z,
                                   double g) {
  // P = p_ref - K ln(u / u_ref) with u / u_ref = 1 + x: log1p keeps P exact near z_ref.
  const double x = f.density(p_ref) * g * (z - z_ref) / f.bulk_modulus;
  return x > -1.0 ? p_ref - f.bulk_modulus * std::log1p(x)
                  : std::numeric_limits<double>::quiet_NaN();
}

/// P(z) of an isothermal ideal gas at rest, from P(z_ref) = p_ref (> -P_atm).
inline double hydrostatic_pressure(const IdealGas& f, double p_ref, double z_ref, double z,
                                   double g) {
  const double atm = IdealGas::atmospheric_pressure;
  return (p_ref + atm) * std::exp(-f.reference_density * g * (z - z_ref) / atm) - atm;
}

struct WaterTable {
  double elevation;     // z_w [m]
  double gas_pressure;  // P_g at z_w [Pa]
  double max_suction;   // s_max [Pa], >= 0
};

struct PorePressures {
  double liquid, gas;  // [Pa]
};

/// The pressures at elevation z [m] of fluids at rest about the water table `w`, gravity |g|.
inline PorePressures water_table_pressures(const CompressibleFluid& liquid, const GasLaw& gas,
                                           const WaterTable& w, double g, double z) {
  const double p_g = std::visit(
      [&](const auto& law) { return hydrostatic_pressure(law, w.gas_pressure, w.elevation, z, g); },
      gas);
  const double p_l = hydrostatic_pressure(liquid, w.gas_pressure, w.elevation, z, g);
  return {std::max(p_l, p_g - w.max_suction), p_g};
}

}  // namespace unsatmpm::physics

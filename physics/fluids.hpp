// Pore fluids: density as a function of gauge pressure (Yerro et al. 2015; docs/models.md).
//
// CompressibleFluid: rho = rho0 exp((p - p0) / K), the liquid, and a gas given a bulk modulus
//   (the paper's Table 2 gas, K_g = 10 kPa). Valid for any finite p; rho > 0 everywhere.
// IdealGas: isothermal, rho = rho0 (p + P_atm) / P_atm, with rho0 the density at gauge 0
//   (atmospheric) and P_atm = 101325 Pa. Valid for p > -P_atm (absolute pressure positive); the
//   law is not checked on the hot path, the input layer bounds the pressures.
// Units: pressures gauge [Pa] (compression positive), densities [kg/m^3], bulk moduli [Pa],
// d_density = d rho / d p [kg/m^3/Pa], d2_density = d^2 rho / d p^2 [kg/m^3/Pa^2] (for the
// implicit solver's Jacobian): rho / K^2 > 0 for CompressibleFluid, 0 for IdealGas (linear in p).
// Both densities increase strictly with p.
#pragma once

#include <cmath>
#include <utility>
#include <variant>

namespace unsatmpm::physics {

struct CompressibleFluid {
  double reference_density;   // rho0 [kg/m^3] at the reference pressure
  double reference_pressure;  // p0 [Pa], gauge
  double bulk_modulus;        // K [Pa]

  /// Validated construction; throws ParameterError naming the parameter ("density",
  /// "reference_pressure", "bulk_modulus") and its valid range.
  static CompressibleFluid create(double reference_density, double reference_pressure,
                                  double bulk_modulus);

  double density(double p) const {
    return reference_density * std::exp((p - reference_pressure) / bulk_modulus);
  }
  double d_density(double p) const { return density(p) / bulk_modulus; }
  double d2_density(double p) const { return density(p) / (bulk_modulus * bulk_modulus); }
  /// {density(p), d_density(p)} with one exponential.
  std::pair<double, double> density_and_slope(double p) const {
    const double rho = density(p);
    return {rho, rho / bulk_modulus};
  }
};

struct IdealGas {
  static constexpr double atmospheric_pressure = 101325.0;  // P_atm [Pa]
  double reference_density;                                 // rho0 [kg/m^3] at gauge 0

  /// Validated construction; throws ParameterError naming "density" and its valid range.
  static IdealGas create(double reference_density);

  /// Valid for p > -P_atm.
  double density(double p) const {
    return reference_density * (p + atmospheric_pressure) / atmospheric_pressure;
  }
  double d_density(double /*p*/) const { return reference_density / atmospheric_pressure; }
  double d2_density(double /*p*/) const { return 0.0; }
  std::pair<double, double> density_and_slope(double p) const { return {density(p), d_density(p)}; }
};

/// The gas phase: a bulk-modulus law or the isothermal ideal gas.
using GasLaw = std::variant<CompressibleFluid, IdealGas>;

/// rho_g(p) [kg/m^3]; one indexed jump (hoist the choice out of hot loops where it matters).
inline double gas_density(const GasLaw& gas, double p) {
  return std::visit([p](const auto& law) { return law.density(p); }, gas);
}
/// d rho_g / d p [kg/m^3/Pa].
inline double gas_d_density(const GasLaw& gas, double p) {
  return std::visit([p](const auto& law) { return law.d_density(p); }, gas);
}
/// {rho_g(p), d rho_g / d p}.
inline std::pair<double, double> gas_density_and_slope(const GasLaw& gas, double p) {
  return std::visit([p](const auto& law) { return law.density_and_slope(p); }, gas);
}
/// d^2 rho_g / d p^2 [kg/m^3/Pa^2].
inline double gas_d2_density(const GasLaw& gas, double p) {
  return std::visit([p](const auto& law) { return law.d2_density(p); }, gas);
}

}  // namespace unsatmpm::physics

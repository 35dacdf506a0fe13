// Pore fluids: density as a function of gauge pressure (SPEC §4).
//
// CompressibleFluid: rho = rho0 exp((p - p0) / K), for the liquid and for a gas given a bulk
//   modulus. IdealGas: isothermal, rho = rho0 (p + P_atm) / P_atm with rho0 the density at
//   atmospheric pressure (gauge 0); valid for p > -P_atm (absolute pressure positive).
// Pressures gauge [Pa] (compression positive), densities [kg/m^3], moduli [Pa].
#pragma once

#include <cmath>
#include <variant>

namespace unsatmpm::physics {

struct CompressibleFluid {
  double reference_density;   // rho0 [kg/m^3] at the reference pressure
  double reference_pressure;  // p0 [Pa]
  double bulk_modulus;        // K [Pa]

  /// Validated construction; throws ParameterError naming the parameter and its range.
  static CompressibleFluid create(double reference_density, double reference_pressure,
                                  double bulk_modulus);
  double density(double p) const {
    return reference_density * std::exp((p - reference_pressure) / bulk_modulus);
  }
  double d_density(double p) const { return density(p) / bulk_modulus; }
};

struct IdealGas {
  static constexpr double atmospheric_pressure = 101325.0;  // P_atm [Pa]
  double reference_density;                                 // rho0 [kg/m^3] at gauge 0

  static IdealGas create(double reference_density);
  double density(double p) const {
    return reference_density * (p + atmospheric_pressure) / atmospheric_pressure;
  }
  double d_density(double /*p*/) const { return reference_density / atmospheric_pressure; }
};

using GasLaw = std::variant<CompressibleFluid, IdealGas>;

inline double gas_density(const GasLaw& g, double p) {
  return std::visit([p](const auto& law) { return law.density(p); }, g);
}
inline double gas_d_density(const GasLaw& g, double p) {
  return std::visit([p](const auto& law) { return law.d_density(p); }, g);
}

}  // namespace unsatmpm::physics

// The rigid van Genuchten soil of the 1D column tests (test_explicit_rain.cpp,
// test_free_surface_nodes.cpp, test_three_phase_surface.cpp): the case's phases, fluids,
// mass-balance form, skeleton and one material `soil`, as YAML lines to place in a case text.
#pragma once

#include <string>

namespace unsatmpm::test_soils {

/// n = 0.4, kappa = 1e-11 m^2, van Genuchten P0 = 20 kPa, lambda = 0.4, Mualem's k_rl, k_rg = 1;
/// water (K_l = 200 MPa) and an ideal gas.
inline std::string rigid_soil_yaml() {
  return R"(phases: solid_liquid_gas
fluids:
  liquid: {density: 1000, bulk_modulus: 2.0e+8, viscosity: 1.0e-3}
  gas: {model: ideal, density: 1.2, viscosity: 1.8e-5}
mass_balance: full
skeleton: rigid
materials:
  - {name: soil, model: linear_elastic, young_modulus: 5.0e+6, poisson_ratio: 0.3,
     solid_density: 2700, porosity: 0.4, intrinsic_permeability: 1.0e-11,
     retention: {model: van_genuchten, p0: 2.0e+4, lambda: 0.4, residual_saturation: 0},
     liquid_relative_permeability: {model: mualem_van_genuchten, lambda: 0.4},
     gas_relative_permeability: {model: constant}}
)";
}

}  // namespace unsatmpm::test_soils

// A hydraulic model of the explicit step's tests (test_step_speed.cpp,
// test_three_phase_pressures.cpp): water of 200 MPa, ideal gas with k_rg = 1, van Genuchten
// retention (P0 = 20 kPa, lambda = 0.4) with the residual saturation given, kappa = 1e-11 m^2.
#pragma once

#include "physics/hydraulic_model.hpp"

namespace unsatmpm::numerics {

inline physics::HydraulicModel mobile_gas_soil(double residual_saturation = 0.0) {
  physics::HydraulicModel hm{};
  hm.liquid = physics::CompressibleFluid::create(1000.0, 0.0, 2e8);
  hm.gas = physics::IdealGas::create(1.2);
  hm.retention = physics::VanGenuchten::create(2e4, 0.4, residual_saturation, 1.0);
  hm.liquid_relative_permeability = physics::MualemVanGenuchten::create(0.4);
  hm.gas_relative_permeability = physics::ConstantRelPerm{};
  hm.solid_density = 2700.0;
  hm.intrinsic_permeability = 1e-11;
  hm.liquid_viscosity = 1e-3;
  hm.gas_viscosity = 1.8e-5;
  return hm;
}

}  // namespace unsatmpm::numerics

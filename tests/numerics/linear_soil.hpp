// A hydraulic model of the pressure-system tests: water of 80 MPa, ideal gas, linear retention
// (S_l = 1 - 1e-6 s), constant relative permeabilities, kappa = 5e-11 m^2.
#pragma once

#include "physics/hydraulic_model.hpp"

namespace unsatmpm::numerics {

inline physics::HydraulicModel linear_soil() {
  return {physics::CompressibleFluid::create(1000.0, 0.0, 8e7),
          physics::IdealGas::create(1.2),
          physics::LinearRetention::create(1e-6, 0.0),
          physics::ConstantRelPerm{},
          physics::ConstantRelPerm{},
          2700.0,
          5e-11,
          1e-3,
          1.8e-5};
}

}  // namespace unsatmpm::numerics

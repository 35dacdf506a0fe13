// The pore-fluid columns of three-phase material points, indexed like MaterialPoints.
//
// In a three-phase case MaterialPoints::mass is the solid mass (1 - n) rho_s V and
// MaterialPoints::stress is the net stress sigma_bar = sigma + max(P_g, P_l) I (SPEC §2, eq. 4);
// the total stress is derived where needed. Pressures are gauge [Pa], positive in compression.
#pragma once

#include <vector>

#include "numerics/grid.hpp"

namespace unsatmpm::numerics {

template <int D>
struct FluidPoints {
  std::vector<double> porosity;         // n [-]
  std::vector<double> liquid_pressure;  // P_l [Pa]
  std::vector<double> gas_pressure;     // P_g [Pa]
  std::vector<double> saturation;       // S_l [-], from the retention curve at the suction
  std::vector<double> liquid_density;   // rho_l [kg/m^3]
  std::vector<double> gas_density;      // rho_g [kg/m^3]
  std::vector<Vec<D>> liquid_velocity;  // v_l [m/s]
  std::vector<Vec<D>> gas_velocity;     // v_g [m/s]

  std::size_t size() const { return porosity.size(); }
  void resize(std::size_t n) {
    porosity.resize(n), liquid_pressure.resize(n), gas_pressure.resize(n), saturation.resize(n);
    liquid_density.resize(n), gas_density.resize(n);
    liquid_velocity.assign(n, Vec<D>::Zero()), gas_velocity.assign(n, Vec<D>::Zero());
  }
};

}  // namespace unsatmpm::numerics

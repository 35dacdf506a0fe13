// The pore-fluid columns of three-phase material points, indexed like MaterialPoints.
//
// In a three-phase case MaterialPoints::mass is the solid mass (1 - n) rho_s V and
// MaterialPoints::stress is the net stress sigma_bar = sigma + max(P_g, P_l) I
// (docs/conventions.md; the paper's eq. 4); the total stress is derived where needed. Pressures are
// gauge [Pa], positive in compression.
#pragma once

#include <vector>

#include "numerics/grid.hpp"
#include "physics/scheme.hpp"
#include "physics/unsaturated_state.hpp"

namespace unsatmpm::numerics {

using physics::Fluid;  // the index of a pore fluid in per-fluid arrays
using physics::gas_phase;
using physics::liquid_phase;

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
  // Scratch of one step, between the mass balances and the pressure update: the right-hand
  // sides r_l, r_g of the mass balances (mass rates per unit volume [kg/m^3/s]), the storage
  // matrix A at the start of the step, the increments dP_l, dP_g [Pa] and div v_s dt. Once the
  // increments are solved, the rates' columns are the offsets' relaxation's scratch
  // (numerics/pressure_offsets.hpp).
  std::vector<double> liquid_rate, gas_rate, liquid_increment, gas_increment;
  std::vector<physics::StorageMatrix> storage;
  std::vector<double> volumetric_strain_increment;
  // The explicit cycle's laws at the current state, evaluated once per step
  // (numerics::refresh_point_laws): S_e [-] and each fluid's drag coefficient
  // n S_a mu_a / (kappa k_ra) [Pa s/m^2]; with them `storage` holds A at the current state.
  std::vector<double> effective_saturation, liquid_drag, gas_drag;
  // The largest conductivity rho_a kappa k_ra / mu_a [s] of the nodes the point's last step took
  // its fluxes from (numerics/three_phase_g2p.hpp): the stable step takes the point's storage
  // against it where it exceeds the point's own.
  std::vector<double> liquid_reach, gas_reach;
  // The explicit cycle's shortfall, per fluid [kg]: between steps, what the point's state holds
  // short of the mass the step's balance assigned it, m + V (A dP + S_a rho_a div v_s dt) (the
  // pressures that hold that mass are found to a tolerance); the next step's balance adds it
  // back, so that the masses telescope (docs/balance_laws.md, "The pressures that hold the
  // masses"). Within a step, from g2p_three_phase to apply_pressure_increments, the fluid's mass
  // at the step's start.
  std::vector<double> liquid_shortfall, gas_shortfall;

  std::size_t size() const { return porosity.size(); }
  void resize(std::size_t n) {
    porosity.resize(n), liquid_pressure.resize(n), gas_pressure.resize(n), saturation.resize(n);
    liquid_density.resize(n), gas_density.resize(n);
    liquid_rate.assign(n, 0.0), gas_rate.assign(n, 0.0);
    liquid_increment.assign(n, 0.0), gas_increment.assign(n, 0.0);
    storage.assign(n, physics::StorageMatrix{0.0, 0.0, 0.0, 0.0});
    volumetric_strain_increment.assign(n, 0.0);
    effective_saturation.assign(n, 0.0), liquid_drag.assign(n, 0.0), gas_drag.assign(n, 0.0);
    liquid_reach.assign(n, 0.0), gas_reach.assign(n, 0.0);
    liquid_shortfall.assign(n, 0.0), gas_shortfall.assign(n, 0.0);
    liquid_velocity.assign(n, Vec<D>::Zero()), gas_velocity.assign(n, Vec<D>::Zero());
  }
};

/// Fluid masses in the domain and what has flowed in through the boundary [kg per out-of-plane
/// measure]: the conservation report compares their changes.
struct FluidBalance {
  double liquid_mass, gas_mass, liquid_inflow, gas_inflow;  // [kg]
  // Each fluid's capacity: its mass if it filled all the pores, sum n V rho_a [kg]; the scale of
  // the mismatch of a fluid absent at the start (writers/run_output.cpp).
  double liquid_capacity = 0.0, gas_capacity = 0.0;
};

}  // namespace unsatmpm::numerics

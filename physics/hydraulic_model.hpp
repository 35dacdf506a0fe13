// Everything a three-phase material point needs from its material's hydraulics, in one value
// type: fluids, retention, relative permeabilities, intrinsic permeability and viscosities.
// The laws are std::variants; each call below is one indexed jump (no virtual call, no heap).
#pragma once

#include <algorithm>
#include <limits>
#include <variant>

#include "physics/fluids.hpp"
#include "physics/permeability.hpp"
#include "physics/retention.hpp"
#include "physics/unsaturated_state.hpp"

namespace unsatmpm::physics {

struct HydraulicModel {
  physics::CompressibleFluid liquid;
  physics::GasLaw gas;
  physics::RetentionCurve retention;
  physics::LiquidRelPerm liquid_relative_permeability;
  physics::GasRelPerm gas_relative_permeability;
  double solid_density;           // rho_s [kg/m^3]
  double intrinsic_permeability;  // kappa [m^2]
  double liquid_viscosity;        // mu_l [Pa s]
  double gas_viscosity;           // mu_g [Pa s]
  // n_max [-]: a point's volume is held at V_s / (1 - n_max) when the solid skeleton would
  // loosen beyond it (see max_volume); 1 = no bound.
  double max_porosity = 1.0;

  /// The largest volume [m^3] of a point of solid mass m [kg]: V_s / (1 - n_max), infinite
  /// without a bound. Beyond it the soil has separated: the opening is air outside the soil, not
  /// pore space, and keeping it in the point's volume would make a point of ever lower density
  /// whose wave speed collapses the explicit step.
  double max_volume(double solid_mass) const {
    return max_porosity < 1.0 ? solid_mass / (solid_density * (1.0 - max_porosity))
                              : std::numeric_limits<double>::infinity();
  }

  double saturation(double s) const {
    return std::visit([s](const auto& r) { return r.saturation(s); }, retention);
  }
  /// Whether some state leaves the pores free of gas (S_g at most gas_free_saturation): a law that
  /// saturates them at s <= 0, or whose occluded gas gives way (retention.hpp, OccludedGas); not
  /// one that keeps S_max < 1 - gas_free_saturation.
  bool can_be_free_of_gas() const {
    return 1.0 - saturation(-std::numeric_limits<double>::max()) <= gas_free_saturation;
  }
  double effective_saturation(double s) const {
    return std::visit([s](const auto& r) { return r.effective_saturation(s); }, retention);
  }
  double d_saturation(double s) const {
    return std::visit([s](const auto& r) { return r.d_saturation(s); }, retention);
  }
  double d2_saturation(double s) const {
    return std::visit([s](const auto& r) { return r.d2_saturation(s); }, retention);
  }
  double d_effective_saturation(double s) const {
    return std::visit([s](const auto& r) { return r.d_effective_saturation(s); }, retention);
  }
  double liquid_density(double p) const { return liquid.density(p); }
  double liquid_d_density(double p) const { return liquid.d_density(p); }
  double liquid_d2_density(double p) const { return liquid.d2_density(p); }
  double gas_density(double p) const { return physics::gas_density(gas, p); }
  double gas_d_density(double p) const { return physics::gas_d_density(gas, p); }
  double gas_d2_density(double p) const { return physics::gas_d2_density(gas, p); }
  /// k_r and dk_r/dS_e of each fluid at effective saturation se.
  double liquid_relative_permeability_value(double se) const {
    return std::visit([se](const auto& m) { return m.value(se); }, liquid_relative_permeability);
  }
  double liquid_relative_permeability_derivative(double se) const {
    return std::visit([se](const auto& m) { return m.d_value(se); }, liquid_relative_permeability);
  }
  double gas_relative_permeability_value(double se) const {
    return std::visit([se](const auto& m) { return m.value(se); }, gas_relative_permeability);
  }
  double gas_relative_permeability_derivative(double se) const {
    return std::visit([se](const auto& m) { return m.d_value(se); }, gas_relative_permeability);
  }

  /// Drag coefficients per unit volume of mixture of the per-fluid-volume momentum balances,
  /// n S_a mu_a / (kappa k_ra) [Pa s / m^2]. A vanishing k_r is floored at 1e-12 so the
  /// coefficient stays finite: the implicit drag then simply locks the phase to the solid.
  double liquid_drag(double n, double s_l, double se) const {
    const double k =
        std::visit([se](const auto& m) { return m.value(se); }, liquid_relative_permeability);
    return n * s_l * liquid_viscosity / (intrinsic_permeability * std::max(k, 1e-12));
  }
  double gas_drag(double n, double s_l, double se) const {
    const double k =
        std::visit([se](const auto& m) { return m.value(se); }, gas_relative_permeability);
    return n * (1.0 - s_l) * gas_viscosity / (intrinsic_permeability * std::max(k, 1e-12));
  }
  physics::StorageMatrix storage(double n, double p_l, double p_g) const {
    return physics::storage_matrix(n, p_l, p_g, liquid, gas, retention);
  }
  /// S_l, the densities and their slopes at (P_l, P_g), each law evaluated once.
  physics::LocalFluidState state(double p_l, double p_g) const {
    return physics::local_fluid_state(p_l, p_g, liquid, gas, retention);
  }
  physics::StorageDerivatives storage_derivatives(double n, double p_l, double p_g) const {
    return physics::storage_matrix_derivatives(n, p_l, p_g, liquid, gas, retention);
  }
};

}  // namespace unsatmpm::physics

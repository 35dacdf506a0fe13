// The flow half of the main cycle's coupling (docs/balance_laws.md, "Two-way coupling"): the
// storage the flow gains from the skeleton, S_a rho_a / K_dr dp*/dP_b per point, with p* =
// max(P_l, P_g) the pore pressure of the net stress and K_dr the skeleton's drained bulk modulus;
// and the points' fluid state after a pressure update.
#pragma once

#include <cmath>
#include <cstdint>
#include <variant>
#include <vector>

#include "cycles/explicit_solver.hpp"
#include "cycles/setup.hpp"
#include "numerics/fluid_points.hpp"
#include "numerics/point_models.hpp"
#include "physics/hydraulic_model.hpp"
#include "physics/unsaturated_state.hpp"

namespace unsatmpm {

/// Each point's added storage [kg/(m^3 Pa)]: S_l rho_l / K and S_g rho_g / K in the column of
/// the fluid whose pressure is p* (the liquid where P_l >= P_g, else the gas); none at a point
/// whose volume is at its bound (HydraulicModel::max_volume): it cannot swell, so the flow must
/// not give it water for a swelling its mechanics will refuse (seen on the embankment near 10 s,
/// with the flow's share given to every point directly: such points reached 10-50 MPa).
template <int D>
std::vector<physics::StorageMatrix> fixed_stress_storage(
    const std::vector<SolidModel>& models, const std::vector<physics::HydraulicModel>& hydraulics,
    const PointSet<D>& points, const numerics::FluidPoints<D>& fluids) {
  // K_dr is the elastic drained modulus everywhere, at a yielding point too. A thousandth of it
  // once stood in for the zero drained tangent at Mohr-Coulomb apex points (against a crest
  // failure of the embankment whose cause was later found in the start values' fit,
  // verification/embankment/README.md). With the undrained coupling it gave the collapsing
  // block's free-surface points (verification/collapse, at the apex) a thousand times the
  // elastic swelling storage: a gas value switched on at the surface drove their liquid by up to
  // 26 times the gas change, and they dried to 9-17 times the initial suction where the explicit
  // cycle kept them within 20 %; with the elastic modulus the two cycles' suctions agree within
  // RMS 0.8 % of it.
  std::vector<physics::StorageMatrix> extra(fluids.size());
  for (std::size_t m = 0; m < models.size(); ++m)
    std::visit(
        [&](const auto& model) {  // one dispatch per material, a plain loop over its points
          const double bound = 1.0 - 1e-9;
          for (auto p = points.ranges[m]; p < points.ranges[m + 1]; ++p) {
            if (points.points.volume[p] >= bound * hydraulics[m].max_volume(points.points.mass[p]))
              continue;  // extra[p] stays zero
            const double sl = fluids.saturation[p];
            const double k = numerics::drained_bulk_modulus<D>(model);
            const double cl = sl * fluids.liquid_density[p] / k;
            const double cg = (1.0 - sl) * fluids.gas_density[p] / k;
            // dp*/dP_l = 1 where the liquid pressure is the larger, else dp*/dP_g = 1.
            if (fluids.liquid_pressure[p] >= fluids.gas_pressure[p])
              extra[p] = {cl, 0.0, cg, 0.0};
            else
              extra[p] = {0.0, cl, 0.0, cg};
          }
        },
        models[m]);
  return extra;
}

/// Saturation and densities of every point from its pressures; returns the first point whose
/// pressures are not finite, or -1.
template <int D>
std::int64_t update_fluid_state(const std::vector<physics::HydraulicModel>& hydraulics,
                                const std::vector<std::int64_t>& ranges,
                                numerics::FluidPoints<D>& fp) {
  for (std::size_t m = 0; m + 1 < ranges.size(); ++m) {
    const auto& hm = hydraulics[m];
    for (auto p = ranges[m]; p < ranges[m + 1]; ++p) {
      const double pl = fp.liquid_pressure[p], pg = fp.gas_pressure[p];
      fp.saturation[p] = hm.saturation(physics::retention_suction(pl, pg));
      fp.liquid_density[p] = hm.liquid_density(pl);
      fp.gas_density[p] = hm.gas_density(pg);
      if (!std::isfinite(pl + pg)) return p;
    }
  }
  return -1;
}

}  // namespace unsatmpm

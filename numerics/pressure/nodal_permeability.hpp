// A point's relative permeabilities taken from its stencil nodes' pressures, the flow's option
// solver.implicit.relative_permeability: nodes (docs/balance_laws.md, "The relative permeability
// at the points or from the nodes"): k_ra = sum_i N_i k_ra(S_e(P_i)) instead of k_ra(S_e(P_p))
// at the point's interpolated pressures. Across a wetting front narrower than a cell the laws at
// a dry point give it the dry soil's permeability, 1e-5 of the wet one's, although its support
// reaches the wet node; the weights over the nodes' laws let the front's water into it as the
// wet node's conductance allows.
#pragma once

#include <array>
#include <vector>

#include "numerics/shape_functions.hpp"
#include "physics/hydraulic_model.hpp"

namespace unsatmpm::numerics {

/// Per stencil node of a point, per fluid a and pressure b: dk_ra/dP_b,i of the point's relative
/// permeability from the nodes, N_i k_ra'(S_e) dS_e/ds ds/dP_b at node i's pressures.
template <int D, class K>
using NodalPermeabilityDerivatives =
    std::array<std::array<std::array<double, 2>, 2>, PointStencil<D, K>::n>;

/// A point's relative permeabilities {k_rl, k_rg} from its stencil `st`: its weights over the laws
/// of `hm` at the nodes' pressures `pressure` (per fluid, per node); with `dk`, their derivatives
/// by node.
template <int D, class K>
std::array<double, 2> nodal_permeability(const physics::HydraulicModel& hm,
                                         const PointStencil<D, K>& st,
                                         const std::array<std::vector<double>, 2>& pressure,
                                         NodalPermeabilityDerivatives<D, K>* dk = nullptr) {
  std::array<double, 2> k{0.0, 0.0};
  for (int a = 0; a < st.n; ++a) {
    const auto i = st.node[a];
    const double s = physics::retention_suction(pressure[0][i], pressure[1][i]);
    const double se = hm.effective_saturation(s);
    k[0] += st.w[a] * hm.liquid_relative_permeability_value(se);
    k[1] += st.w[a] * hm.gas_relative_permeability_value(se);
    if (!dk) continue;
    // As at a point (numerics/pressure/pressure_point.hpp): S depends on the pressures where
    // unsaturated or where an occluded gas gives way, with ds/dP_l = -1 and ds/dP_g = +1.
    const bool unsaturated = s > 0.0 || hm.d_saturation(s) != 0.0;
    const double d_se = unsaturated ? hm.d_effective_saturation(s) : 0.0;
    const std::array<double, 2> d_k{hm.liquid_relative_permeability_derivative(se),
                                    hm.gas_relative_permeability_derivative(se)};
    for (int f = 0; f < 2; ++f) {
      const double g = st.w[a] * d_k[f] * d_se;
      (*dk)[a][f] = {-g, g};
    }
  }
  return k;
}

}  // namespace unsatmpm::numerics

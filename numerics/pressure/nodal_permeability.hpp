// A point's relative permeabilities taken from its stencil nodes' pressures, the flow's option
// solver.implicit.relative_permeability: nodes (docs/balance_laws.md, "The relative permeability
// at the points or from the nodes"): k_ra = sum_i N_i k_ra(S_e(P_i)) instead of k_ra(S_e(P_p))
// at the point's interpolated pressures. Across a wetting front narrower than a cell the laws at
// a dry point give it the dry soil's permeability, 1e-5 of the wet one's, although its support
// reaches the wet node; the weights over the nodes' laws let the front's water into it as the
// wet node's conductance allows. The laws are evaluated once per node and material at each
// evaluation of the flow (fill), not once per point that reaches the node.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "numerics/shape_functions.hpp"
#include "physics/hydraulic_model.hpp"

namespace unsatmpm::numerics {

/// Per stencil node of a point, per fluid a and pressure b: dk_ra/dP_b,i of the point's relative
/// permeability from the nodes, N_i k_ra'(S_e) dS_e/ds ds/dP_b at node i's pressures.
template <int D, class K>
using NodalPermeabilityDerivatives =
    std::array<std::array<std::array<double, 2>, 2>, PointStencil<D, K>::n>;

/// Each material's relative permeabilities at the nodes' pressures, and their slopes in the
/// suction, for the points of that material to weigh (at).
class NodalPermeability {
 public:
  /// The laws of each of `models` at the pressures (per fluid, per node) of the nodes `active`
  /// flags; the others are left as they were (no point reaches them).
  template <class Active>
  void fill(std::span<const physics::HydraulicModel> models,
            const std::array<std::vector<double>, 2>& pressure, Active&& active) {
    n_nodes_ = static_cast<std::int64_t>(pressure[0].size());
    values_.resize(models.size() * static_cast<std::size_t>(n_nodes_) * 4);
    for (std::size_t m = 0; m < models.size(); ++m) {
      const physics::HydraulicModel& hm = models[m];
      for (std::int64_t i = 0; i < n_nodes_; ++i) {
        if (!active(i)) continue;
        const double s = physics::retention_suction(pressure[0][i], pressure[1][i]);
        const double se = hm.effective_saturation(s);
        // As at a point (numerics/pressure/pressure_point.hpp): S depends on the pressures where
        // unsaturated or where an occluded gas gives way, with ds/dP_l = -1 and ds/dP_g = +1.
        const bool unsaturated = s > 0.0 || hm.d_saturation(s) != 0.0;
        const double d_se = unsaturated ? hm.d_effective_saturation(s) : 0.0;
        double* v = &values_[(m * static_cast<std::size_t>(n_nodes_) + i) * 4];
        v[0] = hm.liquid_relative_permeability_value(se);
        v[1] = hm.gas_relative_permeability_value(se);
        v[2] = hm.liquid_relative_permeability_derivative(se) * d_se;
        v[3] = hm.gas_relative_permeability_derivative(se) * d_se;
      }
    }
  }

  /// A point's relative permeabilities {k_rl, k_rg}: its stencil's weights `st` over the values
  /// of its material `material` at the nodes (after fill); with `dk`, their derivatives by node.
  template <int D, class K>
  std::array<double, 2> at(int material, const PointStencil<D, K>& st,
                           NodalPermeabilityDerivatives<D, K>* dk = nullptr) const {
    std::array<double, 2> k{0.0, 0.0};
    const double* laws =
        &values_[static_cast<std::size_t>(material) * static_cast<std::size_t>(n_nodes_) * 4];
    for (int a = 0; a < st.n; ++a) {
      const double* v = laws + static_cast<std::size_t>(st.node[a]) * 4;
      k[0] += st.w[a] * v[0];
      k[1] += st.w[a] * v[1];
      if (dk)
        for (int f = 0; f < 2; ++f) (*dk)[a][f] = {-st.w[a] * v[2 + f], st.w[a] * v[2 + f]};
    }
    return k;
  }

 private:
  std::int64_t n_nodes_ = 0;
  std::vector<double> values_;  // per material, node: k_rl, k_rg, k_rl' dS_e/ds, k_rg' dS_e/ds
};

}  // namespace unsatmpm::numerics

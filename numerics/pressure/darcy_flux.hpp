// The Darcy flux of each fluid at the material points, q_a = J_a / rho_a
// = kappa k_ra / mu_a (-grad P_a + rho_a g) [m/s] (numerics/pressure/pressure_point.hpp), on a
// nodal pressure field at the configuration an integration froze: what the main cycle writes
// for the fluids' motion (docs/output.md).
#pragma once

#include <array>
#include <vector>

#include "numerics/pressure/pressure_point.hpp"
#include "numerics/pressure/quadrature.hpp"
#include "physics/hydraulic_model.hpp"

namespace unsatmpm::numerics {

/// q[a][p] for the points of `q` (quadrature order = the points' order) from the nodal pressures
/// `nodal` [Pa] (per fluid, per node).
template <int D, class K>
void darcy_fluxes(const PointQuadrature<D, K>& pts,
                  const std::vector<physics::HydraulicModel>& models, const Vec<D>& gravity,
                  const std::array<std::vector<double>, 2>& nodal,
                  std::array<std::vector<Vec<D>>, 2>& q) {
  for (auto& v : q) v.assign(pts.size(), Vec<D>::Zero());
  for (std::size_t p = 0; p < pts.size(); ++p) {
    const auto& st = pts.stencil[p];
    std::array<double, 2> pr{0.0, 0.0};
    std::array<Vec<D>, 2> gr{Vec<D>::Zero(), Vec<D>::Zero()};
    for (int a = 0; a < st.n; ++a)
      for (int f = 0; f < 2; ++f) {
        pr[f] += st.w[a] * nodal[f][st.node[a]];
        gr[f] += st.grad[a] * nodal[f][st.node[a]];
      }
    const physics::HydraulicModel& hm = models[pts.model[p]];
    const PointFlow<D> f = point_flow<D, physics::MassBalance::full, false>(
        hm, {pts.porosity[p], 0.0}, pr, gr, gravity, Vec<D>::Zero());
    q[liquid_phase][p] = f.flux[liquid_phase] / hm.liquid_density(pr[liquid_phase]);
    q[gas_phase][p] = f.flux[gas_phase] / hm.gas_density(pr[gas_phase]);
  }
}

}  // namespace unsatmpm::numerics

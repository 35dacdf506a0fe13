// The conductivity at a prescribed pressure, for the explicit cycle's nodes that prescribe a
// fluid's pressure (a face, or the body's free surface where it is open): the soil at such a node
// is at the prescribed state, whatever the points beside it hold. Each node gathers
// sum N V rho_a kappa k_ra / mu_a over the points it reaches, the laws of each point's material
// evaluated at the point's porosity and the prescribed pressure (the other fluid's pressure the
// node's prescribed one if it has one, else the point's); nodal_drag
// (numerics/three_phase_transfers.hpp) takes the mean of it and the points' own. Without it a
// face could wet a dry soil only at the dry soil's conductivity (docs/balance_laws.md, "Wetting a
// dry soil through a face").
#pragma once

#include "numerics/fluid_points.hpp"
#include "numerics/grid.hpp"
#include "numerics/material_points.hpp"
#include "numerics/shape_functions.hpp"
#include "numerics/three_phase_nodes.hpp"
#include "physics/hydraulic_model.hpp"

namespace unsatmpm::numerics {

/// Adds each prescribed node's conductivity at its prescribed state to its record (scatter[0],
/// after p2g_three_phase has reduced the threads' buffers), over the points [begin, end) of one
/// material `hm`. Serial: it evaluates every point's weights (through the kernel memo) and adds
/// only where they reach a prescribed node.
template <int D, class K>
void add_face_conductivities(const Grid<D>& grid, const MaterialPoints<D>& mp,
                             const FluidPoints<D>& fp, const physics::HydraulicModel& hm,
                             std::int64_t begin, std::int64_t end, ThreePhaseNodes<D>& nodes) {
  using L = ThreePhaseLayout<D>;
  TransferStencil<D, K, false> st;  // weights only
  double* records = nodes.scatter[0].data();
  for (std::int64_t p = begin; p < end; ++p) {
    evaluate_stencil<D, K>(st, grid, mp, p);
    for (int a = 0; a < st.n; ++a) {
      const auto i = st.node[a];
      const bool liquid = nodes.liquid_prescribed[i] != 0, gas = nodes.gas_prescribed[i] != 0;
      if (!liquid && !gas) continue;
      const double p_l = liquid ? nodes.liquid_face_pressure[i] : fp.liquid_pressure[p];
      const double p_g = gas ? nodes.gas_face_pressure[i] : fp.gas_pressure[p];
      const physics::LocalFluidState f = hm.state(p_l, p_g);
      const double n = fp.porosity[p], wv = st.w[a] * mp.volume[p];
      double* r = records + i * L::record;
      if (const double q = hm.liquid_drag(n, f.s_l, f.se); liquid && q > 0.0)
        r[L::liquid_face_conductivity] += wv * f.rho_l * n * f.s_l / q;
      if (const double q = hm.gas_drag(n, f.s_l, f.se); gas && q > 0.0)
        r[L::gas_face_conductivity] += wv * f.rho_g * n * (1.0 - f.s_l) / q;
    }
  }
}

}  // namespace unsatmpm::numerics

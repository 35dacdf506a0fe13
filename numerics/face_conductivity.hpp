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

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "numerics/fluid_points.hpp"
#include "numerics/grid.hpp"
#include "numerics/material_points.hpp"
#include "numerics/shape_functions.hpp"
#include "numerics/three_phase_nodes.hpp"
#include "physics/hydraulic_model.hpp"

namespace unsatmpm::numerics {

/// `near`: 1 at every node within one node of a node that prescribes a fluid's pressure (in each
/// direction), 0 elsewhere. A point whose nearest node is not near reaches no prescribed node: its
/// stencil (GIMP's support h + l_p with l_p <= h / 2, or a linear kernel's h) spans only the nodes
/// within one of its nearest.
template <int D>
void mark_near_prescribed(const Grid<D>& grid, const ThreePhaseNodes<D>& nodes,
                          std::vector<std::uint8_t>& near) {
  near.assign(grid.n_nodes(), 0);
  std::array<std::int64_t, D> stride;
  for (int d = 0; d < D; ++d) stride[d] = d == 0 ? 1 : stride[d - 1] * (grid.n_cells[d - 1] + 1);
  for (std::int64_t i = 0; i < grid.n_nodes(); ++i) {
    if (!nodes.liquid_prescribed[i] && !nodes.gas_prescribed[i]) continue;
    const auto ijk = grid.node_ijk(i);
    int count = 1;
    for (int d = 0; d < D; ++d) count *= 3;
    for (int k = 0; k < count; ++k) {
      std::int64_t index = 0;
      bool inside = true;
      for (int d = 0, rest = k; d < D; ++d, rest /= 3) {
        const int j = ijk[d] + rest % 3 - 1;
        inside = inside && j >= 0 && j <= grid.n_cells[d];
        index += j * stride[d];
      }
      if (inside) near[index] = 1;
    }
  }
}

/// Whether point p's nearest node is marked in `near` (mark_near_prescribed).
template <int D>
bool near_prescribed(const Grid<D>& grid, const MaterialPoints<D>& mp, std::int64_t p,
                     const std::vector<std::uint8_t>& near) {
  std::int64_t index = 0, stride = 1;
  for (int d = 0; d < D; ++d) {
    const double u = (mp.position[p][d] - grid.origin[d]) / grid.spacing[d];
    const auto j = std::clamp<std::int64_t>(std::llround(u), 0, grid.n_cells[d]);
    index += j * stride;
    stride *= grid.n_cells[d] + 1;
  }
  return near[index] != 0;
}

/// Adds each prescribed node's conductivity at its prescribed state to its record (scatter[0],
/// after p2g_three_phase has reduced the threads' buffers), over the points [begin, end) of one
/// material `hm`. Serial, over the points whose nearest node is `near` (mark_near_prescribed).
template <int D, class K>
void add_face_conductivities(const Grid<D>& grid, const MaterialPoints<D>& mp,
                             const FluidPoints<D>& fp, const physics::HydraulicModel& hm,
                             std::int64_t begin, std::int64_t end,
                             const std::vector<std::uint8_t>& near, ThreePhaseNodes<D>& nodes) {
  using L = ThreePhaseLayout<D>;
  TransferStencil<D, K, false> st;  // weights only
  double* records = nodes.scatter[0].data();
  // The state at the last pressures met, which a face's nodes mostly share (the laws' powers and
  // exponentials were most of the pass's cost).
  double last_l = std::numeric_limits<double>::quiet_NaN(), last_g = last_l;
  physics::LocalFluidState f{};
  for (std::int64_t p = begin; p < end; ++p) {
    if (!near_prescribed<D>(grid, mp, p, near)) continue;
    evaluate_stencil<D, K>(st, grid, mp, p);
    for (int a = 0; a < st.n; ++a) {
      const auto i = st.node[a];
      const bool liquid = nodes.liquid_prescribed[i] != 0, gas = nodes.gas_prescribed[i] != 0;
      if (!liquid && !gas) continue;
      const double p_l = liquid ? nodes.liquid_face_pressure[i] : fp.liquid_pressure[p];
      const double p_g = gas ? nodes.gas_face_pressure[i] : fp.gas_pressure[p];
      if (p_l != last_l || p_g != last_g) f = hm.state(p_l, p_g), last_l = p_l, last_g = p_g;
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

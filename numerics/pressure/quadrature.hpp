// The material points as the quadrature points of one integration of the pressure system
// (numerics/pressure/pressure_system.hpp), frozen at its start: each point's stencil, material,
// volume, porosity, solid rate, grad ln n and position, the stencil nodes it keeps in the
// Jacobian, and the nodal volumes sum_p N_i V_p; a node is active where its volume exceeds a
// round-off floor (active()); and which active nodes hold no gas (gas_free_nodes).
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "numerics/fluid_points.hpp"
#include "numerics/material_points.hpp"
#include "numerics/shape_functions.hpp"
#include "physics/unsaturated_state.hpp"

namespace unsatmpm::numerics {

template <int D, class K>
struct PointQuadrature {
  using NodeMask = std::uint64_t;  // one bit per stencil node
  static_assert(PointStencil<D, K>::n <= 64, "a stencil of more than 64 nodes");

  std::vector<PointStencil<D, K>> stencil;
  std::vector<NodeMask> jacobian_nodes;  // bit a: stencil node a takes part in the Jacobian
  std::vector<int> model;                // the point's material
  std::vector<double> volume;            // V_p [m^D]
  std::vector<double> porosity;          // n [-]
  std::vector<double> div_vs;            // the solid's volumetric strain rate [1/s]
  std::vector<Vec<D>> grad_ln_n;         // [1/m], from the volume-weighted nodal porosity
  std::vector<Vec<D>> position;          // [m]
  std::vector<double> node_volume;       // sum_p N_i V_p per node [m^D]
  double volume_floor = 0.0;             // [m^D]: node volumes at or below it are round-off

  explicit PointQuadrature(std::int64_t n_nodes) : node_volume(n_nodes, 0.0) {}

  std::size_t size() const { return stencil.size(); }
  /// A node is active where the points' volume on it exceeds the floor, 1e-9 of the smallest
  /// point's volume (as the mechanics' nodes need 1e-9 of the smallest point's mass,
  /// cycles/explicit_solver.hpp). A GIMP point whose domain ends on a node line can give the node
  /// beyond it a weight of round-off size (1e-16): active, that node became the free surface and
  /// held the surface's pressure where no point felt it, and nothing entered (measured: a 1D
  /// column wetted through its free surface took in 1e-16 kg/m^2 in 2 s on 0.0125 m cells,
  /// 1.33 kg/m^2 on 0.025 m cells).
  bool active(std::int64_t i) const { return node_volume[i] > volume_floor; }

  /// Freezes the points' current configuration. `ranges` splits them by material, `div_vs` is
  /// each point's solid rate (empty: none), `jacobian_drop` the drop tolerance
  /// (PressureSystem::set_jacobian_drop_tolerance).
  void fill(const Grid<D>& grid, const MaterialPoints<D>& mp, const FluidPoints<D>& fp,
            const std::vector<std::int64_t>& ranges, std::span<const double> div_vs_in,
            double jacobian_drop) {
    const auto n_mp = mp.size();
    stencil.resize(n_mp), jacobian_nodes.resize(n_mp), model.resize(n_mp);
    volume.resize(n_mp), porosity.resize(n_mp), div_vs.resize(n_mp);
    grad_ln_n.resize(n_mp), position.resize(n_mp);
    std::fill(node_volume.begin(), node_volume.end(), 0.0);
    volume_floor = 0.0;
    if (n_mp > 0) volume_floor = 1e-9 * *std::min_element(mp.volume.begin(), mp.volume.end());
    std::vector<double> porosity_sum(grid.n_nodes(), 0.0);
    mp.kernel_memo.prepare(grid, n_mp);
    for (std::size_t m = 0; m + 1 < ranges.size(); ++m)
      for (auto p = ranges[m]; p < ranges[m + 1]; ++p) {
        auto& st = stencil[p];
        evaluate_stencil<D, K>(st, grid, mp, p);
        jacobian_nodes[p] = kept_nodes(grid, st, jacobian_drop);
        position[p] = mp.position[p];
        model[p] = static_cast<int>(m);
        volume[p] = mp.volume[p], porosity[p] = fp.porosity[p];
        div_vs[p] = div_vs_in.empty() ? 0.0 : div_vs_in[p];
        for (int a = 0; a < st.n; ++a) {
          node_volume[st.node[a]] += st.w[a] * mp.volume[p];
          porosity_sum[st.node[a]] += st.w[a] * mp.volume[p] * fp.porosity[p];
        }
      }
    for (std::size_t p = 0; p < n_mp; ++p) {
      const auto& st = stencil[p];
      Vec<D> g = Vec<D>::Zero();
      for (int a = 0; a < st.n; ++a)
        if (active(st.node[a]))
          g += st.grad[a] * (porosity_sum[st.node[a]] / node_volume[st.node[a]]);
      grad_ln_n[p] = g / porosity[p];
    }
  }

 private:
  /// The stencil nodes where the point's weight N_a or scaled gradient h_min |grad N_a|_max
  /// reaches the drop tolerance (all of them for a tolerance of 0).
  static NodeMask kept_nodes(const Grid<D>& grid, const PointStencil<D, K>& st, double drop) {
    const double h = grid.spacing.minCoeff();
    NodeMask kept = 0;
    for (int a = 0; a < st.n; ++a)
      if (drop == 0.0 || st.w[a] >= drop || h * st.grad[a].cwiseAbs().maxCoeff() >= drop)
        kept |= NodeMask{1} << a;
    return kept;
  }
};

/// 1 at the active nodes free of gas: gas volume sum_p N_i V_p n_p S_g,p at most
/// physics::gas_free_saturation of the pore volume sum_p N_i V_p n_p around them.
template <int D, class K>
std::vector<std::uint8_t> gas_free_nodes(const PointQuadrature<D, K>& q, const FluidPoints<D>& fp) {
  const std::size_t n = q.node_volume.size();
  std::vector<double> pores(n, 0.0), gas(n, 0.0);
  for (std::size_t p = 0; p < q.size(); ++p) {
    const auto& st = q.stencil[p];
    const double v = q.volume[p] * q.porosity[p];
    for (int a = 0; a < st.n; ++a) {
      pores[st.node[a]] += st.w[a] * v;
      gas[st.node[a]] += st.w[a] * v * (1.0 - fp.saturation[p]);
    }
  }
  std::vector<std::uint8_t> free(n, 0);
  for (std::size_t i = 0; i < n; ++i)
    free[i] = q.active(static_cast<std::int64_t>(i)) && physics::free_of_gas(gas[i], pores[i]);
  return free;
}

}  // namespace unsatmpm::numerics

// MUSL's remap (Sulsky, Zhou & Schreyer 1995, "modified update stress last"), the step of the
// explicit transfers that linear shape functions take before the strain: each point's velocity is
// updated first (FLIP/PIC, as g2p would), and its momentum mapped back to the nodes gives the
// velocities of the strain increment, v*_i = sum_p N_ip m_p v_p / sum_p N_ip m_p.
//
// Why (measured 2026-11-29): a node that a point has just reached has a mass N m_p that vanishes
// with the point's weight there, while the point's stress gives it a force that does not (the
// gradient of a linear shape function is 1/h up to the cell's edge). Its own velocity
// v_i + dt f_i / m_i then grows without bound, and in the strain it multiplied that gradient and
// fed the stress back: a free-falling, unstressed elastic block crossing a grid line went from
// 131 J to 7.5e8 J of kinetic energy in five steps and left the grid, in the one-phase cycle and
// the main cycle's mechanics alike. v*_i is a weighted mean of the points' velocities and stays
// bounded. GIMP's weights and gradients both vanish with the overlap at a newly reached node, and
// GIMP keeps the nodes' own velocities (its runs are unchanged).
//
// The explicit three-phase cycle keeps the nodes' own velocities (USL) with either kernel: its
// falling block fails the same way with linear shape functions, but with the remapped solid
// velocity in its strain, the column at water's stiffness that its own-volume-change balance
// holds at rest (tests/cycles/test_saturation_kink.cpp) failed within its 0.2 s (a point's
// masses beyond any pressure). On our reading (not measured) the pressures' work on the grid's
// velocities then no longer matches the compression they are computed from.
#pragma once

#include <cstdint>
#include <type_traits>
#include <utility>
#include <vector>

#include "numerics/explicit_transfers.hpp"

namespace unsatmpm::numerics {

/// For the points [0, n_mp): `update(p, st)` updates point p's velocities at its stencil `st` and
/// returns its mass and solid velocity; their momenta are summed at the nodes (per-thread
/// `buffers`, D + 1 values per node) and `remapped` gets v*_i, or the grid's velocity
/// `grid_velocity` in the components that `fixed` holds (bit d) and along rigid plates. A node no
/// point reaches keeps the grid's velocity.
template <int D, class K, class Points, class Update>
void remap_solid_velocities(const Grid<D>& grid, const Points& mp, int n_threads,
                            const std::vector<Vec<D>>& grid_velocity,
                            const std::vector<std::uint8_t>& fixed,
                            const std::vector<RigidPlate>& plates,
                            std::vector<std::vector<double>>& buffers,
                            std::vector<Vec<D>>& remapped, Update&& update) {
  constexpr int R = D + 1;  // momentum (D), mass
  const std::int64_t n_mp = static_cast<std::int64_t>(mp.size());
  const auto n_nodes = static_cast<std::int64_t>(grid_velocity.size());
  buffers.resize(n_threads);
  for (auto& b : buffers) b.resize(static_cast<std::size_t>(n_nodes * R));
  remapped.resize(n_nodes);
#pragma omp parallel num_threads(n_threads)
  {
    double* buf = cleared_thread_buffer(buffers);
    PointStencil<D, K, false> st;
#pragma omp for schedule(static)
    for (std::int64_t p = 0; p < n_mp; ++p) {
      evaluate_stencil<D, K>(st, grid, mp, p);
      const auto [m, v] = update(p, st);
      for (int a = 0; a < st.n; ++a) {
        double* rec = buf + st.node[a] * R;
        const double wm = st.w[a] * m;
        for (int d = 0; d < D; ++d) rec[d] += wm * v[d];
        rec[D] += wm;
      }
    }
    reduce_thread_buffers(buffers);
#pragma omp for schedule(static)
    for (std::int64_t i = 0; i < n_nodes; ++i) {
      const double* rec = buffers[0].data() + i * R;
      for (int d = 0; d < D; ++d)
        remapped[i][d] =
            (fixed[i] & (1u << d)) || !(rec[D] > 0.0) ? grid_velocity[i][d] : rec[d] / rec[D];
    }
  }
  for (const RigidPlate& plate : plates)
    for (const std::int64_t i : plate.nodes) remapped[i][plate.axis] = grid_velocity[i][plate.axis];
}

/// The one-phase and mixture step's remap (explicit_mechanics_step, before g2p): the FLIP/PIC
/// velocity update of g2p, with the mass p2g used (the mixture's with PoreLoads).
template <int D, class K, class Pore = NoPoreLoads>
void remap_velocities(const Grid<D>& grid, double dt, double flip_fraction, MaterialPoints<D>& mp,
                      NodalState<D>& nodes, const Pore& pore = {}) {
  const int n_threads = static_cast<int>(nodes.scatter.size());
  remap_solid_velocities<D, K>(
      grid, mp, n_threads, nodes.velocity, nodes.fixed, nodes.plates, nodes.remap, nodes.remapped,
      [&](std::int64_t p, const PointStencil<D, K, false>& st) {
        double v_pic[D] = {}, a_sum[D] = {};  // plain scalars, as in g2p
        for (int a = 0; a < st.n; ++a) {
          const double* vn = nodes.velocity[st.node[a]].data();
          const double* an = nodes.acceleration[st.node[a]].data();
          for (int d = 0; d < D; ++d) v_pic[d] += st.w[a] * vn[d], a_sum[d] += st.w[a] * an[d];
        }
        Vec<D>& v = mp.velocity[p];
        for (int d = 0; d < D; ++d)
          v[d] = flip_fraction * (v[d] + dt * a_sum[d]) + (1.0 - flip_fraction) * v_pic[d];
        double m = mp.mass[p];
        if constexpr (std::is_same_v<Pore, PoreLoads>) m += pore.added_mass[p];
        return std::pair<double, Vec<D>>{m, v};
      });
}

}  // namespace unsatmpm::numerics

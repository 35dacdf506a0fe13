// MUSL's remap (Sulsky, Zhou & Schreyer 1995, "modified update stress last"), the step of the
// one-phase cycle's explicit transfers with linear shape functions before the strain: each
// point's velocity is updated first (FLIP/PIC, as g2p would), and its momentum mapped back to the
// nodes gives the velocities of the strain increment, v*_i = sum_p N_ip m_p v_p / sum_p N_ip m_p.
//
// Why (measured 2026-11-29): a node that a point has just reached has a mass N m_p that vanishes
// with the point's weight there, while the point's stress gives it a force that does not (the
// gradient of a linear shape function is 1/h up to the cell's edge). Its own velocity
// v_i + dt f_i / m_i then grows without bound, and in the strain it multiplied that gradient and
// fed the stress back: a free-falling, unstressed elastic block crossing a grid line went from
// 131 J to 7.5e8 J of kinetic energy in five steps and left the grid. v*_i is a weighted mean of
// the points' velocities and stays bounded. GIMP's weights and gradients both vanish with the
// overlap at a newly reached node, and GIMP keeps the nodes' own velocities.
//
// The three-phase cycles keep the nodes' own velocities (USL), and with linear shape functions a
// three-phase block falling across a grid line fails in both as the one-phase block did (a
// point's masses beyond any pressure at the crossing; GIMP is the choice for large motions).
// With the remap their closed saturated columns at P_l ~ P_g (docs/balance_laws.md, "Saturated
// soil at the saturation kink"; 1 m, 0.025 m cells) went unstable at lower liquid stiffness,
// measured to 0.2 s against the same code without it:
//   main cycle, column at rest:    0.5 GPa fails at 68 ms (USL: <= 3.2e-10 J/m^2);
//                                  2.2 GPa fails at 8.9 ms (USL: runs, 0.55 J/m^2)
//   main cycle, loaded by gravity: 0.2 GPa 0.19 J/m^2 (USL 0.12); 0.5 GPa fails at 30 ms
//                                  (USL 0.037 J/m^2)
//   explicit cycle, at rest, 2.2 GPa: fails at 34 ms with the solid's velocity remapped, at
//                                  35 ms with all three phases' (USL: <= 4.9e-11 J/m^2)
// On our reading (not measured) the pressures' work on the grid's velocities no longer matches
// the compression they are computed from, and at the kink that feeds the motion.
#pragma once

#include <cstdint>
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

/// The one-phase step's remap (explicit_mechanics_step, before g2p): the FLIP/PIC velocity
/// update of g2p, with the points' masses as p2g maps them.
template <int D, class K>
void remap_velocities(const Grid<D>& grid, double dt, double flip_fraction, MaterialPoints<D>& mp,
                      NodalState<D>& nodes) {
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
        return std::pair<double, Vec<D>>{mp.mass[p], v};
      });
}

}  // namespace unsatmpm::numerics

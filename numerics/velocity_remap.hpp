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
#include <vector>

#include "numerics/explicit_transfers.hpp"
#include "numerics/parallel.hpp"

namespace unsatmpm::numerics {

/// The one-phase step's remap (explicit_mechanics_step, before g2p): each point's velocity
/// updated as g2p would (FLIP/PIC), its momentum summed at the nodes (per-thread nodes.remap, D
/// values per node) and divided by the node's mass of the same step's p2g (the same points'
/// masses at the same weights), into nodes.remapped; the components that nodes.fixed holds, the
/// rigid plates' normals and the nodes no point reaches keep the grid's velocity.
template <int D, class K>
void remap_velocities(const Grid<D>& grid, double dt, double flip_fraction, MaterialPoints<D>& mp,
                      NodalState<D>& nodes) {
  const std::int64_t n_mp = static_cast<std::int64_t>(mp.size()), n_nodes = nodes.n_nodes();
  const int n_threads = static_cast<int>(nodes.scatter.size());
  nodes.remap.resize(n_threads);
  for (auto& b : nodes.remap) b.resize(static_cast<std::size_t>(n_nodes * D));
  nodes.remapped.resize(n_nodes);
  parallel_region(n_threads, [&] {
    double* buf = cleared_thread_buffer(nodes.remap);
    PointStencil<D, K, false> st;
#pragma omp for schedule(static)
    for (std::int64_t p = 0; p < n_mp; ++p) {
      evaluate_stencil<D, K>(st, grid, mp, p);
      double v_pic[D] = {}, a_sum[D] = {};  // plain scalars, as in g2p
      for (int a = 0; a < st.n; ++a) {
        const double* vn = nodes.velocity[st.node[a]].data();
        const double* an = nodes.acceleration[st.node[a]].data();
        for (int d = 0; d < D; ++d) v_pic[d] += st.w[a] * vn[d], a_sum[d] += st.w[a] * an[d];
      }
      Vec<D>& v = mp.velocity[p];
      for (int d = 0; d < D; ++d)
        v[d] = flip_fraction * (v[d] + dt * a_sum[d]) + (1.0 - flip_fraction) * v_pic[d];
      for (int a = 0; a < st.n; ++a) {
        const double wm = st.w[a] * mp.mass[p];
        for (int d = 0; d < D; ++d) buf[st.node[a] * D + d] += wm * v[d];
      }
    }
    reduce_thread_buffers(nodes.remap);
#pragma omp for schedule(static)
    for (std::int64_t i = 0; i < n_nodes; ++i) {
      const double m = nodes.mass(i);
      for (int d = 0; d < D; ++d)
        nodes.remapped[i][d] = (nodes.fixed[i] & (1u << d)) || !(m > 0.0)
                                   ? nodes.velocity[i][d]
                                   : nodes.remap[0][i * D + d] / m;
    }
  });
  for (const RigidPlate& plate : nodes.plates)
    for (const std::int64_t i : plate.nodes)
      nodes.remapped[i][plate.axis] = nodes.velocity[i][plate.axis];
}

}  // namespace unsatmpm::numerics

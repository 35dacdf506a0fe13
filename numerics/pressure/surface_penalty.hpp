// A fluid's free-surface pressure as a penalty on the face's trace, in place of holding the
// surface node layer (numerics/pressure/free_surface.hpp says what holding a layer costs where the
// face lies between node lines; verification/embankment/investigations.md, "A penalty on the face's
// trace", measures a prototype of this form). Node i's balance of fluid a gains
//     Π_i = Σ_j c_ij (P̄ − P_j),   c_ij = (γ / h) √(λ_i λ_j) B_ij   [kg/(s Pa) per unit
//                                                                     out-of-plane measure in 2D]
// with B the surface mass matrix on the face estimated from the nodes' volume fractions and
// capped by their volumes (numerics/pressure/face_trace.hpp), h the cells' mean edge, λ_i the
// fluid's mobility ρ_a κ / μ_a at full relative permeability, averaged over the points on node i
// with their weights N_i V_p, and γ > 0 the penalty factor (dimensionless). c is symmetric
// positive semi-definite, so the penalty only ever draws the pressures towards P̄. Π_i is mass
// that enters through the face: the operator adds it to F_i and counts it as inflow
// (numerics/pressure/pressure_operator.hpp). The surface nodes the face barely reaches (below
// inside_fraction of a full node's volume) stay held at P̄ (PressureSystem::set_surface_penalty).
#pragma once

#include <cmath>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <vector>

#include "numerics/pressure/face_trace.hpp"
#include "numerics/pressure/free_surface.hpp"
#include "numerics/pressure/quadrature.hpp"
#include "numerics/pressure/unknowns.hpp"
#include "numerics/sparse_pattern.hpp"
#include "physics/hydraulic_model.hpp"

namespace unsatmpm::numerics {

/// The mean edge of the grid's cells [m].
template <int D>
double mean_cell_edge(const Grid<D>& grid) {
  double h = 0.0;
  for (int d = 0; d < D; ++d) h += grid.spacing[d];
  return h / D;
}

/// Node i's volume fraction: the points' volume on it over a full node's, h^D halved per grid face
/// the node lies on (the tent's integral inside the grid), clamped to [0, 1].
template <int D>
double node_volume_fraction(const Grid<D>& grid, std::int64_t i, double node_volume) {
  const auto ijk = grid.node_ijk(i);
  double full = 1.0;
  for (int d = 0; d < D; ++d)
    full *= (ijk[d] == 0 || ijk[d] == grid.n_cells[d]) ? grid.spacing[d] / 2 : grid.spacing[d];
  return std::clamp(node_volume / full, 0.0, 1.0);
}

/// Whether node i, holding `node_volume` [m^D] of the points, has less than inside_fraction of a
/// full node's volume (numerics/pressure/free_surface.hpp): a surface node the face barely
/// reaches, held under the penalty (PressureSystem::set_surface_penalty).
template <int D>
bool light_node(const Grid<D>& grid, double node_volume, std::int64_t i) {
  return node_volume_fraction<D>(grid, i, node_volume) < inside_fraction;
}

/// The coupling c of fluid a's penalty (above) at the points' configuration in `q`; entries of
/// inactive nodes are left out (the cap gives them none). Throws std::invalid_argument unless
/// γ > 0 and finite.
template <int D, class K>
FaceTrace surface_penalty(const Grid<D>& grid, const PointQuadrature<D, K>& q,
                          std::span<const physics::HydraulicModel> models, int fluid,
                          double gamma) {
  if (!(gamma > 0.0 && std::isfinite(gamma)))
    throw std::invalid_argument("surface_penalty: the penalty factor must be > 0 and finite");
  const std::int64_t n = grid.n_nodes();
  const double h = mean_cell_edge<D>(grid);
  std::vector<double> psi(n), mobility(n, 0.0);
  for (std::int64_t i = 0; i < n; ++i)
    psi[i] = face_distance(node_volume_fraction<D>(grid, i, q.node_volume[i]), h);
  FaceTrace c = face_trace<D>(grid, psi);
  cap_by_volume(c, q.node_volume, h);
  for (std::size_t p = 0; p < q.size(); ++p) {
    const auto& m = models[q.model[p]];
    const double lambda =
        fluid == 0 ? m.liquid_density(0.0) * m.intrinsic_permeability / m.liquid_viscosity
                   : m.gas_density(0.0) * m.intrinsic_permeability / m.gas_viscosity;
    const auto& st = q.stencil[p];
    for (int a = 0; a < st.n; ++a) mobility[st.node[a]] += st.w[a] * q.volume[p] * lambda;
  }
  FaceTrace kept;
  for (std::size_t k = 0; k < c.value.size(); ++k) {
    const auto i = c.row[k], j = c.col[k];
    if (!q.active(i) || !q.active(j) || c.value[k] == 0.0) continue;
    const double li = mobility[i] / q.node_volume[i], lj = mobility[j] / q.node_volume[j];
    kept.row.push_back(i), kept.col.push_back(j);
    kept.value.push_back(gamma / h * std::sqrt(li * lj) * c.value[k]);
  }
  return kept;
}

/// The coupling c restricted to the held part of the face, where a surface condition leaves some
/// surface nodes free (`exempt`, among the free-surface nodes `surface`: rain's flux nodes,
/// cycles/rainfall.hpp): the entries between held nodes, these being the surface nodes not
/// exempt and the nodes off the surface that c couples to one of them. The trace reaches nodes
/// inside the body too (a face a tenth of a cell past a node line has the node on that line as
/// its nearest, not a surface node), and left in, such a node under rain drew the face to zero
/// suction before it ponded: a 1D column took in 2.83 kg/m^2 in the first 0.3 s of a rain that
/// brought 0.83. Keeping rows and columns of one node set keeps c symmetric positive
/// semi-definite (a principal submatrix). `exempt` empty: c whole.
inline FaceTrace held_part(FaceTrace c, const std::vector<std::uint8_t>& surface,
                           const std::vector<std::uint8_t>& exempt) {
  if (exempt.empty()) return c;
  std::vector<std::uint8_t> held(surface.size(), 0);
  for (std::size_t k = 0; k < c.value.size(); ++k) {
    const auto i = c.row[k], j = c.col[k];
    if (surface[i] ? !exempt[i] : surface[j] && !exempt[j]) held[i] = 1;
  }
  std::size_t kept = 0;
  for (std::size_t k = 0; k < c.value.size(); ++k) {
    if (!held[c.row[k]] || !held[c.col[k]]) continue;
    c.row[kept] = c.row[k], c.col[kept] = c.col[k], c.value[kept] = c.value[k];
    ++kept;
  }
  c.row.resize(kept), c.col.resize(kept), c.value.resize(kept);
  return c;
}

/// Π_i = Σ_j c_ij (P̄ - P_j) per node into `penalty` (zeroed first) and added to `force`.
inline void add_penalty_mass(const FaceTrace& c, double target, std::span<const double> pressure,
                             std::span<double> penalty, std::span<double> force) {
  std::fill(penalty.begin(), penalty.end(), 0.0);
  for (std::size_t k = 0; k < c.value.size(); ++k)
    penalty[c.row[k]] += c.value[k] * (target - pressure[c.col[k]]);
  for (std::size_t k = 0; k < c.value.size(); ++k)  // the rows are sorted: each once
    if (k == 0 || c.row[k] != c.row[k - 1]) force[c.row[k]] += penalty[c.row[k]];
}

/// dΠ_i/dP_j = -c_ij into the Jacobian's rows of fluid a's unknowns and, as Π counts as inflow,
/// into its inflow integral's row (over `inflow_scale`); at a prescribed node Π cancels in its
/// inflow M P' - F + Π, so nothing goes there.
inline void add_penalty_jacobian(const FaceTrace& c, int a, const PressureUnknowns& unknowns,
                                 const SparsePattern& pattern, double inflow_scale,
                                 std::span<double> values) {
  for (std::size_t k = 0; k < c.value.size(); ++k) {
    const auto row = unknowns(a, c.row[k]), col = unknowns(a, c.col[k]);
    if (row < 0 || col < 0) continue;
    values[pattern.position(row, col)] -= c.value[k];
    values[pattern.position(unknowns.inflow(a), col)] -= c.value[k] / inflow_scale;
  }
}

}  // namespace unsatmpm::numerics

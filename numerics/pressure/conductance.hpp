// The Darcy conductance of the pressure system's nodes, for the main cycle's flow correction
// (cycles/flow_correction.hpp): the linear operator that gives the mass rate leaving each node
// for a nodal pressure field with the coefficients frozen,
//   L_ij = sum_p V_p c_p g_i(x_p) . g_j(x_p)   [kg/(s Pa) per out-of-plane measure],
// c_p = rho kappa k_r / mu at the point (PointFlow::conductivity), one block per fluid, over the
// points of a PressureSystem's quadrature and its unknowns (the free nodes of each fluid), with
// g the shape functions' gradients over the stencil nodes the point keeps in the Jacobian
// (PointQuadrature::jacobian_nodes): a dropped node's gradient is handed to the kept ones in
// proportion to their weights, g_a = grad N_a + (N_a / sum_kept N) sum_dropped grad N_b, so that
// the g still sum to zero. L is then the Galerkin operator where nothing is dropped (linear shape
// functions, or no drop tolerance), and always symmetric and positive semi-definite (a sum of
// V c g g^T), with rows that sum to zero over all nodes: it moves mass between nodes without
// creating any; restricted to the free nodes, what a row leaves over goes to the prescribed ones.
// Dropping GIMP's barely touched nodes narrows its coupling as it does the Jacobian's.
//
// The pattern it builds also holds each node's liquid-gas pair, for the storage blocks the
// correction adds, and every diagonal entry.
//
// Where a fluid's free-surface condition is a penalty on the face's trace
// (numerics/pressure/surface_penalty.hpp: Π = c (P̄ - P) enters node i), a change δ of the nodal
// pressures also sends c δ out through the face, so L gains c between that fluid's unknowns.
// c is symmetric positive semi-definite, so L stays so; its rows no longer sum to zero at the
// face: what they leave over leaves the body, as what goes to a prescribed node does.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "numerics/pressure/face_trace.hpp"
#include "numerics/pressure/quadrature.hpp"
#include "numerics/pressure/unknowns.hpp"
#include "numerics/shape_functions.hpp"
#include "numerics/sparse_pattern.hpp"

namespace unsatmpm::numerics {

/// Point p's gradients g over its stencil (see the header), zero at the dropped nodes.
template <int D, class K>
std::array<Vec<D>, PointStencil<D, K>::n> kept_gradients(const PointQuadrature<D, K>& q,
                                                         std::size_t p) {
  const auto& st = q.stencil[p];
  const auto kept = q.jacobian_nodes[p];
  std::array<Vec<D>, PointStencil<D, K>::n> g;
  Vec<D> dropped = Vec<D>::Zero();
  double weight = 0.0;
  for (int a = 0; a < st.n; ++a) {
    if (kept >> a & 1u) {
      g[a] = st.grad[a];
      weight += st.w[a];
    } else {
      g[a] = Vec<D>::Zero();
      dropped += st.grad[a];
    }
  }
  if (weight > 0.0)
    for (int a = 0; a < st.n; ++a)
      if (kept >> a & 1u) g[a] += (st.w[a] / weight) * dropped;
  return g;
}

/// The pattern over the pressure unknowns of `u` (the inflow integrals left out): each point
/// couples the unknowns of one fluid at the stencil nodes it keeps, each node its two fluids, and
/// each pair of `penalty` the unknowns of its fluid.
template <int D, class K>
SparsePattern conductance_pattern(const PointQuadrature<D, K>& q, const PressureUnknowns& u,
                                  const FacePenalties& penalty = {}) {
  const std::int64_t n = u.n_pressures();
  std::vector<std::vector<std::int64_t>> rows(n);
  for (std::size_t p = 0; p < q.size(); ++p) {
    const auto& st = q.stencil[p];
    const auto kept = q.jacobian_nodes[p];
    for (int a = 0; a < st.n; ++a)
      for (int f = 0; f < 2; ++f)
        if (const auto r = u(f, st.node[a]); r >= 0 && (kept >> a & 1u))
          for (int b = 0; b < st.n; ++b)
            if (const auto c = u(f, st.node[b]); c >= 0 && (kept >> b & 1u)) rows[r].push_back(c);
  }
  for (const auto i : u.nodes())
    if (u(0, i) >= 0 && u(1, i) >= 0)
      rows[u(0, i)].push_back(u(1, i)), rows[u(1, i)].push_back(u(0, i));
  for (int f = 0; f < 2; ++f)
    for (std::size_t k = 0; k < penalty[f].value.size(); ++k)
      if (const auto r = u(f, penalty[f].row[k]), c = u(f, penalty[f].col[k]); r >= 0 && c >= 0)
        rows[r].push_back(c);
  return pattern_from_rows(rows);
}

/// L's values in `pattern` (from conductance_pattern with the same `penalty`), with
/// `conductivity[f][p]` the point's c of fluid f [kg/(m s Pa)]; entries between fluids stay zero.
template <int D, class K>
void assemble_conductance(const PointQuadrature<D, K>& q, const PressureUnknowns& u,
                          const std::array<std::vector<double>, 2>& conductivity,
                          const SparsePattern& pattern, std::span<double> values,
                          const FacePenalties& penalty = {}) {
  std::fill(values.begin(), values.end(), 0.0);
  for (std::size_t p = 0; p < q.size(); ++p) {
    const auto& st = q.stencil[p];
    const auto kept = q.jacobian_nodes[p];
    const auto g = kept_gradients<D, K>(q, p);
    for (int f = 0; f < 2; ++f) {
      const double vc = q.volume[p] * conductivity[f][p];
      if (vc == 0.0) continue;
      for (int a = 0; a < st.n; ++a) {
        const auto r = u(f, st.node[a]);
        if (r < 0 || !(kept >> a & 1u)) continue;
        for (int b = 0; b < st.n; ++b)
          if (const auto c = u(f, st.node[b]); c >= 0 && (kept >> b & 1u))
            values[pattern.position(r, c)] += vc * g[a].dot(g[b]);
      }
    }
  }
  // The face's penalty between free unknowns; a pair with a held node sends nothing, as its
  // pressure does not depart.
  for (int f = 0; f < 2; ++f)
    for (std::size_t k = 0; k < penalty[f].value.size(); ++k)
      if (const auto r = u(f, penalty[f].row[k]), c = u(f, penalty[f].col[k]); r >= 0 && c >= 0)
        values[pattern.position(r, c)] += penalty[f].value[k];
}

}  // namespace unsatmpm::numerics

// The body's face as the grid sees it, and the surface mass matrix of the nodal field on it: the
// building block of a surface condition that acts where the face lies, not at the node layer
// nearest it (numerics/pressure/free_surface.hpp says what holding a node layer costs on a face
// that lies between node lines; verification/embankment/investigations.md, "A penalty on the face's
// trace", measures a penalty built on this matrix).
//
// The face is the zero level set of a signed distance ψ estimated at each node from its volume
// fraction φ_i = Σ_p N_i V_p / ∫ N_i (the points' volume on the node over a full node's): for a
// straight face parallel to a node line, a node a distance a beyond the face (0 ≤ a ≤ h) has
// φ = (h − a)² / (2 h²) under the tent and uGIMP weights, and one a distance a inside it
// φ = 1 − (h − a)² / (2 h²), so
//     ψ = h (√(2 φ) − 1)            for φ < 1/2  (beyond the face, ψ ≤ 0),
//     ψ = h (1 − √(2 (1 − φ)))      for φ ≥ 1/2  (inside, ψ ≥ 0),
// exact for such a face on square cells (h their edge; the mean edge on others). ψ is
// interpolated linearly on the simplices of each cell's Kuhn triangulation (D! simplices, the
// paths from corner 0 adding one direction at a time; conforming between cells, so the face is
// closed), whose zero set is a point (1D), a segment (2D) or a triangle or quadrilateral (3D).
// On it, B_ij = ∫_Γh N_i N_j dΓ with N the cells' multilinear nodal functions, by Gauss–Legendre
// with 3 points on a segment (exact: N_i N_j is of degree 4 along a straight segment) and
// Dunavant's 6-point rule on a triangle (degree 4; N_i N_j is of degree 6 on a plane in 3D).
// Σ_q w_q N(x_q) N(x_q)^T with positive weights: B is symmetric positive semi-definite whatever
// the face, and Σ_ij B_ij is the face's measure.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <span>
#include <stdexcept>
#include <tuple>
#include <vector>

#include "numerics/grid.hpp"

namespace unsatmpm::numerics {

/// A symmetric matrix over node pairs: each (row, col) once, sorted by row then column.
struct FaceTrace {
  std::vector<std::int64_t> row, col;
  std::vector<double> value;  // ∫_Γh N_row N_col dΓ [m^(D-1); 1 in 1D]
};

/// Per fluid, the coupling of its free surface's penalty (numerics/pressure/surface_penalty.hpp;
/// empty: none).
using FacePenalties = std::array<FaceTrace, 2>;

/// The signed distance [m] (> 0 inside the body) of a node whose volume fraction is φ ∈ [0, 1],
/// for cells of edge h (above). Throws std::invalid_argument for φ outside [0, 1].
inline double face_distance(double fraction, double h) {
  if (!(fraction >= 0.0 && fraction <= 1.0))
    throw std::invalid_argument("face_distance: a volume fraction outside [0, 1]");
  return fraction < 0.5 ? h * (std::sqrt(2.0 * fraction) - 1.0)
                        : h * (1.0 - std::sqrt(2.0 * (1.0 - fraction)));
}

namespace face_trace_detail {

// A point of the face in a cell's local coordinates ξ ∈ [0, 1]^D.
template <int D>
using Local = std::array<double, D>;

// Where ψ, linear between corners u and v of the cell, is zero.
template <int D>
Local<D> crossing(int u, int v, double psi_u, double psi_v) {
  const double t = psi_u / (psi_u - psi_v);
  Local<D> x;
  for (int d = 0; d < D; ++d) {
    const double a = (u >> d) & 1, b = (v >> d) & 1;
    x[d] = a + t * (b - a);
  }
  return x;
}

// The physical measure of a segment (2D) or a triangle (3D) given in local coordinates.
template <int D>
double measure(std::span<const Local<D>> p, const Vec<D>& h) {
  std::array<std::array<double, 3>, 2> e{};
  for (int k = 0; k + 1 < static_cast<int>(p.size()); ++k)
    for (int d = 0; d < D; ++d) e[k][d] = (p[k + 1][d] - p[0][d]) * h[d];
  if constexpr (D == 2) return std::hypot(e[0][0], e[0][1]);
  const double cx = e[0][1] * e[1][2] - e[0][2] * e[1][1];
  const double cy = e[0][2] * e[1][0] - e[0][0] * e[1][2];
  const double cz = e[0][0] * e[1][1] - e[0][1] * e[1][0];
  return 0.5 * std::sqrt(cx * cx + cy * cy + cz * cz);
}

// The quadrature points and weights (fractions of the piece's measure) of a piece of the face.
template <int D>
void quadrature(std::span<const Local<D>> p, std::vector<std::pair<Local<D>, double>>& q) {
  q.clear();
  if constexpr (D == 1) {
    q.push_back({p[0], 1.0});
  } else if constexpr (D == 2) {              // Gauss–Legendre, 3 points on [0, 1]
    constexpr double r = 0.3872983346207417;  // sqrt(3/5) / 2
    for (const auto& [s, w] : {std::pair{0.5 - r, 5.0 / 18.0}, std::pair{0.5, 8.0 / 18.0},
                               std::pair{0.5 + r, 5.0 / 18.0}}) {
      Local<D> x;
      for (int d = 0; d < D; ++d) x[d] = p[0][d] + s * (p[1][d] - p[0][d]);
      q.push_back({x, w});
    }
  } else {  // Dunavant's degree-4 rule, barycentric (a, a, 1 - 2a) and its permutations
    for (const auto& [a, w] : {std::pair{0.445948490915965, 0.223381589678011},
                               std::pair{0.091576213509771, 0.109951743655322}}) {
      const double b = 1.0 - 2.0 * a;
      for (const auto& l : {std::array{a, a, b}, std::array{a, b, a}, std::array{b, a, a}}) {
        Local<D> x;
        for (int d = 0; d < D; ++d) x[d] = l[0] * p[0][d] + l[1] * p[1][d] + l[2] * p[2][d];
        q.push_back({x, w});
      }
    }
  }
}

// The pieces of the zero set of ψ in one simplex (its corners as cell corners): 0 or 1 piece in
// 1D and 2D, up to 2 triangles in 3D. Inside is ψ > 0.
template <int D>
int simplex_pieces(const std::array<int, D + 1>& corner, const std::array<double, 1 << D>& psi,
                   std::array<std::array<Local<D>, D>, 2>& piece) {
  std::array<int, D + 1> in{}, out{};
  int n_in = 0, n_out = 0;
  for (int k = 0; k <= D; ++k) (psi[corner[k]] > 0.0 ? in[n_in++] : out[n_out++]) = corner[k];
  if (n_in == 0 || n_out == 0) return 0;
  const auto cut = [&](int u, int v) { return crossing<D>(u, v, psi[u], psi[v]); };
  if constexpr (D < 3) {
    int k = 0;
    for (int i = 0; i < n_in; ++i)
      for (int o = 0; o < n_out; ++o) piece[0][k++] = cut(in[i], out[o]);
    return 1;
  } else {
    if (n_in == 2) {  // a quadrilateral: the cycle in0-out0, in0-out1, in1-out1, in1-out0
      const Local<D> a = cut(in[0], out[0]), b = cut(in[0], out[1]), c = cut(in[1], out[1]),
                     d = cut(in[1], out[0]);
      piece[0] = {a, b, c}, piece[1] = {a, c, d};
      return 2;
    }
    const auto& one = n_in == 1 ? in : out;  // the lone vertex on its side
    const auto& three = n_in == 1 ? out : in;
    piece[0] = {cut(one[0], three[0]), cut(one[0], three[1]), cut(one[0], three[2])};
    return 1;
  }
}

}  // namespace face_trace_detail

/// B_ij = ∫_Γh N_i N_j dΓ over the zero set of the nodal signed distances `psi` (one per grid
/// node, face_distance; > 0 inside the body).
template <int D>
FaceTrace face_trace(const Grid<D>& grid, std::span<const double> psi) {
  namespace detail = face_trace_detail;
  if (static_cast<std::int64_t>(psi.size()) != grid.n_nodes())
    throw std::invalid_argument("face_trace: one distance per grid node expected");
  constexpr int corners = 1 << D;
  // The Kuhn simplices: for each order of the directions, corner 0 and the corners reached by
  // adding them one at a time.
  std::array<int, D> order;
  std::iota(order.begin(), order.end(), 0);
  std::vector<std::array<int, D + 1>> simplices;
  do {
    std::array<int, D + 1> s{};
    for (int k = 0; k < D; ++k) s[k + 1] = s[k] | (1 << order[k]);
    simplices.push_back(s);
  } while (std::next_permutation(order.begin(), order.end()));

  std::vector<std::tuple<std::int64_t, std::int64_t, double>> entries;
  std::array<std::int64_t, corners> node;
  std::array<double, corners> cell_psi;
  std::array<std::array<detail::Local<D>, D>, 2> pieces;
  std::vector<std::pair<detail::Local<D>, double>> points;
  std::array<std::array<double, corners>, corners> local;
  for (std::int64_t c = 0; c < grid.n_cells_total(); ++c) {
    std::int64_t rest = c, base = 0;
    for (int d = 0; d < D; ++d) {
      base += (rest % grid.n_cells[d]) * grid.stride[d];
      rest /= grid.n_cells[d];
    }
    bool any_in = false, any_out = false;
    for (int k = 0; k < corners; ++k) {
      node[k] = base;
      for (int d = 0; d < D; ++d)
        if ((k >> d) & 1) node[k] += grid.stride[d];
      cell_psi[k] = psi[node[k]];
      (cell_psi[k] > 0.0 ? any_in : any_out) = true;
    }
    if (!any_in || !any_out) continue;
    for (auto& r : local) r.fill(0.0);
    for (const auto& s : simplices) {
      const int n = detail::simplex_pieces<D>(s, cell_psi, pieces);
      for (int k = 0; k < n; ++k) {
        const double size = D == 1 ? 1.0 : detail::measure<D>(pieces[k], grid.spacing);
        detail::quadrature<D>(pieces[k], points);
        for (const auto& [x, w] : points) {
          std::array<double, corners> shape;
          for (int a = 0; a < corners; ++a) {
            shape[a] = 1.0;
            for (int d = 0; d < D; ++d) shape[a] *= (a >> d) & 1 ? x[d] : 1.0 - x[d];
          }
          for (int a = 0; a < corners; ++a)
            for (int b = 0; b < corners; ++b) local[a][b] += size * w * shape[a] * shape[b];
        }
      }
    }
    for (int a = 0; a < corners; ++a)
      for (int b = 0; b < corners; ++b)
        if (local[a][b] != 0.0) entries.emplace_back(node[a], node[b], local[a][b]);
  }
  std::sort(entries.begin(), entries.end());
  FaceTrace trace;
  for (const auto& [i, j, v] : entries) {
    if (!trace.row.empty() && trace.row.back() == i && trace.col.back() == j) {
      trace.value.back() += v;
      continue;
    }
    trace.row.push_back(i), trace.col.push_back(j), trace.value.push_back(v);
  }
  return trace;
}

/// Caps each node's share of the trace by its volume V_i [m^D] (Σ_p N_i V_p): B becomes S B S
/// with S = diag(√s_i), s_i = min(1, (2 / h) V_i / B_ii), so that no node's diagonal exceeds
/// 2 V_i / h, what the node beyond a straight face has in 1D at any offset (B_ii = (1 − a/h)²,
/// V_i = h (1 − a/h)² / 2). A straight face parallel to the node lines stays below it in 2D and
/// 3D (4/3 and 8/9 of V_i / h at most), so the cap leaves it alone; it binds where a body's
/// tip or thin wedge puts the face near a node that holds little of the body, which a
/// condition on the trace would otherwise make stiff out of proportion to the node's storage
/// (the embankment's toe, verification/embankment/README.md). S B S stays symmetric positive
/// semi-definite. Throws std::invalid_argument if `volume` is not one per node of the rows.
inline void cap_by_volume(FaceTrace& b, std::span<const double> volume, double h) {
  std::vector<double> scale;  // √s_i of each row's node, by row
  std::vector<std::int64_t> node;
  for (std::size_t k = 0; k < b.value.size(); ++k) {
    if (b.row[k] >= static_cast<std::int64_t>(volume.size()))
      throw std::invalid_argument("cap_by_volume: a node without a volume");
    if (b.row[k] != b.col[k]) continue;
    const double cap = 2.0 * volume[b.row[k]] / h;
    node.push_back(b.row[k]);
    scale.push_back(b.value[k] > cap ? std::sqrt(cap / b.value[k]) : 1.0);
  }
  const auto scale_of = [&](std::int64_t i) {
    const auto at = std::lower_bound(node.begin(), node.end(), i);
    return at != node.end() && *at == i ? scale[at - node.begin()] : 1.0;
  };
  for (std::size_t k = 0; k < b.value.size(); ++k)
    b.value[k] *= scale_of(b.row[k]) * scale_of(b.col[k]);
}

}  // namespace unsatmpm::numerics

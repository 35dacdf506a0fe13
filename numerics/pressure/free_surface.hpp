// The free surface of the active region: the active nodes of every grid cell that has corners
// inside the body and corners outside it (the outer layer of the body, found again at every step,
// so it follows the body as it deforms), and of every cell with a corner inside that no point
// reaches (a gap in the body). Nodes on the grid's outer faces count only through the cells
// inside the grid: a face where the body touches the grid's boundary is not a free surface.
//
// The empty cells. A body torn apart (a slide's surface points thrown off it, a crack opening)
// leaves cells that no point reaches with all their corners active, because points on either
// side reach them. Counted by their corners alone such cells lay inside the body: a point thrown
// off the embankment's face, alone in its cell with the cell below it empty, kept a node joined
// to the body's surface points through the empty cells, a pressure unknown with little more than
// that one point's storage, where the main cycle's flow stopped in steps of 1e-7 s on the gas
// (verification/embankment/investigations.md, "A point thrown off the face"). A gap open to the air
// is a free surface, so its corners are the surface, and a point that has left the body has all its
// nodes on the surface and drains to the surface's pressure. Every cell of an intact body holds
// points (2 to 4 per direction at generation), so its surface is the same either way.
//
// Two layers. With every active node inside (the one-test form) this is the outermost layer: the
// main cycle holds its pressures there (numerics/pressure/pressure_system.hpp) and the explicit
// cycle holds a closed surface's fluids to the solid there. With GIMP a body whose face lies just
// past a node line gives the node beyond a small weight, and the outermost layer is that node
// alone, while the node on the line carries the face's points and most of its outward area. With
// `inside` at an eighth of a full node's volume (the two-test form) the node on the line is in the
// surface too: the explicit cycle applies a surface pressure there (cycles/three_phase_solver.hpp),
// where it had counted the node as closed, so that the water let in through the light node beyond
// could not get out (verification/embankment/investigations.md, "Why only the explicit cycle
// loosens surface points").
//
// The main cycle keeps the outermost layer, which fails on such a face: a 1D column (40 cells per
// metre, GIMP, rigid) whose top lies a tenth of a cell past a node line took in 0.011 kg/m^2 by
// 0.5 s through its wetted top against 0.672 with the top on the line (the explicit cycle: 0.635
// with both layers, 0.506 with the outermost alone, against 0.600). Holding both layers in the main
// cycle instead over-imposes the surface by up to half a cell: on the embankment with a rigid
// skeleton the water taken in by 15 s, outermost layer / both layers, was 2,279 / 3,154 kg/m on
// 0.4 m cells, 3,207 / 3,496 on 0.2 m, 3,296 / 3,435 on 0.1 m and 3,330 / 3,399 on 0.05 m (both
// converging to about 3,350), and on V12 (verification/collapse) it broke the cycles' agreement
// (run-outs 0.30 m apart against 0.1 m allowed, surface points torn to the maximum porosity in the
// main cycle only). Holding only the node layer nearest the face (the inside nodes of the two-test
// form's cells; the light node beyond left free) kept V12's run-outs together (0.02 m apart) but
// not its suctions (RMS difference 0.061 s0 against 0.02 allowed, largest 0.56 s0 against 0.25;
// the outermost layer: 0.007 and 0.059). On the 1D column the water taken in by 0.5 s through a
// top lying 0, 0.1, 0.3 and 0.49 of a cell past the node line, outermost / both layers / nearest
// layer: 0.672 / 0.672 / 0.672, 0.011 / 0.681 / 0.524, 0.102 / 0.729 / 0.677, 0.277 / 0.849 /
// 0.849 kg/m^2 (2026-11-27; a node held up to half a cell inside the face over-imposes it, one
// held outside it with a small weight starves it). A surface condition for the main cycle that
// acts through the outward area, as the explicit cycle's does, is the candidate; not built. A
// prototype penalising the pressure on an estimated face (the surface mass matrix of the nodal
// field on the zero contour of a distance taken from the nodes' volumes) made a column's
// intake (0.1 m cells, by 15 s) independent of where its top lies: 194.0 / 196.6 / 197.2 / 197.4
// kg/m^2 for penalty factors 4 / 16 / 64 / 256 at tops 0 to 5/6 of a cell past a node line,
// against 197.4 on the line and 45 to 190 off it when holding the outermost layer. On the gas it
// failed V12's suctions; on the liquid alone it passed V12, but the main cycle's face then
// loosened in V5b's fast variant (verification/embankment/investigations.md, "A penalty on the
// face's trace"). The penalty on the liquid is built (numerics/pressure/surface_penalty.hpp,
// solver.implicit.surface_penalty), with the surface nodes below inside_fraction held, and is not
// yet the committed cases' choice. What the outermost layer costs on a sloped face: the
// embankment's top 0.2 m at 15 s holds 60 kPa of suction on 0.2 m cells against a converged 15 kPa,
// and 24 kPa before the gravity loading's 3 cm settlement made more of the held nodes light
// (verification/embankment/investigations.md, "Which cycle's face is right").
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "numerics/grid.hpp"
#include "numerics/material_points.hpp"
#include "numerics/shape_functions.hpp"

namespace unsatmpm::numerics {

/// A node is inside the body where the points' volume on it, sum_p N_i V_p, is at least this
/// fraction of a full node's, h^D (an interior node's): an eighth is what the node beyond a
/// straight face gets when the face lies halfway between two node lines (the tent's integral over
/// half a cell, (1/2)^2 / 2, for linear and uGIMP kernels alike), so that the surface is the node
/// layer nearest the body's edge, with the layer beyond while any point reaches it.
inline constexpr double inside_fraction = 0.125;

/// 1 for each grid cell (index x fastest) that a point reaches: each cell its domain, position ±
/// half_size (its share of the body at generation), overlaps by more than 1e-9 of the cell in
/// every direction (a domain that ends on a node line reaches the cell beyond by round-off only).
/// The domain, not the cell holding the point, for linear shape functions too: a distorted body's
/// cell can lose its points for a step while their domains still cover it; only a hole of a cell
/// (a cell and a half where it lies across the node lines) leaves a cell unreached.
template <int D>
std::vector<std::uint8_t> occupied_cells(const Grid<D>& grid, const MaterialPoints<D>& mp) {
  std::vector<std::uint8_t> occupied(grid.n_cells_total(), 0);
  for (std::size_t p = 0; p < mp.size(); ++p) {
    // Per direction the first cell reached and how many (1 or 2: half_size <= h / 2).
    std::array<int, D> first{}, count{};
    for (int d = 0; d < D; ++d) {
      const double h = grid.spacing[d], x = mp.position[p][d] - grid.origin[d];
      const double lp = mp.half_size[p][d], eps = 1e-9 * h;
      const int last_cell = grid.n_cells[d] - 1;
      const int lo = clamped_floor((x - lp + eps) / h, 0, last_cell);
      const int hi = std::max(lo, clamped_floor((x + lp - eps) / h, 0, last_cell));
      first[d] = lo, count[d] = hi - lo + 1;
    }
    std::array<int, D> k{};
    for (;;) {
      std::int64_t c = 0, stride = 1;
      for (int d = 0; d < D; ++d) c += (first[d] + k[d]) * stride, stride *= grid.n_cells[d];
      occupied[c] = 1;
      int d = 0;
      while (d < D && ++k[d] == count[d]) k[d++] = 0;
      if (d == D) break;
    }
  }
  return occupied;
}

/// 1 at the free-surface nodes: the active nodes of the cells that have corners inside the body
/// and either corners outside it or no point in them (`occupied`, occupied_cells); `active(i)`
/// and `inside(i)` say whether node i is active and inside (inside implies active).
template <int D, class Active, class Inside>
std::vector<std::uint8_t> free_surface_nodes(const Grid<D>& grid,
                                             const std::vector<std::uint8_t>& occupied,
                                             Active&& active, Inside&& inside) {
  std::vector<std::uint8_t> surface(grid.n_nodes(), 0);
  constexpr int corners = 1 << D;
  std::array<std::int64_t, corners> node;
  for (std::int64_t c = 0; c < grid.n_cells_total(); ++c) {
    std::int64_t rest = c, base = 0;
    for (int d = 0; d < D; ++d) {
      base += (rest % grid.n_cells[d]) * grid.stride[d];
      rest /= grid.n_cells[d];
    }
    int n_inside = 0;
    for (int k = 0; k < corners; ++k) {
      node[k] = base;
      for (int d = 0; d < D; ++d)
        if ((k >> d) & 1) node[k] += grid.stride[d];
      n_inside += inside(node[k]);
    }
    if (n_inside == 0 || (n_inside == corners && occupied[c])) continue;
    for (int k = 0; k < corners; ++k)
      if (active(node[k])) surface[node[k]] = 1;
  }
  return surface;
}

/// The same with every active node inside: the outermost layer alone (the main cycle's surface,
/// and where the explicit cycle holds a closed surface's fluids to the solid).
template <int D, class Active>
std::vector<std::uint8_t> free_surface_nodes(const Grid<D>& grid,
                                             const std::vector<std::uint8_t>& occupied,
                                             Active&& active) {
  return free_surface_nodes<D>(grid, occupied, active, active);
}

}  // namespace unsatmpm::numerics

// The free surface of the active region: the active nodes of every grid cell that has both
// active and inactive nodes (the outer layer of the body, found again at every prepare of the
// pressure system, so it follows the body as it deforms). Nodes on the grid's outer faces count
// only through the cells inside the grid: a face where the body touches the grid's boundary is
// not a free surface.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "numerics/grid.hpp"

namespace unsatmpm::numerics {

/// 1 at the free-surface nodes; `active(i)` says whether node i is active.
template <int D, class Active>
std::vector<std::uint8_t> free_surface_nodes(const Grid<D>& grid, Active&& active) {
  std::vector<std::uint8_t> surface(grid.n_nodes(), 0);
  constexpr int corners = 1 << D;
  std::array<std::int64_t, corners> node;
  for (std::int64_t c = 0; c < grid.n_cells_total(); ++c) {
    std::int64_t rest = c, base = 0;
    for (int d = 0; d < D; ++d) {
      base += (rest % grid.n_cells[d]) * grid.stride[d];
      rest /= grid.n_cells[d];
    }
    int n_active = 0;
    for (int k = 0; k < corners; ++k) {
      node[k] = base;
      for (int d = 0; d < D; ++d)
        if ((k >> d) & 1) node[k] += grid.stride[d];
      n_active += active(node[k]);
    }
    if (n_active == 0 || n_active == corners) continue;
    for (int k = 0; k < corners; ++k)
      if (active(node[k])) surface[node[k]] = 1;
  }
  return surface;
}

}  // namespace unsatmpm::numerics

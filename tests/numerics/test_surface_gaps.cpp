// The free surface where a body is torn (numerics/pressure/free_surface.hpp, "The empty cells"):
// cells that no point reaches count as outside the body even when all their corners are active,
// so a point that has left the body has every node on the surface, and an intact body's surface
// is what the corners alone make it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <set>
#include <utility>
#include <vector>

#include "numerics/pressure/free_surface.hpp"
#include "numerics/shape_functions.hpp"

namespace unsatmpm::numerics {
namespace test_surface_gaps {

constexpr double h = 0.1;  // cell size [m]
using Cell = std::pair<int, int>;

/// 2 x 2 GIMP points in each of `cells` (their domains tile the cells) on a 1 m square grid of
/// 0.1 m cells.
struct Body {
  Grid<2> grid{Vec<2>(0.0, 0.0), Vec<2>(h, h), {10, 10}};
  MaterialPoints<2> mp;
  explicit Body(const std::set<Cell>& cells) {
    for (const auto& [i, j] : cells)
      for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b)
          mp.push_back(0, Vec<2>((i + 0.25 + 0.5 * a) * h, (j + 0.25 + 0.5 * b) * h),
                       Vec<2>(h / 4, h / 4), 1.0, h * h / 4);
  }
  /// Active nodes: the points' volume on them above 1e-9 of a point's (as PointQuadrature).
  std::vector<std::uint8_t> active() const {
    std::vector<double> volume(grid.n_nodes(), 0.0);
    PointStencil<2, GimpKernel, false> st;
    for (std::size_t p = 0; p < mp.size(); ++p) {
      st.evaluate(grid, mp.position[p], mp.half_size[p]);
      for (int a = 0; a < st.n; ++a) volume[st.node[a]] += st.w[a] * mp.volume[p];
    }
    std::vector<std::uint8_t> on(grid.n_nodes(), 0);
    for (std::int64_t i = 0; i < grid.n_nodes(); ++i) on[i] = volume[i] > 1e-9 * h * h / 4;
    return on;
  }
  std::vector<std::uint8_t> surface(const std::vector<std::uint8_t>& occupied) const {
    const auto on = active();
    return free_surface_nodes<2>(grid, occupied, [&](std::int64_t i) { return on[i] != 0; });
  }
  std::int64_t node(int i, int j) const { return i + j * grid.stride[1]; }
};

/// The cells of [i0, i1) x [j0, j1).
std::set<Cell> box(int i0, int i1, int j0, int j1) {
  std::set<Cell> cells;
  for (int i = i0; i < i1; ++i)
    for (int j = j0; j < j1; ++j) cells.insert({i, j});
  return cells;
}

// Points whose domains tile their cells reach those cells and no other (their domains end on the
// node lines); a point moved a tenth of a cell reaches the cells its domain overlaps; a cell whose
// points have all moved out of it is still reached while their domains cover part of it.
TEST(SurfaceGaps, TheOccupiedCellsAreThoseThePointsDomainsOverlap) {
  Body body(box(2, 5, 3, 6));
  auto occupied = occupied_cells<2>(body.grid, body.mp);
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j)
      EXPECT_EQ(occupied[i + 10 * j] != 0, i >= 2 && i < 5 && j >= 3 && j < 6) << i << ", " << j;
  body.mp.position[0] += Vec<2>(-0.1 * h, 0.0);  // the point at (2.25, 3.25) h: into cell (1, 3)
  occupied = occupied_cells<2>(body.grid, body.mp);
  EXPECT_EQ(occupied[1 + 10 * 3], 1);
  EXPECT_EQ(std::count(occupied.begin(), occupied.end(), 1), 10);
  // The four points of cell (3, 4) moved 0.8 of a cell along x: both columns now lie in cell
  // (4, 4), their domains reaching back to 3.8 h.
  Body moved(box(2, 5, 3, 6));
  for (std::size_t p = 0; p < moved.mp.size(); ++p)
    if (std::floor(moved.mp.position[p][0] / h) == 3 &&
        std::floor(moved.mp.position[p][1] / h) == 4)
      moved.mp.position[p][0] += 0.8 * h;
  for (const auto& x : moved.mp.position)
    EXPECT_FALSE(std::floor(x[0] / h) == 3 && std::floor(x[1] / h) == 4);
  EXPECT_EQ(occupied_cells<2>(moved.grid, moved.mp)[3 + 10 * 4], 1);
}

// An L-shaped body with a cell filled in its inner corner, and a point thrown off it into the
// cell diagonally beyond that corner, with an empty cell between it and the body on either side
// (the embankment's point 1805 at 17 s, verification/embankment/README.md). The corners of the
// two empty cells are all active, and counted by its corners alone the thrown point's node at the
// body's corner was not on the surface. With the empty cells outside, all four of the point's
// nodes are; the body without the point has the same surface either way.
TEST(SurfaceGaps, APointThrownOffTheBodyHasAllItsNodesOnTheSurface) {
  std::set<Cell> l_shape = box(0, 4, 0, 8);                 // x < 0.4 m up to 0.8 m
  for (const auto& c : box(0, 9, 0, 4)) l_shape.insert(c);  // y < 0.4 m across to 0.9 m
  l_shape.insert({4, 4});                                   // the inner corner's cell
  Body body(l_shape);
  const std::vector<std::uint8_t> all(body.grid.n_cells_total(), 1);
  const auto intact = body.surface(occupied_cells<2>(body.grid, body.mp));
  EXPECT_EQ(intact, body.surface(all));
  EXPECT_TRUE(intact[body.node(5, 5)]);  // the filled corner cell's outer node

  Body torn(l_shape);
  torn.mp.push_back(0, Vec<2>(5.4 * h, 5.6 * h), Vec<2>(h / 4, h / 4), 1.0, h * h / 4);
  const auto occupied = occupied_cells<2>(torn.grid, torn.mp);
  EXPECT_EQ(occupied[4 + 10 * 5], 0);  // the empty cells beside and below the thrown point
  EXPECT_EQ(occupied[5 + 10 * 4], 0);
  const auto active = torn.active();
  for (const auto& [i, j] : {Cell{4, 5}, Cell{5, 5}, Cell{4, 6}, Cell{5, 6}, Cell{6, 4}})
    EXPECT_TRUE(active[torn.node(i, j)]) << i << ", " << j;  // both empty cells' corners
  const auto by_corners = torn.surface(all);
  EXPECT_FALSE(by_corners[torn.node(5, 5)]);
  const auto surface = torn.surface(occupied);
  for (const auto& [i, j] : {Cell{5, 5}, Cell{6, 5}, Cell{5, 6}, Cell{6, 6}})
    EXPECT_TRUE(surface[torn.node(i, j)]) << i << ", " << j;
  // The body's own surface is kept: the nodes on the empty cells' far sides were on it already.
  for (std::int64_t i = 0; i < torn.grid.n_nodes(); ++i)
    if (intact[i]) {
      EXPECT_TRUE(surface[i]) << i;
    }
}

}  // namespace test_surface_gaps
}  // namespace unsatmpm::numerics

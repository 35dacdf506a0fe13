// Active nodes and free surfaces with GIMP (numerics/pressure/quadrature.hpp,
// numerics/pressure/free_surface.hpp): a point whose domain ends on a node line gives the node
// beyond a weight of round-off size, which must not make that node active, or it becomes the main
// cycle's free surface where no point feels it; a body whose face lies just past a node line gives
// the node beyond a small weight, and where the explicit cycle applies a surface pressure it then
// acts at both that node and the one on the line, so that the column takes in through its surface
// what a column whose face is on the line takes in.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "cycles/implicit_solver.hpp"
#include "cycles/setup.hpp"
#include "cycles/three_phase_setup.hpp"
#include "cycles/three_phase_solver.hpp"
#include "input/case_parser.hpp"
#include "numerics/pressure/free_surface.hpp"
#include "numerics/pressure/quadrature.hpp"
#include "tests/cycles/rigid_soil.hpp"

namespace unsatmpm {
namespace test_free_surface_nodes {

/// A 1 m column of soil in a 1.5 m grid of `cells_per_metre` cells per metre, 2 GIMP points per
/// cell.
Case column(int cells_per_metre) {
  return parse_case_text(R"(name: col
dimension: 1
grid: {origin: [0], size: [1.5], cells: [)" +
                             std::to_string(cells_per_metre * 3 / 2) + R"(]}
shape_function: gimp
gravity: [-9.81]
)" + test_soils::rigid_soil_yaml() +
                             R"(bodies:
  - {name: col, material: soil, points_per_cell: 2, box: {min: [0], max: [1]},
     initial_state: {suction: 5000, gas_pressure: 0}}
free_surface: {liquid: {suction: 0}, gas: {pressure: 0}}
solver: {end_time: 20, damping: 0, cycle: implicit}
output: {}
)",
                         "<test>");
}

// On 20 to 160 cells per metre the active nodes are those of the column, x <= 1 m, and its free
// surface is the one node at x = 1 m. (On 80 cells per metre the node at 1.0125 m had a volume of
// round-off size, was taken as active and as the surface, and the column took in nothing.)
TEST(FreeSurfaceNodes, AGimpColumnsSurfaceIsItsTopNodeOnEveryCellSize) {
  for (const int n : {20, 40, 80, 160}) {
    const Case c = column(n);
    const auto grid = make_grid<1>(c);
    const PointSet<1> points = fill_bodies<1>(c, grid);
    const numerics::FluidPoints<1> fluids = initial_fluid_state<1>(c, points, hydraulic_models(c));
    numerics::PointQuadrature<1, numerics::GimpKernel> q(grid.n_nodes());
    q.fill(grid, points.points, fluids, points.ranges, {}, 0.0);
    const auto occupied = numerics::occupied_cells<1>(grid, points.points);
    const auto surface = numerics::free_surface_nodes<1>(
        grid, occupied, [&](std::int64_t i) { return q.active(i); });
    for (std::int64_t i = 0; i < grid.n_nodes(); ++i) {
      const double x = grid.origin[0] + i * grid.spacing[0];
      EXPECT_EQ(q.active(i), x <= 1.0 + 1e-9) << n << " cells per metre, node at x = " << x;
      EXPECT_EQ(surface[i] != 0, std::abs(x - 1.0) < 1e-9)
          << n << " cells per metre, node at x = " << x;
    }
  }
}

/// The column's points moved up by `shift` [m].
PointSet<1> shifted_column(const Case& c, const numerics::Grid<1>& grid, double shift) {
  PointSet<1> points = fill_bodies<1>(c, grid);
  for (auto& x : points.points.position) x[0] += shift;
  return points;
}

// A column whose top lies a tenth of a cell past the node at x = 1 m gives the node beyond a
// hundredth of a full node's volume (active, outside) and the surface where a pressure acts is
// it and the node at 1 m; six tenths past, the node beyond is inside (0.18 of a full node's
// volume) and is that surface alone. The outermost layer is the node beyond either way.
TEST(FreeSurfaceNodes, AFaceJustPastANodeLineMakesBothLayersTheSurface) {
  const Case c = column(40);
  const auto grid = make_grid<1>(c);
  const double h = grid.spacing[0];
  for (const double past : {0.1, 0.6}) {
    const PointSet<1> points = shifted_column(c, grid, past * h);
    const numerics::FluidPoints<1> fluids = initial_fluid_state<1>(c, points, hydraulic_models(c));
    numerics::PointQuadrature<1, numerics::GimpKernel> q(grid.n_nodes());
    q.fill(grid, points.points, fluids, points.ranges, {}, 0.0);
    const auto active = [&](std::int64_t i) { return q.active(i); };
    const auto inside = [&](std::int64_t i) {
      return q.node_volume[i] >= numerics::inside_fraction * h;
    };
    const auto occupied = numerics::occupied_cells<1>(grid, points.points);
    const auto near = numerics::free_surface_nodes<1>(grid, occupied, active, inside);
    const auto outer = numerics::free_surface_nodes<1>(grid, occupied, active);
    const std::int64_t line = 40, beyond = 41;  // the nodes at 1 m and 1 m + h
    EXPECT_TRUE(q.active(beyond)) << past;
    EXPECT_EQ(inside(beyond), past > 0.5) << past;
    for (std::int64_t i = 20; i < grid.n_nodes(); ++i) {  // the upper half (its base moved too)
      EXPECT_EQ(near[i] != 0, i == beyond || (i == line && past < 0.5))
          << "past " << past << ", node " << i;
      EXPECT_EQ(outer[i] != 0, i == beyond) << "past " << past << ", node " << i;
    }
  }
}

/// The liquid the explicit cycle's column takes in through its wetted top by 0.5 s [kg/m^2],
/// its points moved up by `shift`.
double water_taken_in(double shift) {
  Case c = column(40);
  c.solver.cycle = Cycle::explicit_dynamic;
  const auto grid = make_grid<1>(c);
  ThreePhaseSolver<1, numerics::GimpKernel> solver(c, grid, shifted_column(c, grid, shift), 1);
  const double start = solver.balance().liquid_mass;
  for (double t = 0.0; t < 0.5 - 1e-12;) {
    const double dt = std::min(0.5 * solver.critical_time_step(), 0.5 - t);
    solver.step(t, dt);
    t += dt;
  }
  return solver.balance().liquid_mass - start;
}

// In the explicit cycle the same column with its top on the node line and a tenth of a cell past
// it takes in the same water within a tenth (the surface moved by 1/400 of the column; the
// cycles' intake differs by a few percent on these cells, docs/cycles.md). With the surface
// pressure acting on the outermost layer alone, the node on the line, which carries the top
// points, counted as closed.
TEST(FreeSurfaceNodes, AnExplicitColumnWhoseTopLiesJustPastANodeLineTakesInAsMuchWater) {
  const double on_line = water_taken_in(0.0), past = water_taken_in(0.1 * 0.025);
  ASSERT_GT(on_line, 0.0);
  EXPECT_NEAR(past, on_line, 0.1 * on_line);
}

/// The liquid the main cycle's column takes in by `end` [s] [kg/m^2], stretched so that its top
/// lies `past` cells beyond the node line at 1 m and its base stays on the grid's edge, its
/// surface's liquid condition a penalty with factor `penalty` (0: the outermost layer held).
double main_cycle_water(double past, double penalty, double end, int cells_per_metre = 40) {
  Case c = column(cells_per_metre);
  c.solver.implicit.surface_penalty = penalty;
  const auto grid = make_grid<1>(c);
  PointSet<1> points = fill_bodies<1>(c, grid);
  const double stretch = 1.0 + past / cells_per_metre;
  auto& mp = points.points;
  for (std::size_t p = 0; p < mp.size(); ++p)
    mp.position[p] *= stretch, mp.half_size[p] *= stretch, mp.volume[p] *= stretch;
  ImplicitSolver<1, numerics::GimpKernel> solver(c, grid, std::move(points), 1);
  const double start = solver.balance().liquid_mass;
  solver.step(0.0, end);  // a rigid skeleton: one flow integration
  return solver.balance().liquid_mass - start;
}

// In the main cycle, holding the outermost layer starves a column whose top lies just past a node
// line (the node beyond, which barely reaches the points, is held; free_surface.hpp: 0.011 against
// 0.672 kg/m^2 by 0.5 s). The penalty on the face's trace (numerics/pressure/surface_penalty.hpp)
// finds the face where it lies; what is left is the points' quadrature of the cut cell, where a
// GIMP point's averaged gradient straddles the node line: first order in the cell size. Measured by
// 20 s (the front across half the column), on 40 / 80 / 160 cells per metre, the deficit against
// the face on the line: 12.0 / 6.5 / 3.4 % a tenth of a cell past, 2.2 / 1.1 / 0.6 % two tenths,
// -2.8 / 0.2 / 0.1 % at half a cell (where the node beyond holds exactly an eighth of a full
// node's volume, the bound below which it is held), 0.04 % or less at nine tenths (gamma 64; 256
// changed them by 0.3 % at most). Checked: the penalised column on the line within 2 % of the
// held one (the penalty converges to it as 1 / gamma), every offset within 15 % on 40 cells per
// metre, and the worst offset's deficit falling at first order.
TEST(FreeSurfaceNodes, AMainCycleColumnTakesInTheSameWaterAtAnyOffsetWithTheTracePenalty) {
  const double held_on_line = main_cycle_water(0.0, 0.0, 20.0);
  ASSERT_GT(held_on_line, 0.0);
  EXPECT_LT(main_cycle_water(0.1, 0.0, 0.5), 0.1 * main_cycle_water(0.0, 0.0, 0.5));
  const double on_line = main_cycle_water(0.0, 64.0, 20.0);
  EXPECT_NEAR(on_line, held_on_line, 0.02 * held_on_line);
  for (const double past : {0.1, 0.5, 0.9})
    EXPECT_NEAR(main_cycle_water(past, 64.0, 20.0), on_line, 0.15 * on_line) << past;
  const double coarse = 1.0 - main_cycle_water(0.1, 64.0, 20.0) / on_line;
  const double fine =
      1.0 - main_cycle_water(0.1, 64.0, 20.0, 80) / main_cycle_water(0.0, 64.0, 20.0, 80);
  EXPECT_GT(coarse, 0.0);
  EXPECT_LT(fine, 0.6 * coarse);
}

}  // namespace test_free_surface_nodes
}  // namespace unsatmpm

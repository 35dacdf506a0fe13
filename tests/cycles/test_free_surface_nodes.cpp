// The main cycle's active nodes and free surface with GIMP (numerics/pressure/quadrature.hpp):
// a point whose domain ends on a node line gives the node beyond a weight of round-off size,
// which must not make that node active, or it becomes the free surface where no point feels it.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "cycles/setup.hpp"
#include "cycles/three_phase_setup.hpp"
#include "input/case_parser.hpp"
#include "numerics/pressure/free_surface.hpp"
#include "numerics/pressure/quadrature.hpp"

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
phases: solid_liquid_gas
fluids:
  liquid: {density: 1000, bulk_modulus: 2.0e+8, viscosity: 1.0e-3}
  gas: {model: ideal, density: 1.2, viscosity: 1.8e-5}
mass_balance: full
skeleton: rigid
materials:
  - {name: soil, model: linear_elastic, young_modulus: 5.0e+6, poisson_ratio: 0.3,
     solid_density: 2700, porosity: 0.4, intrinsic_permeability: 1.0e-11,
     retention: {model: van_genuchten, p0: 2.0e+4, lambda: 0.4, residual_saturation: 0},
     liquid_relative_permeability: {model: mualem_van_genuchten, lambda: 0.4},
     gas_relative_permeability: {model: constant}}
bodies:
  - {name: col, material: soil, points_per_cell: 2, box: {min: [0], max: [1]},
     initial_state: {suction: 5000, gas_pressure: 0}}
free_surface: {liquid: {suction: 0}, gas: {pressure: 0}}
solver: {end_time: 1, damping: 0, cycle: implicit}
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
    const auto surface =
        numerics::free_surface_nodes<1>(grid, [&](std::int64_t i) { return q.active(i); });
    for (std::int64_t i = 0; i < grid.n_nodes(); ++i) {
      const double x = grid.origin[0] + i * grid.spacing[0];
      EXPECT_EQ(q.active(i), x <= 1.0 + 1e-9) << n << " cells per metre, node at x = " << x;
      EXPECT_EQ(surface[i] != 0, std::abs(x - 1.0) < 1e-9)
          << n << " cells per metre, node at x = " << x;
    }
  }
}

}  // namespace test_free_surface_nodes
}  // namespace unsatmpm

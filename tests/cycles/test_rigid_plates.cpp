// Rigid frictionless plates (numerics/rigid_plates.hpp): the plate's nodes share one normal
// velocity, and the plate passes its load to the body without adding or losing any.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "cycles/explicit_solver.hpp"
#include "cycles/implicit_solver.hpp"
#include "cycles/three_phase_solver.hpp"
#include "input/case_parser.hpp"

namespace unsatmpm {
namespace test_rigid_plates {

constexpr double q = 1.0e4, e_stiff = 2.0e7, e_soft = 1.0e7;

/// Two 1 x 1 m columns side by side, stiff (x < 1) and soft, Poisson's ratio 0 (so that each
/// column's vertical strain is its own stress over E), on a roller base between rollers, under a
/// plate at y = 1 that carries the mean pressure q.
Case two_columns() {
  Case c;
  c.file = "<test>";
  c.name = "plate";
  c.dimension = 2;
  c.shape_function = ShapeFunctionKind::linear;
  c.grid = {{0.0, 0.0}, {2.0, 1.5}, {8, 6}};
  c.gravity = {0.0, 0.0};
  c.materials.push_back({"stiff", 2000.0, physics::LinearElastic::create(e_stiff, 0.0)});
  c.materials.push_back({"soft", 2000.0, physics::LinearElastic::create(e_soft, 0.0)});
  c.bodies.push_back({"stiff", 0, 2, BoxGeometry{{0.0, 0.0}, {1.0, 1.0}}, std::vector<double>{}});
  c.bodies.push_back({"soft", 1, 2, BoxGeometry{{1.0, 0.0}, {2.0, 1.0}}, std::vector<double>{}});
  c.boundaries.push_back({"base", {1, 0.0}, MechanicalCondition::roller});
  c.boundaries.push_back({"left", {0, 0.0}, MechanicalCondition::roller});
  c.boundaries.push_back({"right", {0, 2.0}, MechanicalCondition::roller});
  BoundarySpec plate{"plate", {1, 1.0}, MechanicalCondition::rigid_plate};
  plate.traction = TractionSpec{TimeFunction{{{0.0, q}}}, -1, TimeFunction{{{0.0, 0.0}}},
                                "<test>:1:1: traction"};
  c.boundaries.push_back(plate);
  c.solver.end_time = 1.0;
  c.solver.damping = 0.3;
  return c;
}

/// The smallest and largest normal (y) velocity of the plate's nodes that carry material, from
/// node i's mass `mass(i)` and velocities `velocity` [m/s].
template <class Mass>
std::pair<double, double> plate_velocity_range(const numerics::RigidPlate& plate, Mass&& mass,
                                               const std::vector<numerics::Vec<2>>& velocity) {
  double vmin = 1e30, vmax = -1e30;
  for (const auto i : plate.nodes) {
    if (mass(i) <= 0.0) continue;
    vmin = std::min(vmin, velocity[i][1]);
    vmax = std::max(vmax, velocity[i][1]);
  }
  return {vmin, vmax};
}

/// The plate's nodes that carry material move as one; returns that velocity [m/s].
double expect_plate_moves_as_one(const numerics::NodalState<2>& nodes) {
  const auto [vmin, vmax] = plate_velocity_range(
      nodes.plates.at(0), [&](std::int64_t i) { return nodes.mass(i); }, nodes.velocity);
  EXPECT_EQ(vmin, vmax);
  return vmax;
}

/// Explicit steps at half the critical step from 0 to `end` [s].
template <class Solver>
void run_to(Solver& s, double end) {
  double t = 0.0;
  while (t < end) {
    const double dt = 0.5 * s.critical_time_step();
    s.step(t, dt);
    t += dt;
  }
}

TEST(RigidPlates, PlateSharesItsLoadBetweenUnequalColumnsByStiffness) {
  // Both columns compress by one strain, eps = 2 q / (E_stiff + E_soft): the plate's force 2 q
  // (per metre) is split in proportion to the stiffnesses. Without the plate each would take q
  // (strains q / E, 50 % apart), so the check fails without it; with the plate's nodes damped one
  // by one it failed too (the plate chattered, numerics/rigid_plates.hpp).
  const Case c = two_columns();
  const auto grid = make_grid<2>(c);
  ExplicitSolver<2, numerics::LinearKernel> solver(c, grid, fill_bodies<2>(c, grid), 1);
  run_to(solver, 3.0);
  const double eps = 2.0 * q / (e_stiff + e_soft);
  const auto& mp = solver.points();
  for (std::size_t p = 0; p < mp.size(); ++p) {
    const double y0 = mp.position[p][1] - mp.displacement[p][1];
    EXPECT_NEAR(mp.displacement[p][1], -eps * y0, 2e-3 * eps) << "point " << p;
    const double e = mp.material[p] == 0 ? e_stiff : e_soft;
    EXPECT_NEAR(mp.stress[p][1], -e * eps, 2e-3 * q) << "point " << p;
  }
  // The plate's nodes that carry material move as one.
  ASSERT_EQ(solver.nodes().plates.size(), 1u);
  expect_plate_moves_as_one(solver.nodes());
}

/// The same columns, saturated and drained at the plate's sides' level in a three-phase case:
/// the plate's solid velocity is one at every loaded node in both the explicit and the main cycle,
/// and the pore water carries part of the load at first (it cannot leave in the few steps run).
std::string wet_columns(const std::string& cycle) {
  return R"(name: plate
dimension: 2
grid: {origin: [0, 0], size: [2.0, 1.5], cells: [8, 6]}
shape_function: linear
gravity: [0, 0]
phases: solid_liquid_gas
fluids:
  liquid: {density: 1000, bulk_modulus: 2.0e+8, viscosity: 1.0e-3}
  gas: {model: ideal, density: 1.2, viscosity: 1.8e-5}
mass_balance: full
materials:
  - {name: stiff, model: linear_elastic, young_modulus: 2.0e+7, poisson_ratio: 0, solid_density: 2700,
     porosity: 0.4, intrinsic_permeability: 1.0e-12, retention: {model: linear, a_s: 1.0e-6},
     liquid_relative_permeability: {model: constant},
     gas_relative_permeability: {model: power, exponent: 3}}
  - {name: soft, model: linear_elastic, young_modulus: 1.0e+7, poisson_ratio: 0, solid_density: 2700,
     porosity: 0.4, intrinsic_permeability: 1.0e-12, retention: {model: linear, a_s: 1.0e-6},
     liquid_relative_permeability: {model: constant},
     gas_relative_permeability: {model: power, exponent: 3}}
bodies:
  - {name: stiff, material: stiff, points_per_cell: 2, box: {min: [0, 0], max: [1, 1]},
     initial_state: {liquid_pressure: 0, gas_pressure: 0}}
  - {name: soft, material: soft, points_per_cell: 2, box: {min: [1, 0], max: [2, 1]},
     initial_state: {liquid_pressure: 0, gas_pressure: 0}}
boundaries:
  - {name: base, plane: {axis: y, at: 0}, mechanical: roller}
  - {name: left, plane: {axis: x, at: 0}, mechanical: roller}
  - {name: right, plane: {axis: x, at: 2}, mechanical: roller}
  - {name: plate, plane: {axis: y, at: 1}, mechanical: rigid_plate,
     traction: {normal: {ramp: {from: 0, to: 1.0e+4, start: 0, end: 0.004}}}}
solver: {end_time: 1, damping: 0, cycle: )" +
         cycle + R"(}
output: {}
)";
}

TEST(RigidPlates, PlateMovesAsOneOverSaturatedSoilInBothCycles) {
  for (const std::string cycle : {"explicit", "implicit"}) {
    const Case c = parse_case_text(wet_columns(cycle), "case.yaml");
    const auto grid = make_grid<2>(c);
    double top_min = 1e30, top_max = -1e30, p_max = 0.0;
    const auto look = [&](const auto& mp, const auto& fp) {
      for (std::size_t p = 0; p < mp.size(); ++p) {
        p_max = std::max(p_max, fp.liquid_pressure[p]);
        if (mp.position[p][1] - mp.displacement[p][1] < 0.85) continue;  // the top row
        top_min = std::min(top_min, mp.displacement[p][1]);
        top_max = std::max(top_max, mp.displacement[p][1]);
      }
    };
    if (cycle == "explicit") {
      ThreePhaseSolver<2, numerics::LinearKernel> s(c, grid, fill_bodies<2>(c, grid), 1);
      run_to(s, 0.004);
      const auto& nodes = s.nodes();
      const auto [vmin, vmax] = plate_velocity_range(
          nodes.plates.at(0), [&](std::int64_t i) { return nodes.solid_mass(i); },
          nodes.solid_velocity);
      EXPECT_LT(vmax, 0.0);
      EXPECT_NEAR(vmin, vmax, 1e-12 * std::abs(vmin));
      look(s.points(), s.fluids());
    } else {
      ImplicitSolver<2, numerics::LinearKernel> s(c, grid, fill_bodies<2>(c, grid), 1);
      double t = 0.0;
      while (t < 0.004) {
        const double dt = std::min(s.interval(), 0.004 - t);
        s.step(t, dt);
        t += dt;
      }
      EXPECT_LT(expect_plate_moves_as_one(s.mechanics_nodes()), 0.0);
      look(s.points(), s.fluids());
    }
    // The top row settles as one (a relative spread well below the settlement), and the water
    // carries load: its pressure reaches a sizeable part of q.
    EXPECT_LT(top_max, 0.0) << cycle;
    EXPECT_LT(top_max - top_min, 0.02 * std::abs(top_min)) << cycle;
    EXPECT_GT(p_max, 0.3 * q) << cycle;
  }
}

}  // namespace test_rigid_plates
}  // namespace unsatmpm

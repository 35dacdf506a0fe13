// The explicit three-phase cycle at the body's own surface and at faces that prescribe a fluid's
// pressure: what is counted as inflow is what the points take in, and a free-surface condition
// (`free_surface`) acts through the same boundary term as a face (docs/balance_laws.md, "The
// body's free surface").
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "cycles/three_phase_solver.hpp"
#include "input/case_parser.hpp"
#include "tests/cycles/explicit_run.hpp"
#include "tests/cycles/restore_check.hpp"
#include "tests/cycles/rigid_soil.hpp"

namespace unsatmpm {
namespace test_three_phase_surface {

using Solver = ThreePhaseSolver<2, numerics::GimpKernel>;

Solver make(const Case& c) { return explicit_run::make_solver<2, numerics::GimpKernel>(c); }
using explicit_run::run;

/// A 1 m x 1 m block of soil at 5 kPa suction (van Genuchten, S_l = 0.96) in a 2 m x 1.2 m grid,
/// on a base and against a symmetry plane both open to the gas at P_g = 0; `extra` is appended to
/// the case (YAML: a free_surface map, or nothing) and `gravity` is its gravity.
std::string block_text(const std::string& gravity, const std::string& material,
                       const std::string& extra) {
  return R"(
name: block
dimension: 2
grid: {origin: [0, 0], size: [2, 1.2], cells: [20, 12]}
shape_function: gimp
gravity: )" +
         gravity + R"(
phases: solid_liquid_gas
fluids:
  liquid: {density: 1000, bulk_modulus: 2.0e+8, viscosity: 1.0e-3}
  gas: {model: ideal, density: 1.2, viscosity: 1.8e-5}
mass_balance: full
materials:
  - {name: soil, )" +
         material +
         R"(, poisson_ratio: 0.3,
     solid_density: 2700, porosity: 0.4, intrinsic_permeability: 1.0e-11,
     retention: {model: van_genuchten, p0: 2.0e+4, lambda: 0.4, residual_saturation: 0},
     liquid_relative_permeability: {model: mualem_van_genuchten, lambda: 0.4},
     gas_relative_permeability: {model: constant}}
bodies:
  - {name: block, material: soil, points_per_cell: 2, box: {min: [0, 0], max: [1, 1]},
     initial_state: {suction: 5000, gas_pressure: 0}}
boundaries:
  - {name: base, plane: {axis: y, at: 0}, mechanical: fixed, gas: {pressure: 0}}
  - {name: symmetry, plane: {axis: x, at: 0}, mechanical: roller, gas: {pressure: 0}}
solver: {end_time: 1, damping: 0, cycle: explicit}
output: {times: [1]}
)" + extra;
}
Case block(const std::string& gravity, const std::string& material, const std::string& extra) {
  return parse_case_text(block_text(gravity, material, extra), "<test>");
}

const std::string slumping =
    "model: mohr_coulomb, young_modulus: 5.0e+6, cohesion: 500, "
    "friction_angle: 25";
const std::string elastic = "model: linear_elastic, young_modulus: 5.0e+6";

double gas_mismatch(const numerics::FluidBalance& start, const numerics::FluidBalance& b) {
  return std::abs(b.gas_mass - start.gas_mass - b.gas_inflow) / start.gas_mass;
}

// A block slumping under gravity draws gas in through its base. At the base node of its toe
// the points' outward area has a component along the base (the free face above it), and the gas
// crossing it enters the points too. Counted from the face's own area and normal, that inflow
// was missed: the gas balance drifted by 0.073 of the initial gas in 0.15 s on a finer version
// of this block, 0.27 in 0.3 s on this one (measured; 7.2e-6 now). Counted as the points take it in
// (-A_i . J_i), it closes to the mass balance's time-integration error. Tolerance 1e-3: the issue's
// 1e-2 for gas, tenfold tighter over this short run; the block must have slumped (it is not a test
// of a block at rest).
TEST(ThreePhaseSurface, GasDrawnThroughAFaceIsCountedAsThePointsTakeItIn) {
  const Case c = block("[0, -9.81]", slumping, "");
  Solver s = make(c);
  const numerics::FluidBalance start = s.balance();
  run(s, 0.3);
  const numerics::FluidBalance b = s.balance();
  double top = 0.0;
  for (const auto& x : s.points().position) top = std::max(top, x[0]);
  EXPECT_GT(top, 1.0 + 0.05);  // the toe moved out by half a cell
  EXPECT_GT(std::abs(b.gas_inflow), 0.01 * start.gas_mass);
  EXPECT_LT(gas_mismatch(start, b), 1e-3);
}

// Open to the liquid and the gas at the block's own suction and gas pressure, the free surface
// exerts on the fluids exactly the force the points' pressures do: a weightless block stays at
// rest, and neither fluid enters. Tolerance 1e-9 of each fluid's mass: round-off over 200 steps.
TEST(ThreePhaseSurface, AnOpenFreeSurfaceAtTheBlocksOwnPressuresLeavesItAtRest) {
  const Case c =
      block("[0, 0]", elastic, "free_surface: {liquid: {suction: 5000}, gas: {pressure: 0}}\n");
  Solver s = make(c);
  const numerics::FluidBalance start = s.balance();
  const double dt = 0.5 * s.critical_time_step();
  for (int k = 0; k < 200; ++k) s.step(k * dt, dt);
  const numerics::FluidBalance b = s.balance();
  EXPECT_NEAR(b.liquid_mass, start.liquid_mass, 1e-9 * start.liquid_mass);
  EXPECT_NEAR(b.gas_mass, start.gas_mass, 1e-9 * start.gas_mass);
  for (std::size_t p = 0; p < s.fluids().size(); ++p) {
    ASSERT_NEAR(s.fluids().liquid_pressure[p], -5000.0, 1e-3) << "point " << p;
    ASSERT_NEAR(s.fluids().gas_pressure[p], 0.0, 1e-3) << "point " << p;
  }
}

// A column at rest about a water table whose top lies half a cell past a node line, closed to
// both fluids (no free-surface condition), stays at rest: the node on the line carries most of
// the face's area, and free there the pressures' boundary term drove the top row's water out
// (verification/water_table's column so: its top point 8.1 -> 13.8 kPa of suction by 3 s). The
// column on the line stays within 2e-6 rho_l g H over ten consolidation times (V6); 1e-5 here.
TEST(ThreePhaseSurface, AClosedTopHalfACellPastANodeLineLeavesAColumnAtRest) {
  const Case c = parse_case_text(R"(name: column
dimension: 2
grid: {origin: [0, 0], size: [0.2, 2.2], cells: [2, 22]}
shape_function: linear
gravity: [0, -9.81]
phases: solid_liquid_gas
fluids:
  liquid: {density: 1000, bulk_modulus: 1.0e+8, viscosity: 1.0e-3}
  gas: {model: ideal, density: 1.2, viscosity: 1.8e-5}
mass_balance: full
materials:
  - {name: soil, model: linear_elastic, young_modulus: 1.0e+7, poisson_ratio: 0.3,
     solid_density: 2700, porosity: 0.3, intrinsic_permeability: 1.0e-10,
     retention: {model: van_genuchten, p0: 2.0e+4, lambda: 0.4, residual_saturation: 0.1},
     liquid_relative_permeability: {model: mualem_van_genuchten, lambda: 0.4},
     gas_relative_permeability: {model: power, exponent: 3}}
bodies:
  - {name: column, material: soil, points_per_cell: 2, box: {min: [0, 0], max: [0.2, 2.05]},
     initial_stress: {k0: 0.5},
     initial_state: {water_table: {elevation: 1.2, max_suction: 1.0e+5}, gas_pressure: 0}}
boundaries:
  - {name: base, plane: {axis: y, at: 0}, mechanical: fixed}
  - {name: left, plane: {axis: x, at: 0}, mechanical: roller}
  - {name: right, plane: {axis: x, at: 0.2}, mechanical: roller}
solver: {end_time: 1, damping: 0.05, cycle: explicit}
output: {}
)",
                                 "column.yaml");
  Solver s = make(c);
  const auto start = s.fluids().liquid_pressure;
  run(s, 0.2);
  const double tolerance = 1e-5 * 1000.0 * 9.81 * 2.05;
  for (std::size_t p = 0; p < start.size(); ++p)
    ASSERT_NEAR(s.fluids().liquid_pressure[p], start[p], tolerance) << "point " << p;
}

// Wetted at its free surface (suction 0 there, against 5 kPa inside), a weightless block takes
// water in through it: the liquid mass grows, the points next to the surface wet first, and the
// liquid balance closes with the inflow counted at the open surface nodes. Without the
// condition the surface is closed and nothing enters (the control). Tolerance 1e-3 (issue 14).
TEST(ThreePhaseSurface, AWettedFreeSurfaceLetsWaterInAndCountsIt) {
  const Case open =
      block("[0, 0]", elastic, "free_surface: {liquid: {suction: 0}, gas: {pressure: 0}}\n");
  Solver s = make(open);
  const numerics::FluidBalance start = s.balance();
  run(s, 0.2);
  const numerics::FluidBalance b = s.balance();
  EXPECT_GT(b.liquid_inflow, 1e-4 * start.liquid_mass);
  EXPECT_LT(std::abs(b.liquid_mass - start.liquid_mass - b.liquid_inflow),
            1e-3 * (b.liquid_mass - start.liquid_mass));
  double near_face = -1e9, inside = 1e9;  // suction falls from 5 kPa towards 0 at the face x = 1
  for (std::size_t p = 0; p < s.fluids().size(); ++p) {
    const double x = s.points().position[p][0], y = s.points().position[p][1];
    if (y > 0.3 && y < 0.7 && x > 0.95)
      near_face = std::max(near_face, s.fluids().liquid_pressure[p]);
    if (y > 0.3 && y < 0.7 && x < 0.3) inside = std::min(inside, s.fluids().liquid_pressure[p]);
  }
  EXPECT_GT(near_face, inside + 50.0);

  const Case shut = block("[0, 0]", elastic, "");  // the solver keeps a reference to its case
  Solver closed = make(shut);
  const double before = closed.balance().liquid_mass;
  run(closed, 0.2);
  EXPECT_NEAR(closed.balance().liquid_mass, before, 1e-9 * before);
}

// Rain on the block's free surface (cycles/explicit_rain.hpp), gravity along -y, the skeleton
// rigid: the rain falls on the grid's node columns that hold points, x = 0 (half a strip), 0.1,
// ..., 1.0 (the strip [0.95, 1.05] around the block's side): 1.05 m. `intensity` [mm/h] for
// `end` [s].
struct RainRun {
  numerics::FluidBalance start, end;
  double fallen = 0.0;     // [kg/m]
  std::int64_t held = 0;   // surface nodes held at zero suction at the end
  double top_suction = 0;  // the largest suction of the points within 0.05 m of the top [Pa]
  double above_hydrostatic = -1e300;  // max over points of P_l - rho_w g (1 m - y) [Pa]
};

RainRun rain_on_block(double intensity, double end) {
  const Case c =
      block("[0, -9.81]", elastic,
            "skeleton: rigid\nfree_surface: {liquid: {rainfall: " + std::to_string(intensity) +
                "}, gas: {pressure: 0}}\n");
  Solver s = make(c);
  RainRun r;
  r.start = s.balance();
  run(s, end);
  r.end = s.balance();
  r.fallen = intensity * 1e-3 / 3600.0 * 1000.0 * 1.05 * end;
  r.held = s.rain_held_nodes();
  for (std::size_t p = 0; p < s.fluids().size(); ++p)
    r.above_hydrostatic =
        std::max(r.above_hydrostatic,
                 s.fluids().liquid_pressure[p] - 1000.0 * 9.81 * (1.0 - s.points().position[p][1]));
  for (std::size_t p = 0; p < s.fluids().size(); ++p)
    if (s.points().position[p][1] > 0.95)
      r.top_suction =
          std::max(r.top_suction, s.fluids().gas_pressure[p] - s.fluids().liquid_pressure[p]);
  return r;
}

double liquid_mismatch(const RainRun& r) {
  return std::abs(r.end.liquid_mass - r.start.liquid_mass - r.end.liquid_inflow) /
         (r.end.liquid_mass - r.start.liquid_mass);
}

// 36 mm/h (a tenth of K_s = kappa rho g / mu = 353 mm/h) for 0.5 s on the block at 5 kPa suction:
// no node ponds and every drop enters: the inflow is the rain's rate times the time, to
// round-off, and the liquid gained is that inflow within the explicit update's linearisation
// (1e-3 of the gain, as for the wetted surface above).
TEST(ThreePhaseSurface, LightRainAllEntersTheExplicitCycle) {
  const RainRun r = rain_on_block(36.0, 0.5);
  EXPECT_EQ(r.held, 0);
  EXPECT_NEAR(r.end.liquid_inflow, r.fallen, 1e-9 * r.fallen);
  EXPECT_GT(r.top_suction, 0.0);
  EXPECT_LT(liquid_mismatch(r), 1e-3);
}

// 36,000 mm/h (10 kg/(m^2 s), a hundred times K_s) for 0.5 s: the top layer's air (about
// 0.8 kg/m^2 of water at S_l = 0.96) fills within a tenth of a second, the top ponds (held nodes),
// less enters than falls, and the liquid balance closes with the inflow counted (rain on the flux
// nodes, and what the held nodes take in) as above. Below the surface held at zero pressure no
// point's liquid pressure exceeds the hydrostatic one, rho_w g (1 m - y), by more than 1 % of the
// block's hydrostatic range. (With a step sized by each fluid's own wave, the points beside the
// ponded top swung by +-30 kPa and the mismatch was 3.8e-3: numerics/three_phase_g2p.hpp.)
TEST(ThreePhaseSurface, HeavyRainPondsInTheExplicitCycle) {
  const RainRun r = rain_on_block(36000.0, 0.5);
  EXPECT_GE(r.held, 1);
  EXPECT_LT(r.end.liquid_inflow, 0.5 * r.fallen);
  EXPECT_GT(r.end.liquid_inflow, 0.0);
  EXPECT_LT(liquid_mismatch(r), 1e-3);
  EXPECT_LT(r.above_hydrostatic, 0.01 * 1000.0 * 9.81 * 1.0);
}

// Upward seepage, as the main cycle's test (tests/cycles/test_rainfall.cpp): a rigid 1 m column,
// its base held at the pressure of a water table 0.5 m above its top (rho g 1.5 m), no rain, at
// rest about that table at t = 0 (top point at +4.8 kPa, above the gas pressure). Its top becomes
// a seepage face at once and the column settles to steady upward flow with P_l = 0 at the top,
// the pressure falling linearly from the base: the top point's pressure within 1 % of
// rho g 1.5 m (1 - x), water leaving, and the liquid balance closed as above.
TEST(ThreePhaseSurface, ASeepageFaceLetsWaterOutInTheExplicitCycle) {
  const double rho_w = 1000.0, g = 9.81, base = rho_w * g * 1.5;
  const Case c = parse_case_text(R"(
name: seep
dimension: 1
grid: {origin: [0], size: [1.5], cells: [30]}
shape_function: linear
gravity: [-9.81]
)" + test_soils::rigid_soil_yaml() + R"(bodies:
  - {name: col, material: soil, points_per_cell: 2, box: {min: [0], max: [1]},
     initial_state: {water_table: {elevation: 1.5, max_suction: 1.0e+5}, gas_pressure: 0}}
boundaries:
  - {name: base, plane: {axis: x, at: 0}, liquid: {pressure: )" +
                                     std::to_string(base) + R"(}}
free_surface: {liquid: {rainfall: 0}, gas: {pressure: 0}}
solver: {end_time: 2, damping: 0, cycle: explicit}
output: {}
)",
                                 "<test>");
  const auto grid = make_grid<1>(c);
  ThreePhaseSolver<1, numerics::LinearKernel> s(c, grid, fill_bodies<1>(c, grid), 1);
  const numerics::FluidBalance start = s.balance();
  EXPECT_GT(s.fluids().liquid_pressure.back(), 0.0);
  for (double t = 0.0; t < 2.0;) {
    const double dt = std::min(0.5 * s.critical_time_step(), 2.0 - t);
    s.step(t, dt);
    t += dt;
  }
  const numerics::FluidBalance b = s.balance();
  EXPECT_GE(s.rain_held_nodes(), 1);
  const double x_top = s.points().position.back()[0];
  EXPECT_NEAR(s.fluids().liquid_pressure.back(), base * (1.0 - x_top), 0.01 * base * (1.0 - x_top));
  EXPECT_LT(b.liquid_mass - start.liquid_mass, 0.0);
  EXPECT_LT(std::abs(b.liquid_mass - start.liquid_mass - b.liquid_inflow),
            1e-3 * std::abs(b.liquid_mass - start.liquid_mass));
}

// A checkpoint taken while the storm's top is ponded (after 600 steps, about 0.1 s) restores the
// rain's modes and last inflow: the restored run goes on bit for bit with the first
// (tests/cycles/restore_check.hpp).
TEST(ThreePhaseSurface, ARainRunGoesOnBitForBitFromACheckpoint) {
  const std::string text = block_text(
      "[0, -9.81]", elastic,
      "skeleton: rigid\nfree_surface: {liquid: {rainfall: 36000}, gas: {pressure: 0}}\n");
  restore_check::restore_and_compare<2, Solver>(
      text, 600, 300, [](const Solver& a, const Solver& b) {
        EXPECT_GE(a.rain_held_nodes(), 1);
        EXPECT_EQ(a.rain_held_nodes(), b.rain_held_nodes());
        restore_check::expect_same_points<2>(a.points(), b.points());
        restore_check::expect_same_fluids<2>(a.fluids(), b.fluids());
        EXPECT_EQ(a.balance().liquid_inflow, b.balance().liquid_inflow);
      });
}

}  // namespace test_three_phase_surface
}  // namespace unsatmpm

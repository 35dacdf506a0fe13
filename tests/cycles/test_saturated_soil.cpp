// Saturated and mixed soil at atmospheric gas pressure in both cycles (docs/balance_laws.md,
// "Saturated soil"): where the soil holds no gas phase its gas pressure is held and the gas a
// desaturation needs is supplied and counted, so a saturated column under gravity runs, keeps
// P_g = 0 and closes its gas balance; a column with a water table inside starts and stays at
// rest. Before the change the explicit column stopped at t = 0.037 s with P_l = P_g = -inf.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "cycles/implicit_solver.hpp"
#include "cycles/three_phase_solver.hpp"
#include "input/case_parser.hpp"

namespace unsatmpm {
namespace test_saturated_soil {

constexpr double rho_l = 1000.0, g = 9.81, height = 2.0, table = 1.2;

/// A 2 m column, 0.2 m wide, of an elastic soil with the given retention and initial state. The
/// gas relative permeability vanishes with the gas (k_rg = (1 - S_e)^3): a constant k_rg = 1 lets
/// the last 10^-4 of gas in a nearly saturated node flow as if connected, an extremely stiff flow
/// (docs/balance_laws.md, "Two-way coupling").
std::string column(const std::string& retention, const std::string& initial_state,
                   const std::string& cycle, const std::string& loading) {
  return R"(name: column
dimension: 2
grid: {origin: [0.0, 0.0], size: [0.2, 2.0], cells: [2, 20]}
shape_function: linear
gravity: [0.0, -9.81]
phases: solid_liquid_gas
fluids:
  liquid: {density: 1000, bulk_modulus: 1.0e+8, viscosity: 1.0e-3}
  gas: {model: ideal, density: 1.2, viscosity: 1.8e-5}
mass_balance: full
materials:
  - name: soil
    model: linear_elastic
    young_modulus: 1.0e+7
    poisson_ratio: 0.3
    solid_density: 2700
    porosity: 0.3
    intrinsic_permeability: 1.0e-10
    retention: )" +
         retention + R"(
    liquid_relative_permeability: {model: constant}
    gas_relative_permeability: {model: power, exponent: 3}
bodies:
  - name: column
    material: soil
    points_per_cell: 2
    box: {min: [0.0, 0.0], max: [0.2, 2.0]}
    initial_state: )" +
         initial_state + R"(
boundaries:
  - {name: base, plane: {axis: y, at: 0.0}, mechanical: fixed}
  - {name: left, plane: {axis: x, at: 0.0}, mechanical: roller}
  - {name: right, plane: {axis: x, at: 0.2}, mechanical: roller}
solver:
  end_time: 1.0
  damping: 0.05
  cycle: )" +
         cycle + loading + R"(
output: {}
)";
}

template <class Solver>
void run(Solver& s, double end) {
  double t = 0.0;
  while (t < end) {
    double dt;
    if constexpr (requires { s.critical_time_step(); })
      dt = std::min(0.5 * s.critical_time_step(), end - t);
    else
      dt = std::min(s.interval(), end - t);
    s.step(t, dt);
    t += dt;
  }
}

template <template <int, class> class Solver>
Solver<2, numerics::LinearKernel> make(const Case& c) {
  const auto grid = make_grid<2>(c);
  return Solver<2, numerics::LinearKernel>(c, grid, fill_bodies<2>(c, grid), 1);
}

/// A saturated column, P_l = P_g = 0 everywhere at t = 0, loaded by its weight at once and closed
/// to both fluids. Both cycles load the pore water undrained (the main cycle through its two-way
/// coupling, cycles/undrained.hpp) and the water carries the weight. The explicit cycle keeps it
/// saturated at P_g = 0. In the main cycle the top points' liquid pressure, near zero, dips below
/// the gas pressure in the column's first oscillations and lets in a trace of gas, which the water
/// then compresses to its own pressure (a few hundred Pa there): the column stays saturated to
/// within 1 % (a suction below 10 kPa). Both runs stay finite and count every gram of gas.
TEST(SaturatedSoil, SaturatedColumnUnderGravityRunsInBothCycles) {
  for (const std::string cycle : {"explicit", "implicit"}) {
    const Case c = parse_case_text(
        column("{model: linear, a_s: 1.0e-6}", "{liquid_pressure: 0, gas_pressure: 0}", cycle, ""),
        "case.yaml");
    const auto check = [&](const auto& s) {
      const auto& fp = s.fluids();
      double max_liquid = 0.0, min_saturation = 1.0;
      for (std::size_t p = 0; p < fp.gas_pressure.size(); ++p) {
        ASSERT_TRUE(std::isfinite(fp.liquid_pressure[p] + fp.gas_pressure[p])) << cycle;
        max_liquid = std::max(max_liquid, fp.liquid_pressure[p]);
        min_saturation = std::min(min_saturation, fp.saturation[p]);
        if (cycle == "explicit") {
          EXPECT_EQ(fp.gas_pressure[p], 0.0) << "point " << p;
        }
      }
      // The weight is carried by the water: P_l of the order of rho g H at the base.
      EXPECT_GT(max_liquid, 0.1 * rho_l * g * height) << cycle;
      if (cycle == "explicit") {
        EXPECT_EQ(min_saturation, 1.0);
      } else {
        EXPECT_GT(min_saturation, 0.99);
      }
      const numerics::FluidBalance b = s.balance();
      EXPECT_LT(std::abs(b.gas_mass - b.gas_inflow), 1e-6 * b.gas_capacity) << cycle;
    };
    if (cycle == "explicit") {
      auto s = make<ThreePhaseSolver>(c);
      run(s, 0.1);  // the old code stopped at 0.037 s
      check(s);
    } else {
      auto s = make<ImplicitSolver>(c);
      run(s, 0.1);
      check(s);
    }
  }
}

/// A water table at 1.2 m: saturated below, van Genuchten suction above, all at rest after the
/// gravity loading. 0.1 % of rho g H is the tolerance of docs/balance_laws.md's verification.
/// 0.3 s here (about 3 s of run, 20 s under the sanitizers); V6 (verification/water_table) holds
/// it over its consolidation times.
TEST(SaturatedSoil, WaterTableColumnStartsAndStaysAtRestInTheMainCycle) {
  const Case c = parse_case_text(
      column("{model: van_genuchten, p0: 2.0e+4, lambda: 0.4, residual_saturation: 0.1}",
             "{water_table: {elevation: 1.2, max_suction: 1.0e+5}, gas_pressure: 0}", "implicit",
             "\n  gravity_loading: {damping: 0.5, tolerance: 1.0e-6, max_time: 20}"),
      "case.yaml");
  auto s = make<ImplicitSolver>(c);
  s.load_gravity();
  run(s, 0.3);
  const auto& mp = s.points();
  const auto& fp = s.fluids();
  for (std::size_t p = 0; p < mp.size(); ++p) {
    const double z = mp.position[p][1] - mp.displacement[p][1];
    EXPECT_NEAR(fp.liquid_pressure[p], rho_l * g * (table - z), 1e-3 * rho_l * g * height)
        << "point " << p << " at z = " << z;
    EXPECT_LT(mp.displacement[p].norm(), 0.1 / 1000.0);
  }
}

/// Wetting to saturation: a 1 m column at 20 kPa suction under a 5 kPa pond, its gas escaping at
/// the base. The main cycle fills it (the base saturates), and its liquid balance closes: the
/// pond's jump at t = 0 spans most of the retention curve, and its mass is now taken exactly
/// (numerics::PressureSystem::start); with the storage at the dry state it was off by 1.3 % of
/// the column's water.
TEST(SaturatedSoil, WettingToSaturationClosesTheLiquidBalance) {
  const Case c = parse_case_text(R"(name: wetting
dimension: 1
grid: {origin: [0], size: [1], cells: [20]}
shape_function: linear
gravity: [-9.81]
phases: solid_liquid_gas
fluids:
  liquid: {density: 1000, bulk_modulus: 1.0e+8, viscosity: 1.0e-3}
  gas: {model: ideal, density: 1.2, viscosity: 1.8e-5}
mass_balance: full
skeleton: rigid
materials:
  - {name: soil, model: linear_elastic, young_modulus: 1.0e+7, poisson_ratio: 0.3,
     solid_density: 2700, porosity: 0.3, intrinsic_permeability: 1.0e-11,
     retention: {model: van_genuchten, p0: 1.0e+4, lambda: 0.5, residual_saturation: 0.1},
     liquid_relative_permeability: {model: mualem_van_genuchten, lambda: 0.5},
     gas_relative_permeability: {model: power, exponent: 2}}
bodies:
  - {name: column, material: soil, points_per_cell: 2, box: {min: [0], max: [1]},
     initial_state: {suction: 2.0e+4, gas_pressure: 0}}
boundaries:
  - {name: top, plane: {axis: x, at: 1}, liquid: {pressure: 5000}, gas: {pressure: 0}}
  - {name: bottom, plane: {axis: x, at: 0}, gas: {pressure: 0}}
solver: {end_time: 1000, damping: 0, cycle: implicit}
output: {history_interval: 20}
)",
                                 "case.yaml");
  const auto grid = make_grid<1>(c);
  ImplicitSolver<1, numerics::LinearKernel> s(c, grid, fill_bodies<1>(c, grid), 1);
  const numerics::FluidBalance start = s.balance();
  double t = 0.0;
  while (t < 1000.0) {
    const double dt = std::min(s.interval(), 1000.0 - t);
    s.step(t, dt);
    t += dt;
    const numerics::FluidBalance b = s.balance();
    // Tolerance: CVODE's relative tolerance 1e-6 accumulated over the run, times 100.
    ASSERT_LT(std::abs(b.liquid_mass - start.liquid_mass - b.liquid_inflow),
              1e-4 * start.liquid_mass)
        << "t = " << t;
  }
  const auto& fp = s.fluids();
  EXPECT_EQ(*std::max_element(fp.saturation.begin(), fp.saturation.end()), 1.0);
  EXPECT_GT(s.balance().liquid_mass, 1.8 * start.liquid_mass);  // from S_l = 0.5 to nearly 1
}

/// A column that saturates through and through, with a gas relative permeability that does not
/// vanish with the gas (k_rg = 1, as a user may give): once a node's gas storage is gone its gas
/// pressure is held, but gas still flows through it, and what its balance asks is counted as
/// inflow. Before it was not: after the column saturated, gas kept leaving the top from soil
/// holding none, and the gas balance missed by 0.38 of the initial gas (8.4e-4 now).
TEST(SaturatedSoil, GasThroughNodesThatLostTheirGasIsCounted) {
  const Case c = parse_case_text(R"(name: saturating
dimension: 1
grid: {origin: [0], size: [1], cells: [50]}
shape_function: linear
gravity: [-9.81]
phases: solid_liquid_gas
fluids:
  liquid: {density: 1000, bulk_modulus: 2.0e+9, viscosity: 1.0e-3}
  gas: {model: ideal, density: 1.2, viscosity: 1.8e-5}
mass_balance: full
skeleton: rigid
materials:
  - {name: soil, model: linear_elastic, young_modulus: 1.0e+7, poisson_ratio: 0.3,
     solid_density: 2700, porosity: 0.4, intrinsic_permeability: 1.0e-11,
     retention: {model: van_genuchten, p0: 2.0e+4, lambda: 0.4, residual_saturation: 0,
                 max_saturation: 1},
     liquid_relative_permeability: {model: mualem_van_genuchten, lambda: 0.4},
     gas_relative_permeability: {model: constant}}
bodies:
  - {name: column, material: soil, points_per_cell: 2, box: {min: [0], max: [1]},
     initial_state: {suction: 2.0e+4, gas_pressure: 0}}
boundaries:
  - {name: top, plane: {axis: x, at: 1}, liquid: {suction: 0}, gas: {pressure: 0}}
solver: {end_time: 700, damping: 0, cycle: implicit}
output: {history_interval: 10}
)",
                                 "case.yaml");
  const auto grid = make_grid<1>(c);
  ImplicitSolver<1, numerics::LinearKernel> s(c, grid, fill_bodies<1>(c, grid), 1);
  const numerics::FluidBalance start = s.balance();
  double t = 0.0;
  while (t < 700.0) {
    const double dt = std::min(s.interval(), 700.0 - t);
    s.step(t, dt);
    t += dt;
  }
  const numerics::FluidBalance b = s.balance();
  EXPECT_EQ(b.gas_mass, 0.0);  // saturated through
  // Tolerance: the issue's 1e-2 for gas, on the initial gas mass.
  EXPECT_LT(std::abs(b.gas_mass - start.gas_mass - b.gas_inflow), 1e-2 * start.gas_mass);
  EXPECT_LT(std::abs(b.liquid_mass - start.liquid_mass - b.liquid_inflow),
            1e-3 * start.liquid_mass);
}

}  // namespace test_saturated_soil
}  // namespace unsatmpm

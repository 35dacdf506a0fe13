// Gravity loading before t = 0 (solver.gravity_loading): a laterally confined elastic column
// loaded from zero stress reaches sigma_yy = -(weight above) and the K0 ratio nu / (1 - nu); the
// same column as a three-phase mixture at a uniform suction carries the fluids' weight too (net
// stress = total stress + P_g with P_g = 0); displacements, velocities and plastic strains are
// reset; a loading that cannot balance within max_time throws BlowUpError naming the ratio.
// Tolerances, set before the runs: the force ratio reached is at most the tolerance asked; the
// cell-row mean of sigma_yy within 1 % of rho g H (the damped dynamics stop at a force ratio of
// 1e-4, and with linear shape functions each point carries its cell's mid-depth stress, so single
// points are off by up to rho g h / 2: 1/16 of rho g H here, which the row mean removes). The
// columns are stiff (settlement 1.3e-4 m): the points' shift within their cells moves the MPM
// equilibrium by ~ rho g u, which at E = 2 MPa (u = 1.3 cm) was 1 % of rho g H by itself.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "cycles/explicit_solver.hpp"
#include "cycles/implicit_solver.hpp"
#include "cycles/setup.hpp"
#include "input/case_parser.hpp"

namespace unsatmpm {
namespace test_gravity_loading {

constexpr double height = 2.0, cell = 0.25, g = 9.81, poisson = 0.3;

const std::string dry_column = R"(name: column
dimension: 2
grid: {origin: [0, 0], size: [0.5, 2.25], cells: [2, 9]}
shape_function: linear
gravity: [0, -9.81]
materials:
  - {name: m, density: 1800, model: linear_elastic, young_modulus: 2.0e8, poisson_ratio: 0.3}
bodies: [{name: b, material: m, points_per_cell: 2, box: {min: [0, 0], max: [0.5, 2]}}]
boundaries:
  - {name: base, plane: {axis: y, at: 0}, mechanical: fixed}
  - {name: left, plane: {axis: x, at: 0}, mechanical: roller}
  - {name: right, plane: {axis: x, at: 0.5}, mechanical: roller}
solver:
  end_time: 1
  damping: 0
  gravity_loading: {damping: 0.7, tolerance: 1.0e-4, max_time: 20}
output: {}
)";

const std::string wet_column = R"(name: column3
dimension: 2
grid: {origin: [0, 0], size: [0.5, 2.25], cells: [2, 9]}
shape_function: linear
gravity: [0, -9.81]
phases: solid_liquid_gas
fluids:
  liquid: {density: 1000, bulk_modulus: 1.0e+8, viscosity: 1.0e-3}
  gas: {model: bulk_modulus, density: 1, bulk_modulus: 1.0e+4, viscosity: 1.8e-5}
mass_balance: full
materials:
  - {name: m, model: mohr_coulomb, young_modulus: 2.0e8, poisson_ratio: 0.3, cohesion: 1000,
     friction_angle: 20, suction_strength: {cohesion_increase: 1.5e4, cohesion_rate: 0.7,
     friction_increase: 0.1}, solid_density: 2700, porosity: 0.35,
     intrinsic_permeability: 1.0e-12,
     retention: {model: van_genuchten, p0: 4.0e5, lambda: 0.5, residual_saturation: 0,
                 max_saturation: 0.95},
     liquid_relative_permeability: {model: power, exponent: 3},
     gas_relative_permeability: {model: constant}}
bodies:
  - {name: b, material: m, points_per_cell: 2, box: {min: [0, 0], max: [0.5, 2]},
     initial_state: {suction: 8.0e5, gas_pressure: 0}}
boundaries:
  - {name: base, plane: {axis: y, at: 0}, mechanical: fixed, gas: {pressure: 0}}
  - {name: left, plane: {axis: x, at: 0}, mechanical: roller}
  - {name: right, plane: {axis: x, at: 0.5}, mechanical: roller}
solver:
  end_time: 1
  damping: 0
  cycle: implicit
  gravity_loading: {damping: 0.7, tolerance: 1.0e-4, max_time: 20}
output: {}
)";

/// Largest |mean sigma_yy of a cell row - reference| / (rho g H), and the largest error of the K0
/// ratio below the top cell. The reference of a row is the weight above the cell's mid-depth per
/// unit width, -g (mass of the rows above + half the row's own mass) / width, exact for the
/// linear stress of a cell whatever the settlement (mass conservation); `rho` [kg/m^3] only
/// scales the error.
std::pair<double, double> stress_errors(const numerics::MaterialPoints<2>& mp,
                                        const std::vector<double>& mass, double rho, double width) {
  std::map<int, double> row_mass, row_stress;
  std::map<int, int> row_count;
  double k0_error = 0.0;
  for (std::size_t p = 0; p < mp.size(); ++p) {
    const int row = static_cast<int>(mp.position[p][1] / cell);
    row_mass[row] += mass[p], row_stress[row] += mp.stress[p][1], row_count[row] += 1;
    if (height - mp.position[p][1] > cell)
      k0_error =
          std::max(k0_error, std::abs(mp.stress[p][0] / mp.stress[p][1] - poisson / (1 - poisson)));
  }
  double worst = 0.0, above = 0.0;
  for (auto it = row_mass.rbegin(); it != row_mass.rend(); ++it) {  // from the top down
    const int row = it->first;
    const double reference = -g * (above + 0.5 * it->second) / width;
    worst = std::max(worst, std::abs(row_stress[row] / row_count[row] - reference));
    above += it->second;
  }
  return {worst / (rho * g * height), k0_error};
}

TEST(GravityLoading, DryColumnReachesItsWeightAndResetsTheMotion) {
  const Case c = parse_case_text(dry_column, "column.yaml");
  const auto grid = make_grid<2>(c);
  ExplicitSolver<2, numerics::LinearKernel> solver(c, grid, fill_bodies<2>(c, grid), 1);
  const GravityLoadingReport r = solver.load_gravity();
  EXPECT_LE(r.force_ratio, 1e-4);
  EXPECT_GT(r.steps, 10);
  EXPECT_GT(r.max_displacement, 1e-5);  // it did settle (rho g H^2 / 2M = 1.3e-4 m)
  const auto [error, k0] = stress_errors(solver.points(), solver.points().mass, 1800.0, 0.5);
  EXPECT_LT(error, 0.01);
  EXPECT_LT(k0, 0.02);
  for (std::size_t p = 0; p < solver.points().size(); ++p) {
    EXPECT_EQ(solver.points().displacement[p].norm(), 0.0);
    EXPECT_EQ(solver.points().velocity[p].norm(), 0.0);
  }
}

TEST(GravityLoading, UnsaturatedColumnCarriesTheFluidsWeightInNetStress) {
  const Case c = parse_case_text(wet_column, "column3.yaml");
  const auto grid = make_grid<2>(c);
  ImplicitSolver<2, numerics::LinearKernel> solver(c, grid, fill_bodies<2>(c, grid), 1);
  const GravityLoadingReport r = solver.load_gravity();
  EXPECT_LE(r.force_ratio, 1e-4);
  // Weight density of the mixture: (1 - n) rho_s + n S_l rho_l + n S_g rho_g.
  const auto& fp = solver.fluids();
  const double s_l = fp.saturation[0];
  const double rho = 0.65 * 2700.0 + 0.35 * (s_l * 1000.0 + (1.0 - s_l) * fp.gas_density[0]);
  EXPECT_NEAR(s_l, 0.95 / std::sqrt(5.0), 1e-9);  // van Genuchten at s = 2 P0
  std::vector<double> mass = solver.points().mass;
  for (std::size_t p = 0; p < mass.size(); ++p)
    mass[p] +=
        fp.porosity[p] * solver.points().volume[p] *
        (fp.saturation[p] * fp.liquid_density[p] + (1.0 - fp.saturation[p]) * fp.gas_density[p]);
  const auto [error, k0] = stress_errors(solver.points(), mass, rho, 0.5);
  EXPECT_LT(error, 0.01);
  EXPECT_LT(k0, 0.02);  // elastic: the strength at 800 kPa (c = 15.9 kPa) holds this column
  EXPECT_EQ(r.max_plastic_strain, 0.0);
  // The porosity follows the volume change: the solid volume (1 - n) V is kept.
  const double v0 = cell * cell / 4.0;
  for (std::size_t p = 0; p < fp.size(); ++p)
    EXPECT_NEAR((1.0 - fp.porosity[p]) * solver.points().volume[p], 0.65 * v0, 1e-12 * v0);
}

TEST(GravityLoading, NotBalancedWithinMaxTimeIsAnError) {
  std::string text = dry_column;
  text.replace(text.find("max_time: 20"), 12, "max_time: 0.01");
  const Case c = parse_case_text(text, "column.yaml");
  const auto grid = make_grid<2>(c);
  ExplicitSolver<2, numerics::LinearKernel> solver(c, grid, fill_bodies<2>(c, grid), 1);
  try {
    solver.load_gravity();
    FAIL() << "no error";
  } catch (const BlowUpError& e) {
    EXPECT_NE(std::string(e.what()).find("did not balance within max_time = 0.01 s"),
              std::string::npos)
        << e.what();
  }
}

/// Pore pressures held above what the soil can hold: a water table 2 m above the column's top
/// leaves +20 kPa of liquid pressure at its top under no total stress, beyond the tension cut-off
/// (c / tan(phi) = 2.7 kPa). No equilibrium exists; the top points expand, their held pressure
/// pushing harder as their volume grows, and the loading's step shrank with their speed: a 2D
/// slope's toe so took 248,034 steps to leave the grid, velocities of 1e149 m/s in the state it
/// kept. It must stop at the collapse of its step, say why it could not balance, and keep a state
/// of finite, bounded speeds.
TEST(GravityLoading, PorePressuresBeyondTheSoilsStrengthStopAtTheStepsCollapse) {
  std::string text = wet_column;
  const auto edit = [&](const std::string& from, const std::string& to) {
    ASSERT_NE(text.find(from), std::string::npos) << from;
    text.replace(text.find(from), from.size(), to);
  };
  edit("size: [0.5, 2.25], cells: [2, 9]", "size: [0.5, 6.25], cells: [2, 25]");
  edit("initial_state: {suction: 8.0e5, gas_pressure: 0}",
       "initial_state: {water_table: {elevation: 4, max_suction: 1.0e5}, gas_pressure: 0}");
  const Case c = parse_case_text(text, "column3.yaml");
  const auto grid = make_grid<2>(c);
  ImplicitSolver<2, numerics::LinearKernel> solver(c, grid, fill_bodies<2>(c, grid), 1);
  const auto& mp = solver.points();
  double initial_speed = 0.0;  // the solid's P wave (no point moves yet)
  for (std::size_t p = 0; p < mp.size(); ++p) {
    const double modulus = 2.0e8 * 0.7 / (1.3 * 0.4);  // E (1 - nu) / ((1 + nu)(1 - 2 nu))
    initial_speed = std::max(initial_speed, std::sqrt(modulus * mp.volume[p] / mp.mass[p]));
  }
  try {
    solver.load_gravity();
    FAIL() << "no error";
  } catch (const BlowUpError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("gravity loading (before t = 0) failed"), std::string::npos) << what;
    EXPECT_NE(what.find("the explicit step collapsed"), std::string::npos) << what;
    EXPECT_NE(what.find("the pore pressures are held during the loading"), std::string::npos)
        << what;
  }
  for (std::size_t p = 0; p < mp.size(); ++p) {
    ASSERT_TRUE(std::isfinite(mp.volume[p])) << p;
    ASSERT_LT(mp.velocity[p].norm(), wave_speed_blowup_factor * initial_speed) << p;
  }
}

}  // namespace test_gravity_loading
}  // namespace unsatmpm

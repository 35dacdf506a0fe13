// Saturated soil with water's own stiffness (K_l = 2.2 GPa) at the saturation kink, in the
// explicit cycle's nodal pressure update (docs/balance_laws.md, "Saturated soil at the saturation
// kink"): a closed 1 m column at P_l = P_g = 0 with the linear retention law, whose storage just
// on the tension side of s = 0 is some 2,000 times its saturated one. Before points free of gas
// took their own volume change themselves, the column at rest failed at 56 ms and the one loaded
// by its weight at 9 ms.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "cycles/three_phase_solver.hpp"
#include "input/case_parser.hpp"

namespace unsatmpm {
namespace test_saturation_kink {

constexpr double young = 1.0e7, poisson = 0.3, porosity = 0.3, k_l = 2.2e9, height = 1.0;
constexpr double rho_s = 2700.0, rho_l = 1000.0, g = 9.81;

/// The column, 50 cells of 0.025 m with 2 points each, base fixed, no fluid boundary; the
/// body's `initial_stress` entry (empty: none, the weight then comes on at once).
Case column(const std::string& initial_stress) {
  return parse_case_text(R"(name: kink
dimension: 1
grid: {origin: [0], size: [1.25], cells: [50]}
shape_function: linear
gravity: [-9.81]
phases: solid_liquid_gas
fluids:
  liquid: {density: 1000, bulk_modulus: 2.2e+9, viscosity: 1.0e-3}
  gas: {model: ideal, density: 1.2, viscosity: 1.8e-5}
mass_balance: full
pressure_update: nodal
materials:
  - {name: soil, model: linear_elastic, young_modulus: 1.0e+7, poisson_ratio: 0.3,
     solid_density: 2700, porosity: 0.3, intrinsic_permeability: 1.0e-14,
     retention: {model: linear, a_s: 1.0e-6}, liquid_relative_permeability: {model: constant},
     gas_relative_permeability: {model: power, exponent: 3}}
bodies:
  - {name: block, material: soil, points_per_cell: 2, box: {min: [0], max: [1]},
     initial_state: {suction: 0, gas_pressure: 0})" +
                             initial_stress + R"(}
boundaries:
  - {name: base, plane: {axis: x, at: 0}, mechanical: fixed}
solver: {end_time: 0.2, damping: 0, cycle: explicit}
output: {}
)",
                         "kink.yaml");
}

/// Runs to 0.2 s at the cycle's stable step; returns the largest kinetic energy of the solid,
/// sum 1/2 m v^2 [J/m^2], with every pressure finite.
double largest_kinetic_energy(const Case& c) {
  const auto grid = make_grid<1>(c);
  ThreePhaseSolver<1, numerics::LinearKernel> s(c, grid, fill_bodies<1>(c, grid), 1);
  double t = 0.0, largest = 0.0;
  while (t < 0.2) {
    const double dt = std::min(0.5 * s.critical_time_step(), 0.2 - t);
    s.step(t, dt);
    t += dt;
    const auto& mp = s.points();
    double kinetic = 0.0;
    for (std::size_t p = 0; p < mp.size(); ++p)
      kinetic += 0.5 * mp.mass[p] * mp.velocity[p].squaredNorm();
    largest = std::max(largest, kinetic);
  }
  const auto& fp = s.fluids();
  for (std::size_t p = 0; p < fp.size(); ++p)
    EXPECT_TRUE(std::isfinite(fp.liquid_pressure[p] + fp.gas_pressure[p])) << "point " << p;
  const numerics::FluidBalance b = s.balance();
  EXPECT_LT(std::abs(b.gas_mass - b.gas_inflow), 1e-6 * b.gas_capacity);
  return largest;
}

/// In equilibrium with its weight (k0 stresses), the column stays at rest: its water seeps down
/// at kappa rho_l g / mu_l = 1e-7 m/s, a kinetic energy of order 1e-12 J/m^2; 1e-9 is a thousand
/// times that.
TEST(SaturationKink, ColumnAtRestStaysAtRestWithWatersStiffness) {
  EXPECT_LT(largest_kinetic_energy(column(", initial_stress: {k0: 0.5}")), 1e-9);
}

/// Its weight put on at once: with its masses kept, the column is a linear elastic system under a
/// constant load F, so its kinetic energy F.u - u.K.u / 2 never exceeds the static strain energy
/// F.K^-1.F / 2 = gamma^2 H^3 / (6 M_u), with the undrained constrained modulus
/// M_u = M + K_l / n and gamma the saturated unit weight (0.0105 J/m^2 here; the explicit
/// pointwise update reaches 0.0089).
TEST(SaturationKink, ColumnLoadedByItsWeightStaysWithinItsStrainEnergy) {
  const double m = young * (1.0 - poisson) / ((1.0 + poisson) * (1.0 - 2.0 * poisson));
  const double m_u = m + k_l / porosity;
  const double gamma = ((1.0 - porosity) * rho_s + porosity * rho_l) * g;
  const double strain_energy = gamma * gamma * std::pow(height, 3) / (6.0 * m_u);
  EXPECT_LT(largest_kinetic_energy(column("")), strain_energy);
}

/// Terzaghi's loaded column (verification/terzaghi_load with water's stiffness and a 10 ms ramp):
/// 20 cells of 0.05 m, drained at its top, loaded there by q0 = 10 kPa. The top point desaturates
/// a little where the drained node pulls its water; the points below it, free of gas, took that
/// node's gas increments into a gas pressure that they do not hold, which fell to vacuum: the run
/// failed at 5.2 ms (at 6.8 ms with kappa = 3e-10 m^2 and the verification case's 0.2 GPa). Their
/// gas pressure is held now. Checked at t = 0.05 s: every point free of gas keeps P_g = 0, and the
/// base's liquid pressure is Terzaghi's, B q0 sum_m 2 / M exp(-M^2 T) with M = (2m + 1) pi / 2
/// at the base, T = c_v (t - t_ramp / 2) / H^2 (the ramp as a step at its middle), within the
/// 0.02 q0 verification/terzaghi_load allows its profiles.
TEST(SaturationKink, LoadedColumnDrainedAtItsTopConsolidatesWithWatersStiffness) {
  const Case c = parse_case_text(R"(name: drained
dimension: 1
grid: {origin: [0], size: [1], cells: [20]}
shape_function: linear
gravity: [0]
phases: solid_liquid_gas
fluids:
  liquid: {density: 1000, bulk_modulus: 2.2e+9, viscosity: 1.0e-3}
  gas: {model: ideal, density: 1.2, viscosity: 1.8e-5}
mass_balance: full
pressure_update: nodal
materials:
  - {name: soil, model: linear_elastic, young_modulus: 1.0e+7, poisson_ratio: 0.3,
     solid_density: 2700, porosity: 0.4, intrinsic_permeability: 1.0e-10,
     retention: {model: linear, a_s: 1.0e-6}, liquid_relative_permeability: {model: constant},
     gas_relative_permeability: {model: power, exponent: 3}}
bodies:
  - {name: column, material: soil, points_per_cell: 2, box: {min: [0], max: [1]},
     initial_state: {liquid_pressure: 0, gas_pressure: 0}}
boundaries:
  - {name: base, plane: {axis: x, at: 0}, mechanical: fixed}
  - {name: top, plane: {axis: x, at: 1}, liquid: {pressure: 0}, gas: {pressure: 0},
     traction: {normal: {ramp: {from: 0, to: 1.0e+4, start: 0, end: 0.01}}}}
solver: {end_time: 0.05, damping: 0, cycle: explicit}
output: {}
)",
                                 "drained.yaml");
  const auto grid = make_grid<1>(c);
  ThreePhaseSolver<1, numerics::LinearKernel> s(c, grid, fill_bodies<1>(c, grid), 1);
  constexpr double end = 0.05, ramp = 0.01, q0 = 1.0e4, n = 0.4, kappa = 1.0e-10, mu = 1.0e-3;
  double t = 0.0;
  while (t < end) {
    const double dt = std::min(0.5 * s.critical_time_step(), end - t);
    s.step(t, dt);
    t += dt;
  }
  const auto& fp = s.fluids();
  int free_of_gas = 0;
  for (std::size_t p = 0; p < fp.size(); ++p) {
    if (1.0 - fp.saturation[p] > physics::gas_free_saturation) continue;
    ++free_of_gas;
    EXPECT_EQ(fp.gas_pressure[p], 0.0) << "point " << p;
  }
  EXPECT_GE(free_of_gas, 30);  // all but the top few points stay saturated
  const double m = young * (1.0 - poisson) / ((1.0 + poisson) * (1.0 - 2.0 * poisson));
  const double c_v = kappa / mu / (1.0 / m + n / k_l), skempton = 1.0 / (1.0 + n * m / k_l);
  const double time_factor = c_v * (end - 0.5 * ramp) / (height * height);
  double u = 0.0;
  for (int k = 0; k < 50; ++k) {
    const double big_m = (2 * k + 1) * std::numbers::pi / 2.0;
    u += (k % 2 == 0 ? 2.0 : -2.0) / big_m * std::exp(-big_m * big_m * time_factor);
  }
  EXPECT_NEAR(fp.liquid_pressure[0], skempton * q0 * u, 0.02 * q0);
}

}  // namespace test_saturation_kink
}  // namespace unsatmpm

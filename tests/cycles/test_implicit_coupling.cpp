// The implicit cycle's coupling of explicit mechanics and the implicit flow (fixed-stress split)
// on Terzaghi's consolidation: a saturated column switched on under its own weight, drained at
// the top, impervious and fixed at the bottom. At t = 0 the total stress is carried by the pore
// water (P_l = rho_sat g depth, net stress 0, in equilibrium); the excess over hydrostatic,
// u0 = gamma' depth with gamma' = (rho_sat - rho_w) g, then dissipates as
//   u = sum_m 2 gamma' H (-1)^m / M_m^2 sin(M_m z/H) exp(-M_m^2 T),  M_m = pi (2m + 1) / 2,
//   T = c_v t / H^2,  c_v = (kappa / mu) / (1/M + n/K_l),  M the constrained modulus.
// The surface settles by (gamma' H^2/2 - sum_m 2 gamma' H^2 (-1)^m / M_m^3 exp(-M_m^2 T)) / M.
// Tolerances, set before the runs: RMS error <= 2 % and max error <= 5 % of gamma' H at
// T = 0.05, 0.2 and 0.5 (20 cells: the discretisation alone errs ~0.5 %; the rest is left for the
// splitting and for the dynamic mechanics, damped at alpha = 0.1); the top point's settlement
// within 5 % of the final settlement gamma' H^2 / (2 M) (set after the pressures were seen, before
// the settlement was); the liquid-mass mismatch below 1e-3. The liquid is ten times softer than
// water (K_l = 0.2 GPa): the mechanics' step shrinks as 1 / sqrt(K_u), and water's 2 GPa would
// cost minutes under the sanitizers; V7 runs water under `slow`.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "cycles/implicit_solver.hpp"
#include "input/case_parser.hpp"
#include "tests/cycles/restore_check.hpp"

namespace unsatmpm {
namespace test_implicit_coupling {

constexpr double height = 1.0, porosity = 0.3, rho_s = 2700.0, rho_w = 1000.0, g = 9.81;
constexpr double young = 1e7, poisson = 0.3, k_l = 2e8, mu = 1e-3, kappa = 3.72e-12;

double constrained_modulus() {
  return young * (1.0 - poisson) / ((1.0 + poisson) * (1.0 - 2.0 * poisson));
}
double consolidation_coefficient() {
  return kappa / mu / (1.0 / constrained_modulus() + porosity / k_l);
}
double gamma_buoyant() { return ((1.0 - porosity) * rho_s + porosity * rho_w - rho_w) * g; }

double settlement_series(double t_factor) {
  double s = gamma_buoyant() * height * height / 2.0;
  for (int m = 0; m < 200; ++m) {
    const double mm = std::numbers::pi * (2 * m + 1) / 2.0;
    s -= 2.0 * gamma_buoyant() * height * height * (m % 2 ? -1.0 : 1.0) / (mm * mm * mm) *
         std::exp(-mm * mm * t_factor);
  }
  return s / constrained_modulus();
}

double excess_series(double depth, double t_factor) {
  double u = 0.0;
  for (int m = 0; m < 200; ++m) {
    const double mm = std::numbers::pi * (2 * m + 1) / 2.0;
    u += 2.0 * gamma_buoyant() * height * (m % 2 ? -1.0 : 1.0) / (mm * mm) *
         std::sin(mm * depth / height) * std::exp(-mm * mm * t_factor);
  }
  return u;
}

Case consolidation_column() {
  Case c;
  c.file = "<test>";
  c.name = "terzaghi";
  c.dimension = 1;
  c.shape_function = ShapeFunctionKind::linear;
  c.grid = {{0.0}, {height}, {20}};
  c.gravity = {-g};
  c.phases = Phases::solid_liquid_gas;
  c.fluids = FluidsSpec{physics::CompressibleFluid::create(rho_w, 0.0, k_l), mu,
                        physics::IdealGas::create(1.2), 1.8e-5};
  c.mass_balance = physics::MassBalance::full;
  c.skeleton = physics::Skeleton::deformable;
  HydraulicSpec h{rho_s,
                  porosity,
                  kappa,
                  physics::LinearRetention::create(1e-6, 0.0),
                  physics::ConstantRelPerm{},
                  physics::ConstantRelPerm{}};
  c.materials.push_back(
      {"soil", (1 - porosity) * rho_s, physics::LinearElastic::create(young, poisson), h});
  c.bodies.push_back({"column", 0, 2, BoxGeometry{{0.0}, {height}}, std::vector<double>{0.0},
                      InitialPressures{0.0, 0.0}});
  BoundarySpec base{"base", {0, 0.0}, MechanicalCondition::fixed, std::nullopt, std::nullopt};
  BoundarySpec top{"top", {0, height}, std::nullopt, std::nullopt, std::nullopt};
  top.liquid = LiquidCondition{LiquidCondition::Kind::pressure, TimeFunction{{{0.0, 0.0}}}};
  top.gas_pressure = TimeFunction{{{0.0, 0.0}}};
  c.boundaries = {base, top};
  c.solver.damping = 0.1;
  c.solver.flip_fraction = 1.0;
  c.solver.cycle = Cycle::implicit_pressure;
  c.solver.end_time = 0.5 * height * height / consolidation_coefficient();
  return c;
}

TEST(ImplicitCoupling, TerzaghiConsolidationUnderSelfWeight) {
  const Case c = consolidation_column();
  const auto grid = make_grid<1>(c);
  ImplicitSolver<1, numerics::LinearKernel> solver(c, grid, fill_bodies<1>(c, grid), 1);
  auto& fp = solver.fluids();
  const auto& mp = solver.points();
  const double rho_sat = (1.0 - porosity) * rho_s + porosity * rho_w;
  for (std::size_t p = 0; p < fp.size(); ++p) {
    fp.liquid_pressure[p] = rho_sat * g * (height - mp.position[p][0]);
    fp.liquid_density[p] = c.fluids->liquid.density(fp.liquid_pressure[p]);
  }
  const double scale = gamma_buoyant() * height;
  const double final_settlement = settlement_series(1e9);
  const numerics::FluidBalance start = solver.balance();
  double t = 0.0;
  for (const double t_factor : {0.05, 0.2, 0.5}) {
    const double t_end = t_factor * height * height / consolidation_coefficient();
    while (t < t_end - 1e-12) {
      const double dt = std::min(solver.interval(), t_end - t);
      solver.step(t, dt);
      t += dt;
    }
    double sum = 0.0, worst = 0.0;
    for (std::size_t p = 0; p < fp.size(); ++p) {
      const double depth = height - mp.position[p][0];
      const double u = fp.liquid_pressure[p] - rho_w * g * depth;
      const double e = (u - excess_series(depth, t_factor)) / scale;
      sum += e * e;
      worst = std::max(worst, std::abs(e));
    }
    const double rms = std::sqrt(sum / fp.size());
    EXPECT_LT(rms, 0.02) << "T = " << t_factor;
    EXPECT_LT(worst, 0.05) << "T = " << t_factor;
    const double settlement = -mp.displacement[fp.size() - 1][0];  // the top point
    EXPECT_NEAR(settlement, settlement_series(t_factor), 0.05 * final_settlement)
        << "T = " << t_factor;
    const numerics::FluidBalance b = solver.balance();
    const double mismatch =
        (b.liquid_mass - start.liquid_mass - b.liquid_inflow) / start.liquid_mass;
    EXPECT_LT(std::abs(mismatch), 1e-3) << "T = " << t_factor;
  }
}

/// The pore pressures of the loaded column (tests/cycles/restore_check.hpp: 1 m, saturated, a
/// 10 kPa load ramped over 8 ms, drained at the top) at t = 0.2 s (T = 0.26), run with coupling
/// intervals of `interval` seconds; and the largest liquid mismatch met on the way.
std::pair<std::vector<double>, double> loaded_column_at(double interval) {
  std::string text = restore_check::loaded_column("implicit");
  const std::string tail = "cycle: implicit}";
  text.replace(text.find(tail), tail.size(),
               "cycle: implicit, implicit: {coupling_interval: " + std::to_string(interval) + "}}");
  const Case c = parse_case_text(text, "<test>");
  const auto grid = make_grid<1>(c);
  ImplicitSolver<1, numerics::LinearKernel> solver(c, grid, fill_bodies<1>(c, grid), 1);
  const numerics::FluidBalance start = solver.balance();
  double t = 0.0, worst = 0.0;
  while (t < 0.2 - 1e-12) {
    const double dt = std::min(solver.interval(), 0.2 - t);
    solver.step(t, dt);
    t += dt;
    const numerics::FluidBalance b = solver.balance();
    worst = std::max(
        worst, std::abs(b.liquid_mass - start.liquid_mass - b.liquid_inflow) / start.liquid_mass);
  }
  return {solver.fluids().liquid_pressure, worst};
}

TEST(ImplicitCoupling, IntervalsFarBeyondTheFlowsCellTimeGiveTheSamePressures) {
  // The load's pressure relaxes across a cell within h^2 / (k K_u) = 1.6e-4 s (K_u = K_l / n),
  // the time the interval was once bounded by (docs/balance_laws.md). Intervals of 1 ms and
  // 50 ms (300 times that) must give the same consolidation, within 2 % of the load (V9's
  // tolerance against the series), and keep the water.
  const auto [fine, fine_mismatch] = loaded_column_at(1e-3);
  const auto [coarse, coarse_mismatch] = loaded_column_at(5e-2);
  double worst = 0.0, largest = 0.0;
  for (std::size_t p = 0; p < fine.size(); ++p) {
    worst = std::max(worst, std::abs(coarse[p] - fine[p]));
    largest = std::max(largest, fine[p]);
  }
  EXPECT_GT(largest, 5e3);  // still consolidating: most of the load in the water at the base
  EXPECT_LT(worst, 0.02 * 1e4);
  EXPECT_LT(fine_mismatch, 1e-9);
  EXPECT_LT(coarse_mismatch, 1e-9);
}

}  // namespace test_implicit_coupling
}  // namespace unsatmpm

namespace unsatmpm {
namespace test_implicit_coupling {

// A solver restored from a checkpoint goes on as the one that wrote it (tests/cycles/
// restore_check.hpp; docs/output.md, "Checkpoints and resume").
/// V1's infiltration into a rigid unsaturated column, in the main cycle.
const char* const rigid_infiltration = R"(
name: infiltration
dimension: 1
grid: {origin: [0], size: [1], cells: [40]}
shape_function: linear
gravity: [0]
phases: solid_liquid_gas
fluids:
  liquid: {density: 1000, bulk_modulus: 8.0e+7, viscosity: 1.0e-3}
  gas: {model: ideal, density: 1.2, viscosity: 1.8e-5}
mass_balance: full
skeleton: rigid
materials:
  - {name: soil, model: linear_elastic, young_modulus: 1.0e+7, poisson_ratio: 0.3,
     solid_density: 2700, porosity: 0.3, intrinsic_permeability: 5.0e-11,
     retention: {model: linear, a_s: 1.0e-6}, liquid_relative_permeability: {model: constant},
     gas_relative_permeability: {model: constant}}
bodies:
  - {name: column, material: soil, points_per_cell: 4, box: {min: [0], max: [1]},
     initial_state: {suction: 5.0e+5, gas_pressure: 0}}
boundaries:
  - {name: top, plane: {axis: x, at: 1}, liquid: {suction: 0}, gas: {pressure: 0}}
  - {name: bottom, plane: {axis: x, at: 0}, gas: {pressure: 0}}
solver: {end_time: 6, damping: 0, cycle: implicit, implicit: {coupling_interval: 0.03}}
output: {times: [6]}
)";

TEST(CheckpointRestore, MainCycleWithADeformableSkeletonGoesOnBitForBit) {
  using S = ImplicitSolver<1, numerics::LinearKernel>;
  restore_check::restore_and_compare<1, S>(
      restore_check::loaded_column("implicit"), 10, 20, [](const S& a, const S& b) {
        EXPECT_GT(a.fluids().liquid_pressure[20], 1e3);  // the load made pore pressure
        restore_check::expect_same_points<1>(a.points(), b.points());
        restore_check::expect_same_fluids<1>(a.fluids(), b.fluids());
        EXPECT_TRUE(restore_check::same_bits(a.nodal_pressures()[0], b.nodal_pressures()[0]));
        EXPECT_EQ(a.balance().liquid_inflow, b.balance().liquid_inflow);
        EXPECT_EQ(a.interval(), b.interval());
      });
}

TEST(CheckpointRestore, MainCycleWithARigidSkeletonAgreesWithinCvodesTolerance) {
  using S = ImplicitSolver<1, numerics::LinearKernel>;
  restore_check::restore_and_compare<1, S>(rigid_infiltration, 10, 30, [](const S& a, const S& b) {
    const double rtol = 1e-6, atol = 1.0;  // the case's CVODE tolerances (the defaults)
    for (const auto field :
         {&numerics::FluidPoints<1>::liquid_pressure, &numerics::FluidPoints<1>::gas_pressure}) {
      const auto& pa = a.fluids().*field;
      const auto& pb = b.fluids().*field;
      double scale = 0.0, worst = 0.0;
      for (std::size_t p = 0; p < pa.size(); ++p) {
        scale = std::max(scale, std::abs(pa[p]));
        worst = std::max(worst, std::abs(pa[p] - pb[p]));
      }
      EXPECT_LE(worst, 10.0 * (rtol * scale + atol));
    }
    // The infiltration moved the pressures: the comparison is not of two states at rest.
    EXPECT_LT(a.fluids().liquid_pressure.back(), 4.5e5);
  });
}

/// A column at 20 kPa suction and gas pressure 0 whose top is given a gas pressure of 5 kPa
/// alone (the liquid closed there): switching it on at t = 0 jumps the top node's gas pressure,
/// and the top node's liquid must follow so that no water appears. Before, the jump's suction
/// change dried the points at the top, and 2.0e-3 of the column's water was counted as leaving
/// through a face that prescribes none (measured, both skeletons); now the liquid moved is the
/// Newton iteration's 1e-8 of that. Tolerance: 1e-9 of the liquid mass. The gas does enter
/// (control).
TEST(ImplicitCoupling, AGasPressureSwitchedOnAloneBringsNoWater) {
  for (const char* skeleton : {"rigid", "deformable"}) {
    const Case c = parse_case_text(std::string(R"(name: gas_top
dimension: 1
grid: {origin: [0], size: [1], cells: [20]}
shape_function: linear
gravity: [0]
phases: solid_liquid_gas
fluids:
  liquid: {density: 1000, bulk_modulus: 2.0e+9, viscosity: 1.0e-3}
  gas: {model: ideal, density: 1.2, viscosity: 1.8e-5}
mass_balance: full
skeleton: )") + skeleton + R"(
materials:
  - {name: soil, model: linear_elastic, young_modulus: 1.0e+7, poisson_ratio: 0.3,
     solid_density: 2700, porosity: 0.4, intrinsic_permeability: 1.0e-12,
     retention: {model: van_genuchten, p0: 2.0e+4, lambda: 0.4, residual_saturation: 0},
     liquid_relative_permeability: {model: mualem_van_genuchten, lambda: 0.4},
     gas_relative_permeability: {model: power, exponent: 3}}
bodies:
  - {name: column, material: soil, points_per_cell: 2, box: {min: [0], max: [1]},
     initial_state: {suction: 2.0e+4, gas_pressure: 0}}
boundaries:
  - {name: base, plane: {axis: x, at: 0}, mechanical: fixed}
  - {name: top, plane: {axis: x, at: 1}, gas: {pressure: 5000}}
solver: {end_time: 1.0e-3, damping: 0, cycle: implicit}
output: {times: [1.0e-3]}
)",
                                   "case.yaml");
    const auto grid = make_grid<1>(c);
    ImplicitSolver<1, numerics::LinearKernel> s(c, grid, fill_bodies<1>(c, grid), 1);
    const numerics::FluidBalance start = s.balance();
    double t = 0.0;
    while (t < 1e-3) {
      const double dt = std::min(s.interval(), 1e-3 - t);
      s.step(t, dt);
      t += dt;
    }
    const numerics::FluidBalance b = s.balance();
    EXPECT_LT(std::abs(b.liquid_inflow), 1e-9 * start.liquid_mass) << skeleton;
    EXPECT_LT(std::abs(b.liquid_mass - start.liquid_mass), 1e-9 * start.liquid_mass) << skeleton;
    EXPECT_GT(b.gas_inflow, 1e-3 * start.gas_mass) << skeleton;
  }
}

}  // namespace test_implicit_coupling
}  // namespace unsatmpm

// Properties of the explicit three-phase cycle on small columns: hydrostatic equilibrium is kept,
// steady Darcy flow reaches kappa/mu dP/L, nothing moves without a driving force, and the
// implicit drag is stable at steps far above the drag relaxation time.
#include <gtest/gtest.h>

#include <random>

#include "cycles/three_phase_solver.hpp"
#include "input/case_parser.hpp"
#include "tests/cycles/restore_check.hpp"
#include "tests/cycles/suction_block.hpp"

namespace unsatmpm {
namespace test_three_phase_cycle {

constexpr double rho_l = 1000.0, kappa = 1e-11, mu_l = 1e-3, porosity = 0.4;

/// A saturated 1D column of 1 m, rigid skeleton, 20 cells, 2 points per cell.
Case saturated_column() {
  Case c;
  c.file = "<test>";
  c.name = "column";
  c.dimension = 1;
  c.shape_function = ShapeFunctionKind::linear;
  c.grid = {{0.0}, {1.0}, {20}};
  c.gravity = {0.0};
  c.phases = Phases::solid_liquid_gas;
  c.fluids = FluidsSpec{physics::CompressibleFluid::create(rho_l, 0.0, 2e9), mu_l,
                        physics::IdealGas::create(1.2), 1.8e-5};
  c.mass_balance = physics::MassBalance::full;
  c.skeleton = physics::Skeleton::rigid;
  HydraulicSpec h{2650.0,
                  porosity,
                  kappa,
                  physics::LinearRetention::create(1e-6, 0.0),
                  physics::ConstantRelPerm{},
                  physics::ConstantRelPerm{}};
  c.materials.push_back(
      {"soil", (1 - porosity) * 2650.0, physics::LinearElastic::create(1e7, 0.3), h});
  c.bodies.push_back({"column", 0, 2, BoxGeometry{{0.0}, {1.0}}, std::vector<double>{0.0},
                      InitialPressures{0.0, 0.0}});
  c.solver.end_time = 1.0;
  c.solver.damping = 0.0;
  c.solver.flip_fraction = 1.0;
  return c;
}

BoundarySpec pressure_boundary(const char* name, double at, double p_liquid, double p_gas) {
  BoundarySpec b{name, {0, at}, std::nullopt, std::nullopt, std::nullopt};
  b.liquid = LiquidCondition{LiquidCondition::Kind::pressure, TimeFunction{{{0.0, p_liquid}}}};
  b.gas_pressure = TimeFunction{{{0.0, p_gas}}};
  return b;
}

ThreePhaseSolver<1, numerics::LinearKernel> make_solver(const Case& c) {
  const auto grid = make_grid<1>(c);
  return ThreePhaseSolver<1, numerics::LinearKernel>(c, grid, fill_bodies<1>(c, grid), 1);
}

void run(ThreePhaseSolver<1, numerics::LinearKernel>& s, double end, double& t) {
  while (t < end) {
    const double dt = std::min(0.5 * s.critical_time_step(), end - t);
    s.step(t, dt);
    t += dt;
  }
}

TEST(ThreePhaseCycle, NothingMovesWithoutADrivingForce) {
  Case c = saturated_column();
  c.boundaries.push_back(pressure_boundary("top", 1.0, 0.0, 0.0));
  auto s = make_solver(c);
  double t = 0.0;
  run(s, 0.01, t);
  const auto& fp = s.fluids();
  for (std::size_t p = 0; p < fp.size(); ++p) {
    EXPECT_NEAR(fp.liquid_pressure[p], 0.0, 1e-6);
    EXPECT_NEAR(fp.liquid_velocity[p][0], 0.0, 1e-12);
  }
}

// A column under gravity with the hydrostatic pressure rho_l g depth stays at rest: the discrete
// pressure gradient of a linear field balances the nodal weight exactly with symmetric points.
TEST(ThreePhaseCycle, HydrostaticColumnStaysAtRest) {
  Case c = saturated_column();
  c.gravity = {-9.81};
  c.boundaries.push_back(pressure_boundary("top", 1.0, 0.0, 0.0));
  auto s = make_solver(c);
  auto& fp = s.mutable_fluids();
  const auto& mp = s.points();
  std::vector<double> p0(fp.size());
  for (std::size_t p = 0; p < fp.size(); ++p) {
    p0[p] = fp.liquid_pressure[p] = rho_l * 9.81 * (1.0 - mp.position[p][0]);
    fp.liquid_density[p] = c.fluids->liquid.density(p0[p]);
  }
  double t = 0.0;
  run(s, 0.1, t);
  for (std::size_t p = 0; p < fp.size(); ++p) {
    EXPECT_NEAR(fp.liquid_pressure[p], p0[p], 1.0) << "point " << p;  // of up to 9810 Pa
    EXPECT_LT(std::abs(fp.liquid_velocity[p][0]), 1e-6) << "point " << p;
  }
}

// Steady flow through a saturated column between two prescribed pressures: the liquid's Darcy
// flux n (v_l - v_s) reaches kappa / mu_l * dP / L.
TEST(ThreePhaseCycle, SteadyDarcyFlow) {
  Case c = saturated_column();
  const double dp = 1e4;
  c.boundaries.push_back(pressure_boundary("bottom", 0.0, dp, 0.0));
  c.boundaries.push_back(pressure_boundary("top", 1.0, 0.0, 0.0));
  c.bodies[0].initial_pressures = InitialPressures{dp / 2, 0.0};
  auto s = make_solver(c);
  double t = 0.0;
  run(s, 0.5, t);
  const double q_expected = kappa / mu_l * dp / 1.0;  // upward, +x
  const auto& fp = s.fluids();
  for (std::size_t p = 0; p < fp.size(); ++p) {
    const double q = porosity * fp.liquid_velocity[p][0];
    EXPECT_NEAR(q, q_expected, 0.02 * q_expected) << "point " << p;
  }
}

// The mass balances solved at the nodes: the first-order mass change sum_p V_p A_p dP_p equals
// dt sum_p V_p r_p for both fluids, uniform data give the pointwise answer, a rate linear in x
// gives the pointwise (linear) increments at points of interior cells, and the gas pressure is
// held where no point has gas storage.
TEST(ThreePhaseCycle, NodalMassBalanceConservesAndReproducesLinearFields) {
  Case c = saturated_column();
  c.bodies[0].points_per_cell = 4;
  const auto grid = make_grid<1>(c);
  const PointSet<1> set = fill_bodies<1>(c, grid);
  const auto& mp = set.points;
  const auto n_mp = static_cast<std::int64_t>(mp.size());
  numerics::FluidPoints<1> fp;
  fp.resize(mp.size());
  numerics::ThreePhaseNodes<1> nodes;
  nodes.resize(grid.n_nodes(), 2);
  const double dt = 1e-3, h = grid.spacing[0];
  const auto nodal = [&] {
    numerics::nodal_pressure_increments<1, numerics::LinearKernel>(grid, mp, dt, nodes, fp);
  };
  const physics::StorageMatrix uniform{2e-6, -1e-6, -3e-8, 5e-7};

  for (std::int64_t p = 0; p < n_mp; ++p) {
    fp.storage[p] = uniform;
    fp.liquid_rate[p] = 2.0 - 5.0 * mp.position[p][0];
    fp.gas_rate[p] = 0.3 + 0.1 * mp.position[p][0];
  }
  numerics::FluidPoints<1> pointwise = fp;
  numerics::point_pressure_increments<1>(dt, 0, n_mp, mp, pointwise);
  nodal();
  for (std::int64_t p = 0; p < n_mp; ++p) {
    const double x = mp.position[p][0];
    if (x > h && x < 1.0 - h) {
      EXPECT_NEAR(fp.liquid_increment[p], pointwise.liquid_increment[p],
                  1e-12 * std::abs(pointwise.liquid_increment[p]))
          << p;
      EXPECT_NEAR(fp.gas_increment[p], pointwise.gas_increment[p],
                  1e-12 * std::abs(pointwise.gas_increment[p]))
          << p;
    }
  }

  // Storage and rates varying from point to point: the mass change is kept, phase by phase.
  for (std::int64_t p = 0; p < n_mp; ++p) {
    const double x = mp.position[p][0], w = 1.0 + 0.5 * std::sin(37.0 * x);
    fp.storage[p] = {w * 2e-6, -w * 1e-6, -3e-8, (2.0 - w) * 5e-7};
    fp.liquid_rate[p] = std::sin(11.0 * x) + 0.3;
    fp.gas_rate[p] = std::cos(7.0 * x);
  }
  nodal();
  double gained_l = 0.0, gained_g = 0.0, rate_l = 0.0, rate_g = 0.0;
  for (std::int64_t p = 0; p < n_mp; ++p) {
    const auto& a = fp.storage[p];
    const double v = mp.volume[p], dl = fp.liquid_increment[p], dg = fp.gas_increment[p];
    gained_l += v * (a.ll * dl + a.lg * dg), gained_g += v * (a.gl * dl + a.gg * dg);
    rate_l += v * dt * fp.liquid_rate[p], rate_g += v * dt * fp.gas_rate[p];
  }
  EXPECT_NEAR(gained_l, rate_l, 1e-12 * std::abs(rate_l));
  EXPECT_NEAR(gained_g, rate_g, 1e-12 * std::abs(rate_g));

  // Saturated everywhere (A_gg = 0): P_g held, dP_l = dt r_l / A_ll for a uniform rate.
  for (std::int64_t p = 0; p < n_mp; ++p) {
    fp.storage[p] = {1e-8, 0.0, 0.0, 0.0};
    fp.liquid_rate[p] = 4.0, fp.gas_rate[p] = 1.0;
  }
  nodal();
  for (std::int64_t p = 0; p < n_mp; ++p) {
    EXPECT_EQ(fp.gas_increment[p], 0.0);
    EXPECT_NEAR(fp.liquid_increment[p], dt * 4.0 / 1e-8, 1e-9 * dt * 4.0 / 1e-8);
  }
}

}  // namespace test_three_phase_cycle
}  // namespace unsatmpm

namespace unsatmpm {
namespace test_three_phase_cycle {

using test_blocks::block_under_suction;

// The body's free surface (not a grid boundary) holds its fluids (cycles/three_phase_solver.hpp,
// mark_free_surface): a block at a uniform suction of 10 kPa, without gravity, standing free in a
// larger grid keeps its water and its pressures. The integration by parts of the fluids' pressure
// force assumes zero pressure beyond the body, so without the free-surface condition the suction
// drew water in through the surface: 2.7e-3 of the liquid mass per second on this block
// (measured), 4e-6 in these 200 steps. Tolerance 1e-12 of the mass: round-off.
TEST(ThreePhaseCycle, AFreeSurfaceHoldsTheFluidsOfABlockUnderSuction) {
  const Case c = block_under_suction("[0, 0]", "{min: [0.5, 0.5], max: [1.5, 1.5]}");
  const auto grid = make_grid<2>(c);
  ThreePhaseSolver<2, numerics::GimpKernel> solver(c, grid, fill_bodies<2>(c, grid), 1);
  const double before = solver.balance().liquid_mass;
  const double dt = 0.5 * solver.critical_time_step();
  for (int s = 0; s < 200; ++s) solver.step(s * dt, dt);
  EXPECT_NEAR(solver.balance().liquid_mass, before, 1e-12 * before);
  for (std::size_t p = 0; p < solver.fluids().size(); ++p)
    ASSERT_NEAR(solver.fluids().liquid_pressure[p], -1.0e4, 1e-6) << "point " << p;
}

// The full form's flux divergence moves no mass across a node (docs/balance_laws.md, "A flux
// divergence that moves no mass across a node"): with the points displaced at random from their
// tiling, so that sum_p V_p grad N_i is no longer zero inside, and random velocities of the three
// phases, sum_p V_p div J_p vanishes to round-off for both fluids; the uncorrected divergence
// sum_i grad N_i . J_i does not (the control).
TEST(ThreePhaseCycle, TheFluxDivergenceMovesNoMassAcrossANode) {
  const Case c = block_under_suction("[0, -9.81]", "{min: [0.3, 0.3], max: [1.7, 1.5]}");
  const auto grid = make_grid<2>(c);
  PointSet<2> set = fill_bodies<2>(c, grid);
  auto& mp = set.points;
  const auto hydraulics = hydraulic_models(c);
  numerics::FluidPoints<2> fp = initial_fluid_state<2>(c, set, hydraulics);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> shift(-0.02, 0.02), speed(-0.1, 0.1);
  for (std::size_t p = 0; p < mp.size(); ++p) {
    mp.position[p] += numerics::Vec<2>(shift(random), shift(random));
    mp.velocity[p] = {speed(random), speed(random)};
    fp.liquid_velocity[p] = {speed(random), speed(random)};
    fp.gas_velocity[p] = {speed(random), speed(random)};
  }
  numerics::ThreePhaseNodes<2> nodes;
  nodes.resize(grid.n_nodes(), 1);
  for (std::size_t m = 0; m < hydraulics.size(); ++m)
    numerics::refresh_point_laws<2>(hydraulics[m], set.ranges[m], set.ranges[m + 1], fp);
  numerics::p2g_three_phase<2, numerics::GimpKernel>(grid, mp, fp, {0.0, -9.81}, nodes);
  numerics::solve_grid_three_phase<2, numerics::Skeleton::deformable>(1e-5, 0.0, 1e-12, nodes);
  double sum_l = 0.0, sum_g = 0.0, size_l = 0.0, size_g = 0.0, uncorrected = 0.0;
  numerics::TransferStencil<2, numerics::GimpKernel> st;
  for (std::size_t p = 0; p < mp.size(); ++p) {
    st.evaluate(grid, mp.position[p], mp.half_size[p]);
    const auto k = numerics::interpolate<2, numerics::GimpKernel>(st, nodes);
    sum_l += mp.volume[p] * k.div_flux_l, size_l += mp.volume[p] * std::abs(k.div_flux_l);
    sum_g += mp.volume[p] * k.div_flux_g, size_g += mp.volume[p] * std::abs(k.div_flux_g);
    for (int a = 0; a < st.n; ++a) {
      const auto i = st.node[a];
      uncorrected += mp.volume[p] * nodes.liquid_theta[i] *
                     st.grad[a].dot(nodes.liquid_velocity[i] - nodes.solid_velocity[i]);
    }
  }
  ASSERT_GT(size_l, 0.0);
  EXPECT_LT(std::abs(sum_l), 1e-12 * size_l);
  EXPECT_LT(std::abs(sum_g), 1e-12 * size_g);
  EXPECT_GT(std::abs(uncorrected), 1e-3 * size_l);
}

}  // namespace test_three_phase_cycle
}  // namespace unsatmpm

namespace unsatmpm {
namespace test_three_phase_cycle {

// A solver restored from a checkpoint goes on as the one that wrote it (tests/cycles/
// restore_check.hpp; docs/output.md, "Checkpoints and resume").
TEST(CheckpointRestore, ThreePhaseCycleGoesOnBitForBit) {
  using S = ThreePhaseSolver<1, numerics::LinearKernel>;
  restore_check::restore_and_compare<1, S>(
      restore_check::loaded_column("explicit"), 300, 300, [](const S& a, const S& b) {
        restore_check::expect_same_points<1>(a.points(), b.points());
        restore_check::expect_same_fluids<1>(a.fluids(), b.fluids());
        EXPECT_EQ(a.balance().liquid_inflow, b.balance().liquid_inflow);
      });
}

}  // namespace test_three_phase_cycle
}  // namespace unsatmpm

// Properties of the explicit one-phase cycle: conservation, exact rigid motion, free fall,
// and the static answer of a damped elastic column.
#include <gtest/gtest.h>

#include <limits>

#include "cycles/explicit_solver.hpp"
#include "tests/cycles/restore_check.hpp"

namespace unsatmpm {
namespace test_explicit_cycle {

Case block_case(int dimension, ShapeFunctionKind kernel) {
  Case c;
  c.file = "<test>";
  c.name = "block";
  c.dimension = dimension;
  c.shape_function = kernel;
  c.grid.origin.assign(dimension, 0.0);
  c.grid.size.assign(dimension, 1.0);
  c.grid.cells.assign(dimension, 10);
  c.gravity.assign(dimension, 0.0);
  c.materials.push_back({"soil", 2000.0, physics::LinearElastic::create(1e6, 0.25)});
  c.bodies.push_back(
      {"block", 0, 2,
       BoxGeometry{std::vector<double>(dimension, 0.3), std::vector<double>(dimension, 0.6)},
       std::vector<double>(dimension, 0.0)});
  c.solver.end_time = 1.0;
  c.solver.damping = 0.0;
  return c;
}

template <int D, class K>
ExplicitSolver<D, K> make_solver(const Case& c) {
  const auto grid = make_grid<D>(c);
  return ExplicitSolver<D, K>(c, grid, fill_bodies<D>(c, grid), 2);
}

template <int D>
numerics::Vec<D> total_momentum(const numerics::MaterialPoints<D>& mp) {
  numerics::Vec<D> p = numerics::Vec<D>::Zero();
  for (std::size_t i = 0; i < mp.size(); ++i) p += mp.mass[i] * mp.velocity[i];
  return p;
}

// Exact up to round-off. GIMP's support tails give nodes with a tiny mass, whose accelerations
// f/m amplify round-off; the bound (a strain of 1e-9 against E) still catches any real error.
template <int D, class K>
void rigid_translation_is_exact(ShapeFunctionKind kind, double tol) {
  Case c = block_case(D, kind);
  c.bodies[0].initial_velocity = std::vector<double>(D, 0.37);
  auto solver = make_solver<D, K>(c);
  const auto x0 = solver.points().position;
  const double dt = 0.2 * solver.critical_time_step();
  for (int s = 0; s < 50; ++s) solver.step(dt);
  const auto& mp = solver.points();
  for (std::size_t p = 0; p < mp.size(); ++p) {
    for (int d = 0; d < D; ++d) {
      EXPECT_NEAR(mp.velocity[p][d], 0.37, tol);
      EXPECT_NEAR(mp.position[p][d] - x0[p][d], 0.37 * 50 * dt, tol);
    }
    EXPECT_LT(mp.stress[p].norm(), 1e-9 * 1e6);  // no strain from a rigid motion
  }
}

TEST(ExplicitCycle, ProjectingToTheGridKeepsMassAndMomentumAndChangesNoPoint) {
  // The output at t = 0 (project_to_grid): the nodal mass sums to the points', a block moving
  // as one has that velocity at every node it reaches, and gravity is the only acceleration.
  Case c = block_case(2, ShapeFunctionKind::gimp);
  c.bodies[0].initial_velocity = std::vector<double>{0.3, -0.2};
  c.gravity = {0.0, -9.81};
  auto solver = make_solver<2, numerics::GimpKernel>(c);
  const auto before = solver.points().position;
  solver.project_to_grid();
  double nodal = 0.0, points = 0.0;
  for (std::int64_t i = 0; i < solver.nodes().n_nodes(); ++i) {
    nodal += solver.nodes().mass(i);
    if (solver.nodes().mass(i) <= 1e-9 * 2000.0) continue;
    EXPECT_NEAR(solver.nodes().velocity[i][0], 0.3, 1e-12);
    EXPECT_NEAR(solver.nodes().velocity[i][1], -0.2, 1e-12);
    EXPECT_NEAR(solver.nodes().acceleration[i][0], 0.0, 1e-12);  // no stress yet, no support
    EXPECT_NEAR(solver.nodes().acceleration[i][1], -9.81, 1e-12);
  }
  for (const double m : solver.points().mass) points += m;
  EXPECT_NEAR(nodal, points, 1e-12 * points);
  EXPECT_EQ(solver.points().position, before);
}

TEST(ExplicitCycle, RigidTranslationIsExactLinear2D) {
  rigid_translation_is_exact<2, numerics::LinearKernel>(ShapeFunctionKind::linear, 1e-12);
}
TEST(ExplicitCycle, RigidTranslationIsExactGimp3D) {
  rigid_translation_is_exact<3, numerics::GimpKernel>(ShapeFunctionKind::gimp, 1e-8);
}

// Without boundaries, gravity or damping, internal forces cancel: momentum is conserved (up to
// the forces on nodes below the mass floor, which are dropped, and round-off).
TEST(ExplicitCycle, MomentumConservedUnderInternalForces) {
  Case c = block_case(2, ShapeFunctionKind::gimp);
  c.bodies[0].initial_velocity =
      SineVelocity{{0.05, -0.02}, 0, 10.0, 0.3};  // a non-uniform field that strains the block
  auto solver = make_solver<2, numerics::GimpKernel>(c);
  const auto p0 = total_momentum<2>(solver.points());
  const double dt = 0.3 * solver.critical_time_step();
  for (int s = 0; s < 200; ++s) solver.step(dt);
  const auto p1 = total_momentum<2>(solver.points());
  EXPECT_GT(solver.points().stress[0].norm(), 1.0);  // the block did strain
  EXPECT_LT((p1 - p0).norm(), 1e-8 * p0.norm());
}

// A free block in gravity falls with g and stays unstressed.
TEST(ExplicitCycle, FreeFallHasAccelerationG) {
  Case c = block_case(2, ShapeFunctionKind::linear);
  c.gravity = {0.0, -9.81};
  auto solver = make_solver<2, numerics::LinearKernel>(c);
  const double dt = 1e-4;
  const int n = 300;
  for (int s = 0; s < n; ++s) solver.step(dt);
  const auto& mp = solver.points();
  for (std::size_t p = 0; p < mp.size(); ++p) {
    EXPECT_NEAR(mp.velocity[p][1], -9.81 * n * dt, 1e-10);
    EXPECT_LT(mp.stress[p].norm(), 1e-6);
  }
}

// The same fall across grid lines: each row of points that crosses one reaches nodes of almost no
// mass. With linear shape functions and the nodes' own velocities in the strain (USL) the block
// took stress there and flew apart within a millisecond of the first crossing (kinetic energy
// from 131 J to 7.5e8 J in five steps); with MUSL's remapped velocities it falls as one
// (numerics/velocity_remap.hpp). 0.25 s of fall crosses about three cell rows of 0.1 m; linear in
// 2D and 3D, and GIMP (its own nodal velocities) in 2D.
template <int D, class K>
void falls_across_grid_lines(ShapeFunctionKind kind) {
  Case c = block_case(D, kind);
  c.grid.size.assign(D, 2.0);
  c.grid.cells.assign(D, 20);
  c.bodies[0].geometry =
      BoxGeometry{std::vector<double>(D, 0.75), std::vector<double>(D, 1.25)};  // off the lines
  c.gravity.assign(D, 0.0);
  c.gravity[D - 1] = -9.81;
  c.materials[0].model = physics::LinearElastic::create(1e8, 0.2);
  auto solver = make_solver<D, K>(c);
  const double dt = 0.5 * solver.critical_time_step();
  const int n = static_cast<int>(0.25 / dt);
  for (int s = 0; s < n; ++s) solver.step(dt);
  const auto& mp = solver.points();
  for (std::size_t p = 0; p < mp.size(); ++p) {
    EXPECT_NEAR(mp.velocity[p][D - 1], -9.81 * n * dt, 1e-9);
    EXPECT_NEAR(mp.velocity[p][0], 0.0, 1e-9);
    EXPECT_LT(mp.stress[p].norm(), 1e-3);  // Pa, against E = 1e8 Pa
  }
}

TEST(ExplicitCycle, FreeFallAcrossGridLinesStaysUnstressedLinear2D) {
  falls_across_grid_lines<2, numerics::LinearKernel>(ShapeFunctionKind::linear);
}
TEST(ExplicitCycle, FreeFallAcrossGridLinesStaysUnstressedLinear3D) {
  falls_across_grid_lines<3, numerics::LinearKernel>(ShapeFunctionKind::linear);
}
TEST(ExplicitCycle, FreeFallAcrossGridLinesStaysUnstressedGimp2D) {
  falls_across_grid_lines<2, numerics::GimpKernel>(ShapeFunctionKind::gimp);
}

// Damping must take the column to rest; the check of the static stress is V3's job, here only
// that the kinetic energy decays and that the base holds. Pure FLIP keeps velocity modes that
// the grid cannot see (more points than nodes) forever; a 2% PIC share removes them.
TEST(ExplicitCycle, DampedColumnComesToRest) {
  Case c = block_case(1, ShapeFunctionKind::linear);
  c.grid.size = {1.0};
  c.bodies[0].geometry = BoxGeometry{{0.0}, {1.0}};
  c.gravity = {-9.81};
  c.solver.damping = 0.2;
  c.solver.flip_fraction = 0.98;
  c.boundaries.push_back({"base", {0, 0.0}, MechanicalCondition::fixed});
  auto solver = make_solver<1, numerics::LinearKernel>(c);
  const double dt = 0.5 * solver.critical_time_step();
  for (int s = 0; s < 4000; ++s) solver.step(dt);
  const auto& mp = solver.points();
  double ek = 0.0;
  for (std::size_t p = 0; p < mp.size(); ++p) ek += 0.5 * mp.mass[p] * mp.velocity[p].squaredNorm();
  EXPECT_LT(ek, 1e-12);
  // The weight of the whole column reaches the base: sigma_xx of the lowest point ~ -rho g H.
  EXPECT_NEAR(mp.stress[0][0], -2000.0 * 9.81 * (1.0 - 0.025), 2000.0 * 9.81 * 0.05);
}

TEST(ExplicitCycle, BlowUpIsReportedWithThePoint) {
  Case c = block_case(2, ShapeFunctionKind::linear);
  c.bodies[0].initial_velocity = std::vector<double>{100.0, 0.0};  // leaves the grid quickly
  auto solver = make_solver<2, numerics::LinearKernel>(c);
  try {
    for (int s = 0; s < 1000; ++s) solver.step(1e-3);
    FAIL() << "no error raised";
  } catch (const BlowUpError& e) {
    EXPECT_NE(std::string(e.what()).find("left the grid"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("material point"), std::string::npos);
  }
}

// A wave speed grown past wave_speed_blowup_factor times its initial value is a collapse of the
// explicit step, reported with the fastest point instead of crawling on at vanishing steps. One
// point is set moving at 1e4 times the P-wave speed: the step after it ends the run; at 1e-3
// times, the same steps go on (the control).
TEST(ExplicitCycle, ACollapsedStepIsReportedWithTheFastestPoint) {
  const Case c = block_case(2, ShapeFunctionKind::linear);
  for (const double factor : {1e-3, 1e4}) {
    auto solver = make_solver<2, numerics::LinearKernel>(c);
    const double c0 = solver.max_wave_speed();
    solver.points().velocity[7] = {factor * c0, 0.0};
    try {
      solver.step(1e-9);
      EXPECT_LT(factor, 1.0) << "no collapse reported at " << factor << " times c";
    } catch (const BlowUpError& e) {
      EXPECT_GT(factor, 1.0) << e.what();
      EXPECT_NE(std::string(e.what()).find("the explicit step collapsed"), std::string::npos)
          << e.what();
      EXPECT_NE(std::string(e.what()).find("material point 7 "), std::string::npos) << e.what();
    }
  }
}

// PoreLoads::max_volume (HydraulicModel::max_volume, the bounded porosity): a block set expanding
// at div v = 1/s grows by about 0.2 % in 2 ms (a tenth of its elastic period); with the bound at
// 0.05 % above each point's volume, every point stops at its bound, and with no bound (an
// infinite one, as for a material without n_max) the same run passes it (the control).
TEST(ExplicitCycle, VolumeIsHeldAtItsBound) {
  const Case c = block_case(2, ShapeFunctionKind::linear);
  const auto grid = make_grid<2>(c);
  const auto models = solid_models(c);
  for (const bool bounded : {true, false}) {
    PointSet<2> points = fill_bodies<2>(c, grid);
    auto& mp = points.points;
    for (std::size_t p = 0; p < mp.size(); ++p)
      mp.velocity[p] = 0.5 * (mp.position[p] - numerics::Vec<2>(0.45, 0.45));
    const std::vector<double> v0 = mp.volume, zeros(mp.size(), 0.0),
                              none(mp.size(), std::numeric_limits<double>::infinity());
    std::vector<double> bound(mp.size());
    for (std::size_t p = 0; p < mp.size(); ++p) bound[p] = 1.0005 * v0[p];
    std::vector<numerics::StrengthMemo> memo(mp.size());
    const numerics::PoreLoads loads{zeros, zeros, zeros, memo, bounded ? bound : none};
    numerics::NodalState<2> nodes;
    nodes.resize(grid.n_nodes(), 1);
    for (int step = 0; step < 20; ++step)
      explicit_mechanics_step<2, numerics::LinearKernel>(grid, models, {0.0, 1.0},
                                                         numerics::Vec<2>::Zero(), 1e-12, 1e-4,
                                                         loads, {}, nodes, points);
    int at_bound = 0, above = 0;
    for (std::size_t p = 0; p < mp.size(); ++p) {
      at_bound += mp.volume[p] == bound[p];
      above += mp.volume[p] > bound[p];
    }
    if (bounded) {
      EXPECT_EQ(above, 0);
      EXPECT_EQ(at_bound, static_cast<int>(mp.size()));
    } else {
      EXPECT_EQ(above, static_cast<int>(mp.size()));
    }
  }
}

}  // namespace test_explicit_cycle
}  // namespace unsatmpm

namespace unsatmpm {
namespace test_explicit_cycle {

// A solver restored from a checkpoint goes on as the one that wrote it (tests/cycles/
// restore_check.hpp; docs/output.md, "Checkpoints and resume").
const char* const one_phase_2d = R"(
name: block
dimension: 2
grid: {origin: [0, 0], size: [1, 2], cells: [8, 16]}
shape_function: gimp
gravity: [0, -9.81]
materials:
  - {name: soil, density: 1800, model: mohr_coulomb, young_modulus: 1.0e+6, poisson_ratio: 0.3,
     friction_angle: 30, dilatancy_angle: 0, cohesion: 1000}
bodies:
  - {name: block, material: soil, points_per_cell: 2, box: {min: [0, 0], max: [1, 1.5]}}
boundaries:
  - {name: base, plane: {axis: y, at: 0}, mechanical: fixed}
  - {name: left, plane: {axis: x, at: 0}, mechanical: roller}
  - {name: right, plane: {axis: x, at: 1}, mechanical: roller}
  - name: top
    plane: {axis: y, at: 1.5}
    traction: {normal: {ramp: {from: 0, to: 2.0e+4, start: 0, end: 0.05}}}
solver: {end_time: 1, damping: 0.02}
output: {times: [1]}
)";

TEST(CheckpointRestore, OnePhaseCycleGoesOnBitForBit) {
  using S = ExplicitSolver<2, numerics::GimpKernel>;
  restore_check::restore_and_compare<2, S>(one_phase_2d, 150, 150, [](const S& a, const S& b) {
    EXPECT_GT(a.points().plastic_strain[0] + a.points().displacement[0].norm(), 0.0);
    restore_check::expect_same_points<2>(a.points(), b.points());
  });
}

}  // namespace test_explicit_cycle
}  // namespace unsatmpm

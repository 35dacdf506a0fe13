#include <gtest/gtest.h>

#include <cmath>

#include "cycles/explicit_solver.hpp"
#include "cycles/tractions.hpp"
#include "input/input_node.hpp"

namespace unsatmpm {
namespace test_tractions {

/// A box body of `width` x 1 m in a 2 x 1.5 m grid of 0.25 m cells, with a traction on its top
/// (y = 1) or on another plane.
Case loaded_box(double width, double plane_y, TimeFunction normal) {
  Case c;
  c.file = "<test>";
  c.name = "box";
  c.dimension = 2;
  c.shape_function = ShapeFunctionKind::linear;
  c.grid = {{0.0, 0.0}, {2.0, 1.5}, {8, 6}};
  c.gravity = {0.0, 0.0};
  c.materials.push_back({"soil", 2000.0, physics::LinearElastic::create(1e7, 0.3)});
  c.bodies.push_back({"box", 0, 2, BoxGeometry{{0.0, 0.0}, {width, 1.0}}, std::vector<double>{}});
  BoundarySpec load{"load", {1, plane_y}};
  load.traction = TractionSpec{normal, -1, TimeFunction{{{0.0, 0.0}}}, "<test>:1:1: traction"};
  c.boundaries.push_back(load);
  c.solver.end_time = 1.0;
  c.solver.damping = 0.0;
  return c;
}

std::vector<numerics::NodalForce<2>> forces_at(const Case& c, double t) {
  const auto grid = make_grid<2>(c);
  const auto set = fill_bodies<2>(c, grid);
  BoundaryTractions<2> tr(c, grid, set.points);
  std::vector<numerics::NodalForce<2>> f;
  tr.forces(t, set.points, f);
  return f;
}

TEST(Tractions, ConsistentNodalForcesOfAUniformPressureOnTheTop) {
  const auto f = forces_at(loaded_box(2.0, 1.0, TimeFunction{{{0.0, 1000.0}}}), 0.3);
  ASSERT_EQ(f.size(), 9u);  // every node of y = 1
  double total = 0.0;
  const auto grid = make_grid<2>(loaded_box(2.0, 1.0, TimeFunction{{{0.0, 1.0}}}));
  for (const auto& nf : f) {
    const double x = grid.node_position(nf.node)[0];
    EXPECT_DOUBLE_EQ(grid.node_position(nf.node)[1], 1.0);
    // Pushes into the body, which lies below: -y. End nodes carry half a cell.
    const double expected = (x == 0.0 || x == 2.0) ? 0.125 : 0.25;
    EXPECT_NEAR(nf.force[1], -1000.0 * expected, 1e-9);
    EXPECT_EQ(nf.force[0], 0.0);
    total += nf.force[1];
  }
  EXPECT_NEAR(total, -1000.0 * 2.0, 1e-9);  // pressure times the loaded width
}

TEST(Tractions, CoverOnlyWhereTheBodyTouchesThePlaneAndFollowTheTimeFunction) {
  // Body 1.1 m wide: it covers 4.4 cells of the plane; a ramp 0 -> 2000 Pa over 1 s.
  const Case c = loaded_box(1.1, 1.0, TimeFunction{{{0.0, 0.0}, {1.0, 2000.0}}});
  const auto f = forces_at(c, 0.5);
  const auto grid = make_grid<2>(c);
  double total = 0.0, moment = 0.0;
  for (const auto& nf : f) {
    total += nf.force[1];
    moment += nf.force[1] * grid.node_position(nf.node)[0];
  }
  // 1000 Pa where the points' footprints meet the plane: the cell the edge cuts, [1, 1.25], keeps
  // its first point column (x = 1.0625, half size 0.0625), so the points cover [0, 1.125].
  EXPECT_NEAR(total, -1000.0 * 1.125, 1e-9);
  EXPECT_NEAR(moment / total, 0.5625, 1e-12);
}

TEST(Tractions, RefuseAPlaneWithoutMaterialOrWithMaterialOnBothSides) {
  const TimeFunction p{{{0.0, 1.0}}};
  for (const double y : {1.5, 0.5}) {
    const Case c = loaded_box(2.0, y, p);
    const auto grid = make_grid<2>(c);
    const auto set = fill_bodies<2>(c, grid);
    try {
      BoundaryTractions<2> tr(c, grid, set.points);
      FAIL() << "accepted a traction on y = " << y;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("<test>:1:1: traction"), std::string::npos);
      EXPECT_NE(std::string(e.what()).find(y > 1.0 ? "no material" : "both sides"),
                std::string::npos)
          << e.what();
    }
  }
}

TEST(Tractions, ElasticColumnSettlesByTheConstrainedModulus) {
  // One-phase column under a surcharge, sides on rollers, base fixed, no gravity: the static
  // settlement of the top points is p z / M (M the constrained modulus), reached under damping.
  Case c = loaded_box(2.0, 1.0, TimeFunction{{{0.0, 1.0e4}}});
  c.boundaries.push_back({"base", {1, 0.0}, MechanicalCondition::fixed});
  c.boundaries.push_back({"left", {0, 0.0}, MechanicalCondition::roller});
  c.boundaries.push_back({"right", {0, 2.0}, MechanicalCondition::roller});
  c.solver.damping = 0.3;
  ExplicitSolver<2, numerics::LinearKernel> solver(c, make_grid<2>(c),
                                                   fill_bodies<2>(c, make_grid<2>(c)), 1);
  double t = 0.0;
  while (t < 0.5) {
    const double dt = 0.5 * solver.critical_time_step();
    solver.step(t, dt);
    t += dt;
  }
  const double e = 1e7, nu = 0.3, m = e * (1 - nu) / ((1 + nu) * (1 - 2 * nu));
  const auto& mp = solver.points();
  for (std::size_t p = 0; p < mp.size(); ++p) {
    const double z = mp.position[p][1] - mp.displacement[p][1];
    EXPECT_NEAR(mp.displacement[p][1], -1.0e4 * z / m, 2e-3 * 1.0e4 / m) << "point " << p;
    EXPECT_NEAR(mp.stress[p][1], -1.0e4, 20.0);
  }
}

/// Two loaded planes that share a node, the box's top (y = 1) and its right side (x = 2), with
/// the box moved down 0.09 m: each load keeps its own columns, so every column of both sees the
/// body (a table of columns shared by the loads gave the top's corner node the side's column
/// there, and the top's corner column then saw nothing), and each load totals its pressure times
/// its face.
TEST(Tractions, TwoLoadsMeetingAtACornerKeepTheirOwnColumns) {
  Case c = loaded_box(2.0, 1.0, TimeFunction{{{0.0, 1000.0}}});
  BoundarySpec side{"side", {0, 2.0}};
  side.traction = TractionSpec{TimeFunction{{{0.0, 300.0}}}, -1, TimeFunction{{{0.0, 0.0}}},
                               "<test>:2:1: traction"};
  c.boundaries.push_back(side);
  const auto grid = make_grid<2>(c);
  auto set = fill_bodies<2>(c, grid);
  BoundaryTractions<2> tr(c, grid, set.points);
  for (std::size_t q = 0; q < set.points.size(); ++q) set.points.position[q][1] -= 0.09;
  std::vector<numerics::NodalForce<2>> f;
  tr.forces(0.0, set.points, f);
  EXPECT_FALSE(tr.unreached_node([](std::int64_t) { return 0.0; }, 1.0));  // every column sees
  double fx = 0.0, fy = 0.0;
  for (const auto& nf : f) fx += nf.force[0], fy += nf.force[1];
  EXPECT_NEAR(fy, -1000.0 * 2.0, 1e-9);  // the top, 2 m wide, pushed down
  EXPECT_NEAR(fx, -300.0 * 1.0, 1e-9);   // the side, 1 m high, pushed towards -x
}

/// The box moved down rigidly by 0.09 m: its lower point row in the top cell (y = 0.8125) has
/// left that cell, the upper one (0.9375) stays. Under a uniform stress equal to the load,
/// sigma_yy = -p, the internal forces -sum_p V_p sigma grad N_i (linear N) must balance the load's
/// nodal forces at every node of the top two rows, as they do at t = 0. A load held on the plane's
/// nodes did not: those nodes got all of it, the upper row's volume balances half (the points
/// there took twice the load; cycles/tractions.hpp).
TEST(Tractions, FollowTheFaceSoThatAUniformStressBalancesThem) {
  constexpr double p = 1000.0, drop = 0.09;
  const Case c = loaded_box(2.0, 1.0, TimeFunction{{{0.0, p}}});
  const auto grid = make_grid<2>(c);
  auto set = fill_bodies<2>(c, grid);
  BoundaryTractions<2> tr(c, grid, set.points);
  auto& mp = set.points;
  for (std::size_t q = 0; q < mp.size(); ++q) mp.position[q][1] -= drop;
  std::vector<numerics::NodalForce<2>> f;
  tr.forces(0.0, mp, f);
  std::vector<double> external(grid.n_nodes(), 0.0), internal(grid.n_nodes(), 0.0);
  for (const auto& nf : f) external[nf.node] += nf.force[1];
  const double hx = grid.spacing[0], hy = grid.spacing[1];
  for (std::size_t q = 0; q < mp.size(); ++q) {  // bilinear N over the point's cell
    const int cx = static_cast<int>(mp.position[q][0] / hx);
    const int cy = static_cast<int>(mp.position[q][1] / hy);
    const double u = mp.position[q][0] / hx - cx;
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b) {
        const double dndy = (a ? u : 1.0 - u) * (b ? 1.0 : -1.0) / hy;
        internal[(cx + a) * grid.stride[0] + (cy + b) * grid.stride[1]] -= mp.volume[q] * -p * dndy;
      }
  }
  double total = 0.0;
  for (std::int64_t i = 0; i < grid.n_nodes(); ++i) {
    total += external[i];
    if (grid.node_position(i)[1] >= 0.75) {
      EXPECT_NEAR(external[i] + internal[i], 0.0, 1e-9 * p) << "node " << i;
    }
  }
  EXPECT_NEAR(total, -p * 2.0, 1e-9);  // the load's whole force
}

/// The same in 3D, on a box 1 x 1 m wide that covers three quarters of a 1.25 m plane along x (so
/// the columns at its edge see it from one side), moved down by 0.09 m: the load's whole force,
/// and a uniform stress equal to it balancing every node of the top two node layers.
TEST(Tractions, FollowTheFaceIn3D) {
  constexpr double p = 1000.0, drop = 0.09;
  Case c;
  c.file = "<test>";
  c.name = "box3";
  c.dimension = 3;
  c.shape_function = ShapeFunctionKind::linear;
  c.grid = {{0.0, 0.0, 0.0}, {1.25, 1.0, 1.5}, {5, 4, 6}};
  c.gravity = {0.0, 0.0, 0.0};
  c.materials.push_back({"soil", 2000.0, physics::LinearElastic::create(1e7, 0.3)});
  c.bodies.push_back(
      {"box", 0, 2, BoxGeometry{{0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}}, std::vector<double>{}});
  BoundarySpec load{"load", {2, 1.0}};
  load.traction = TractionSpec{TimeFunction{{{0.0, p}}}, -1, TimeFunction{{{0.0, 0.0}}},
                               "<test>:1:1: traction"};
  c.boundaries.push_back(load);
  c.solver.end_time = 1.0;
  const auto grid = make_grid<3>(c);
  auto set = fill_bodies<3>(c, grid);
  BoundaryTractions<3> tr(c, grid, set.points);
  auto& mp = set.points;
  for (std::size_t q = 0; q < mp.size(); ++q) mp.position[q][2] -= drop;
  std::vector<numerics::NodalForce<3>> f;
  tr.forces(0.0, mp, f);
  std::vector<double> external(grid.n_nodes(), 0.0), internal(grid.n_nodes(), 0.0);
  for (const auto& nf : f) external[nf.node] += nf.force[2];
  const double h = grid.spacing[0];              // cubic cells
  for (std::size_t q = 0; q < mp.size(); ++q) {  // trilinear N over the point's cell
    int cell[3];
    double u[3];
    for (int d = 0; d < 3; ++d) {
      cell[d] = static_cast<int>(mp.position[q][d] / h);
      u[d] = mp.position[q][d] / h - cell[d];
    }
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b)
        for (int e = 0; e < 2; ++e) {
          const double dndz = (a ? u[0] : 1.0 - u[0]) * (b ? u[1] : 1.0 - u[1]) * (e ? 1 : -1) / h;
          const std::int64_t i = (cell[0] + a) * grid.stride[0] + (cell[1] + b) * grid.stride[1] +
                                 (cell[2] + e) * grid.stride[2];
          internal[i] -= mp.volume[q] * -p * dndz;
        }
  }
  double total = 0.0;
  for (std::int64_t i = 0; i < grid.n_nodes(); ++i) {
    total += external[i];
    if (grid.node_position(i)[2] >= 0.75) {
      EXPECT_NEAR(external[i] + internal[i], 0.0, 1e-9 * p) << "node " << i;
    }
  }
  EXPECT_NEAR(total, -p * 1.0, 1e-9);  // the load times the 1 m^2 the box covers
}

}  // namespace test_tractions
}  // namespace unsatmpm

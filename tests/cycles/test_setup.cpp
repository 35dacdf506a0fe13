#include <gtest/gtest.h>

#include "cycles/setup.hpp"

namespace unsatmpm {
namespace test_setup {

Case two_body_case() {
  Case c;
  c.file = "<test>";
  c.name = "two";
  c.dimension = 2;
  c.shape_function = ShapeFunctionKind::linear;
  c.grid = {{0.0, 0.0}, {4.0, 2.0}, {8, 4}};  // h = 0.5
  c.gravity = {0.0, -9.81};
  c.materials.push_back({"a", 1000.0, physics::LinearElastic::create(1e6, 0.2)});
  c.materials.push_back({"b", 3000.0, physics::LinearElastic::create(1e6, 0.2)});
  // Listed first with material b: must still come after material a's points.
  c.bodies.push_back({"triangle", 1, 3, PolygonGeometry{{{{2.0, 0.0}, {4.0, 0.0}, {4.0, 2.0}}}, {}},
                      std::vector<double>{}});
  c.bodies.push_back({"box", 0, 2, BoxGeometry{{0.0, 0.0}, {3.0, 1.0}}, std::vector<double>{}});
  c.solver.end_time = 1.0;
  c.solver.damping = 0.0;
  return c;
}

TEST(Setup, FillsBodiesOrderedByMaterialWithTheirMass) {
  const Case c = two_body_case();
  const auto grid = make_grid<2>(c);
  const auto set = fill_bodies<2>(c, grid);
  const auto& mp = set.points;
  ASSERT_EQ(set.ranges.size(), 3u);
  EXPECT_EQ(set.ranges[0], 0);
  EXPECT_EQ(set.ranges[2], static_cast<std::int64_t>(mp.size()));
  double mass_a = 0.0, mass_b = 0.0;
  for (std::int64_t p = 0; p < set.ranges[2]; ++p) {
    EXPECT_EQ(mp.material[p], p < set.ranges[1] ? 0 : 1);
    EXPECT_EQ(mp.id[p], p);
    (mp.material[p] == 0 ? mass_a : mass_b) += mp.mass[p];
  }
  // Box 3 x 1 m^2 at 1000 kg/m^3, less its overlap with the earlier-listed triangle (0.5 m^2,
  // below y = x - 2): sampling is exact but in the cells the diagonal cuts, so a cell's mass
  // (0.25 m^2) is the tolerance.
  EXPECT_NEAR(mass_a, 1000.0 * (3.0 - 0.5), 1000.0 * 0.25);
  EXPECT_NEAR(mass_b, 3000.0 * 2.0, 3000.0 * 0.25);  // the triangle's area is 2 m^2
}

TEST(Setup, BoxOfWholeCellsGetsExactlyKToTheDPointsPerCell) {
  Case c = two_body_case();
  c.bodies.erase(c.bodies.begin());
  const auto set = fill_bodies<2>(c, make_grid<2>(c));
  EXPECT_EQ(set.points.size(), 6u * 2u * 4u);  // 6 x 2 cells, 2x2 points each
  for (std::size_t p = 0; p < set.points.size(); ++p) {
    EXPECT_DOUBLE_EQ(set.points.volume[p], 0.25 / 4.0);
    EXPECT_DOUBLE_EQ(set.points.half_size[p][0], 0.125);
  }
}

TEST(Setup, MarksFixedAndRollerNodes) {
  Case c = two_body_case();
  c.boundaries.push_back({"base", {1, 0.0}, MechanicalCondition::fixed});
  c.boundaries.push_back({"left", {0, 0.0}, MechanicalCondition::roller});
  const auto grid = make_grid<2>(c);
  numerics::NodalState<2> nodes;
  nodes.resize(grid.n_nodes(), 1);
  mark_boundaries<2>(c, grid, nodes.fixed);
  for (std::int64_t i = 0; i < grid.n_nodes(); ++i) {
    const auto x = grid.node_position(i);
    std::uint8_t expected = 0;
    if (x[1] == 0.0) expected |= 3;
    if (x[0] == 0.0) expected |= 1;
    EXPECT_EQ(nodes.fixed[i], expected) << "node " << i;
  }
}

}  // namespace test_setup
}  // namespace unsatmpm

// The resource estimate (cycles/resources.hpp): its point counts against the points fill_bodies
// makes, its memory monotone in the case's size, and the refusal naming the key and its line.
#include <gtest/gtest.h>

#include <string>

#include "cycles/resources.hpp"
#include "cycles/setup.hpp"
#include "input/case_parser.hpp"

namespace unsatmpm {
namespace test_resources {

Case polygon_and_box_case(int dimension) {
  Case c;
  c.file = "<test>";
  c.name = "two";
  c.dimension = dimension;
  c.shape_function = ShapeFunctionKind::gimp;
  c.gravity.assign(dimension, 0.0);
  c.materials.push_back({"a", 1000.0, physics::LinearElastic::create(1e6, 0.2)});
  if (dimension == 2) {
    c.grid = {{0.0, 0.0}, {4.0, 2.0}, {8, 4}};
    c.bodies.push_back({"slope", 0, 3, PolygonGeometry{{{{0.3, 0.1}, {3.7, 0.2}, {1.1, 1.9}}}, {}},
                        std::vector<double>{}});
    c.bodies.push_back({"box", 0, 2, BoxGeometry{{0.5, 0.0}, {3.5, 1.5}}, std::vector<double>{}});
  } else {
    c.grid = {{0.0, 0.0, 0.0}, {4.0, 2.0, 1.0}, {8, 4, 2}};
    c.bodies.push_back({"slope", 0, 2,
                        PolygonGeometry{{{{0.3, 0.1}, {3.7, 0.2}, {1.1, 1.9}}}, {{0.0, 0.5}}},
                        std::vector<double>{}});
  }
  c.solver.end_time = 1.0;
  c.solver.damping = 0.0;
  return c;
}

template <int D>
double filled_points(const Case& c) {
  return static_cast<double>(fill_bodies<D>(c, make_grid<D>(c)).points.size());
}

TEST(Resources, CountsTheSamePointsAsTheBodiesGetWhereTheyDoNotOverlap) {
  Case c2 = polygon_and_box_case(2);
  c2.bodies.pop_back();  // the polygon alone: counted sample by sample
  EXPECT_EQ(estimate_resources(c2, 1).points, filled_points<2>(c2));
  EXPECT_TRUE(estimate_resources(c2, 1).points_exact);
  Case box = polygon_and_box_case(2);
  box.bodies.erase(box.bodies.begin());
  EXPECT_EQ(estimate_resources(box, 1).points, filled_points<2>(box));
  const Case c3 = polygon_and_box_case(3);
  EXPECT_EQ(estimate_resources(c3, 1).points, filled_points<3>(c3));
  EXPECT_EQ(estimate_resources(c3, 1).nodes, 9.0 * 5.0 * 3.0);
  // Overlapping bodies: the estimate bounds the points from above.
  const Case both = polygon_and_box_case(2);
  EXPECT_GE(estimate_resources(both, 1).points, filled_points<2>(both));
}

TEST(Resources, MemoryGrowsWithCellsPointsThreadsAndThePhases) {
  Case c = polygon_and_box_case(2);
  const double base = estimate_resources(c, 1).bytes;
  EXPECT_GT(estimate_resources(c, 2).bytes, base);
  Case finer = c;
  finer.grid.cells = {16, 8};
  EXPECT_GT(estimate_resources(finer, 1).bytes, base);
  Case denser = c;
  denser.bodies[1].points_per_cell = 4;
  EXPECT_GT(estimate_resources(denser, 1).bytes, base);
  c.phases = Phases::solid_liquid_gas;
  c.solver.cycle = Cycle::explicit_dynamic;
  const double explicit_cycle = estimate_resources(c, 1).bytes;
  EXPECT_GT(explicit_cycle, base);
  c.solver.cycle = Cycle::implicit_pressure;
  EXPECT_GT(estimate_resources(c, 1).bytes, explicit_cycle);
}

const char* const big_case = R"(name: big
dimension: 2
grid: {origin: [0, 0], size: [1, 1], cells: [100000, 100000]}
shape_function: linear
gravity: [0, -9.81]
materials:
  - {name: soil, density: 1800, model: linear_elastic, young_modulus: 1.0e7, poisson_ratio: 0.3}
bodies:
  - name: block
    material: soil
    points_per_cell: 2
    box: {min: [0, 0], max: [0.5, 0.5]}
solver: {end_time: 1, damping: 0}
output: {times: [0.5]}
)";

std::string refusal(const std::string& text, double limit) {
  const Case c = parse_case_text(text, "big.yaml");
  try {
    require_resources(c, InputNode::load_text(text, "big.yaml"), 1, limit);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(Resources, RefusesAGridWhoseNodesAloneExceedTheLimitAtGridCells) {
  // 1e10 nodes at 200 bytes: 2 TB.
  const std::string what = refusal(big_case, 1e12);
  EXPECT_NE(what.find("big.yaml:3:"), std::string::npos) << what;
  EXPECT_NE(what.find("grid.cells"), std::string::npos) << what;
  EXPECT_NE(what.find("--max-memory"), std::string::npos) << what;
}

TEST(Resources, RefusesTooManyPointsAtTheLargestBodysPointsPerCell) {
  std::string text = big_case;
  text.replace(text.find("[100000, 100000]"), 16, "[3000, 3000]");
  text.replace(text.find("points_per_cell: 2"), 18, "points_per_cell: 6");
  // 9e6 nodes (1.8 GB), 1500^2 cells of 36 points (57 GB): refused at 10 GB, at the body's key.
  const std::string what = refusal(text, 10e9);
  EXPECT_NE(what.find("big.yaml:11:"), std::string::npos) << what;
  EXPECT_NE(what.find("bodies[0].points_per_cell"), std::string::npos) << what;
  EXPECT_NE(what.find(" 81000000 material points"), std::string::npos) << what;
  EXPECT_EQ(refusal(text, 100e9), "");  // the override lets it through
}

TEST(Resources, RefusesABodyThinnerThanTheSampleSpacingAtItsEntry) {
  std::string text = big_case;
  text.replace(text.find("[100000, 100000]"), 16, "[10, 10]");
  text.replace(text.find("max: [0.5, 0.5]"), 15, "max: [0.5, 0.02]");  // samples at y = 0.025...
  const std::string what = refusal(text, 1e12);
  EXPECT_NE(what.find("big.yaml:9:"), std::string::npos) << what;
  EXPECT_NE(what.find("bodies[0]: body 'block' holds no material point"), std::string::npos)
      << what;
}

TEST(Resources, ABodyAllInsideAnEarlierOneIsNamed) {
  Case c = polygon_and_box_case(2);
  c.bodies[0].geometry = BoxGeometry{{0.0, 0.0}, {4.0, 2.0}};  // covers the box that follows
  try {
    fill_bodies<2>(c, make_grid<2>(c));
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("<test>: bodies[1]: body 'box' holds no material point"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace test_resources
}  // namespace unsatmpm

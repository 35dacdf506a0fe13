// TopRowPressures (cycles/top_row_pressures.hpp): a node's ponding pressure is the highest liquid
// pressure of the top-row points it carries, interpolated with their GIMP weights; a node that
// carries none keeps its own.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

#include "cycles/top_row_pressures.hpp"

namespace unsatmpm {
namespace {

// Cells of 0.25 m; two top-row points of half-size 1/16 m on either side of node 2 (x = 0.5): the
// one above reaches nodes 2 and 3 with weights 3/4 and 1/4 (node 3 beyond the body holds an
// eighth of a full node's volume), the one below nodes 1 and 2 with 1/4 and 3/4. Nodal liquid
// pressures 100 a [Pa] at node a.
TEST(TopRowPressures, ANodeTakesTheHighestOfItsTopPointsAndOtherwiseItsOwn) {
  const numerics::Grid<1> grid(numerics::Vec<1>(0.0), numerics::Vec<1>(0.25), {4});
  numerics::MaterialPoints<1> mp;
  mp.push_back(0, numerics::Vec<1>(0.5625), numerics::Vec<1>(0.0625), 1.0, 0.125);
  mp.push_back(0, numerics::Vec<1>(0.4375), numerics::Vec<1>(0.0625), 1.0, 0.125);
  const std::vector<std::pair<std::int64_t, double>> top_row = {{0, 1.0}, {1, 1.0}};
  TopRowPressures<1, numerics::GimpKernel> ponding;
  ponding.build(grid, mp, top_row);
  const auto nodal = [](std::int64_t a) { return 100.0 * static_cast<double>(a); };
  const double above = 0.75 * 200.0 + 0.25 * 300.0, below = 0.25 * 100.0 + 0.75 * 200.0;
  EXPECT_NEAR(ponding.at(3, 1e4, nodal), above, 1e-9);  // not its own 1e4
  EXPECT_NEAR(ponding.at(2, -1e4, nodal), std::max(above, below), 1e-9);
  EXPECT_NEAR(ponding.at(1, -1e4, nodal), below, 1e-9);
  EXPECT_EQ(ponding.at(0, -123.0, nodal), -123.0);
  EXPECT_EQ(ponding.at(4, 45.0, nodal), 45.0);
  // Built again without the point above: node 3 carries none and keeps its own.
  ponding.build(grid, mp, {{1, 1.0}});
  EXPECT_EQ(ponding.at(3, 1e4, nodal), 1e4);
  EXPECT_NEAR(ponding.at(2, -1e4, nodal), below, 1e-9);
}

}  // namespace
}  // namespace unsatmpm

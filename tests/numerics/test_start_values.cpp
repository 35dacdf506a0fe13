// The flow's nodal start values (numerics/pressure/nodal_projection.hpp): the first start fits
// them to the points' pressures (exact for a linear field, within the points' range where they
// lie on a line); a later start keeps the field the flow reached and fits only what the points
// depart from it (a steep front survives the restart, a new node takes the fit).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "numerics/pressure/pressure_system.hpp"
#include "tests/numerics/linear_soil.hpp"
#include "tests/numerics/pressure_column.hpp"

namespace unsatmpm::numerics {
namespace test_start_values {

using System = PressureSystem<2, LinearKernel>;

/// A linear field [Pa] over the column.
double linear(const Vec<2>& x) { return -3e4 + 2e4 * x[0] - 9.81e3 * x[1]; }

// The flow's start values: a weighted least-squares linear fit to the points around each node,
// exact for a linear field at every node, the edge nodes included (where the plain mean is
// biased by the one-sided support).
TEST(PressureSystem, StartValuesReproduceALinearField) {
  Column c(13);
  System sys(c.grid, {linear_soil(), linear_soil()}, MassBalance::full, Vec<2>(0.0, -9.81));
  const auto field = [](const Vec<2>& x) { return -3e4 + 2e4 * x[0] - 9.81e3 * x[1]; };
  for (std::size_t p = 0; p < c.fp.size(); ++p)
    c.fp.liquid_pressure[p] = field(c.mp.position[p]), c.fp.gas_pressure[p] = 0.0;
  prepare(sys, c);
  std::vector<double> y0(sys.n_unknowns());
  std::array<std::vector<double>, 2> nodal;
  sys.start(0.0, c.fp, y0, nodal, System::Prescribed::switch_on);
  int checked = 0;
  for (std::int64_t i = 0; i < c.grid.n_nodes(); ++i) {
    if (sys.unknown(liquid_phase, i) < 0) continue;
    EXPECT_NEAR(nodal[0][i], field(c.grid.node_position(i)), 1e-6) << "node " << i;
    ++checked;
  }
  EXPECT_EQ(checked, 20);  // every node of the 4 x 3 cells, corners and edges included
}

// Points nearly on a line (one column, its x offsets within 0.01 m in 0.5 m cells) cannot carry
// a fit across the line: the slope there is noise, and extrapolated to the nodes it made a start
// value far outside the points' pressures (3.59 MPa against -71 to +8 kPa on the embankment's
// crest). The nodes take the points' mean instead, within their range.
TEST(PressureSystem, StartValuesOfAPointLineStayWithinItsPressures) {
  const Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(0.5, 0.5), {2, 3});
  MaterialPoints<2> mp;
  FluidPoints<2> fp;
  std::vector<double> pressures;
  for (int k = 0; k < 14; ++k) {
    const double y = 0.1 + 0.1 * k;
    mp.push_back(0, Vec<2>(0.25 + 0.01 * std::sin(7.0 * y), y), Vec<2>(0.125, 0.125), 100.0,
                 0.0625);
    pressures.push_back(-7e4 + 5e4 * y * y);  // not linear in y: the fit's residual
  }
  fp.resize(mp.size());
  for (std::size_t p = 0; p < mp.size(); ++p)
    fp.porosity[p] = 0.35, fp.liquid_pressure[p] = pressures[p], fp.gas_pressure[p] = 0.0;
  System sys(grid, {linear_soil()}, MassBalance::full, Vec<2>(0.0, -9.81));
  const std::vector<std::int64_t> ranges{0, static_cast<std::int64_t>(mp.size())};
  sys.prepare(mp, fp, ranges);
  std::vector<double> y0(sys.n_unknowns());
  std::array<std::vector<double>, 2> nodal;
  sys.start(0.0, fp, y0, nodal, System::Prescribed::switch_on);
  const auto [lo, hi] = std::minmax_element(pressures.begin(), pressures.end());
  int checked = 0;
  for (std::int64_t i = 0; i < grid.n_nodes(); ++i) {
    if (sys.unknown(liquid_phase, i) < 0 || grid.node_ijk(i)[0] == 2) continue;  // x = 1: unused
    EXPECT_GE(nodal[0][i], *lo) << "node " << i;
    EXPECT_LE(nodal[0][i], *hi) << "node " << i;
    ++checked;
  }
  EXPECT_EQ(checked, 8);  // x = 0 and x = 0.5, y = 0 ... 1.5
}

/// A wetting front one cell wide: nodes at x <= 0.5 m at -100 kPa, at x >= 1 m at -1 kPa
/// (liquid); the gas at 2 kPa.
std::array<std::vector<double>, 2> front(const Grid<2>& grid) {
  std::array<std::vector<double>, 2> r{std::vector<double>(grid.n_nodes()),
                                       std::vector<double>(grid.n_nodes(), 2e3)};
  for (std::int64_t i = 0; i < grid.n_nodes(); ++i)
    r[0][i] = grid.node_position(i)[0] <= 0.5 ? -1e5 : -1e3;
  return r;
}

/// The points' pressures: the nodal field `r` at the points plus the linear field (liquid) and
/// half of it (gas).
void set_points(System& sys, Column& c, const std::array<std::vector<double>, 2>& r) {
  std::array<std::vector<double>, 2> at;
  sys.at_points(r, at);
  for (std::size_t p = 0; p < c.fp.size(); ++p) {
    c.fp.liquid_pressure[p] = at[0][p] + linear(c.mp.position[p]);
    c.fp.gas_pressure[p] = at[1][p] + 0.5 * linear(c.mp.position[p]);
    c.fp.saturation[p] = 0.5;
  }
}

// The points carry the reached front plus a linear change (what the mechanics' undrained
// response adds, smooth): fitted afresh, the front's nodes move by kilopascals (the smoothing a
// restart used to apply at every interval); started from the reached field, every node holds the
// front plus the change, to round-off.
TEST(PressureSystem, ALaterStartKeepsTheFrontTheFlowReached) {
  Column c(13);
  System sys(c.grid, {linear_soil(), linear_soil()}, MassBalance::full, Vec<2>(0.0, -9.81));
  prepare(sys, c);
  prepare(sys, c);  // the nodes of the integration before: the same
  const auto reached = front(c.grid);
  set_points(sys, c, reached);
  const auto expected = [&](int a, std::int64_t i) {
    return reached[a][i] + (a == 0 ? 1.0 : 0.5) * linear(c.grid.node_position(i));
  };
  std::vector<double> y0(sys.n_unknowns());
  std::array<std::vector<double>, 2> fitted, restarted;
  sys.start(0.0, c.fp, y0, fitted, System::Prescribed::continuing);
  double worst_fit = 0.0;
  for (std::int64_t i = 0; i < c.grid.n_nodes(); ++i)
    worst_fit = std::max(worst_fit, std::abs(fitted[0][i] - expected(0, i)));
  EXPECT_GT(worst_fit, 1e3);  // the fit smooths the front
  sys.start(0.0, c.fp, y0, restarted, System::Prescribed::continuing, System::JumpBase::points,
            System::StartFrom::reached, &reached);
  int checked = 0;
  for (std::int64_t i = 0; i < c.grid.n_nodes(); ++i)
    for (int a = 0; a < 2; ++a) {
      if (sys.unknown(a, i) < 0) continue;
      EXPECT_NEAR(restarted[a][i], expected(a, i), 1e-6) << "node " << i << " fluid " << a;
      EXPECT_EQ(y0[sys.unknown(a, i)], restarted[a][i]);
      ++checked;
    }
  EXPECT_EQ(checked, 40);
}

// Nodes that were not active in the integration before have no reached value: they take the fit
// of the points, and whatever the reached field holds there is not used. With a linear field at
// the points and the reached field equal to it at the old nodes, every node starts on the field.
TEST(PressureSystem, ALaterStartFitsTheNodesNewlyActive) {
  Column c(13);
  System sys(c.grid, {linear_soil(), linear_soil()}, MassBalance::full, Vec<2>(0.0, -9.81));
  Column left = c;  // the points of the left two columns of cells only
  left.mp = MaterialPoints<2>{};
  for (std::size_t p = 0; p < c.mp.size(); ++p)
    if (c.mp.position[p][0] < 1.0)
      left.mp.push_back(0, c.mp.position[p], c.mp.half_size[p], c.mp.mass[p], c.mp.volume[p]);
  left.fp.resize(left.mp.size());
  left.div_vs.assign(left.mp.size(), 0.0);
  left.ranges = {0, static_cast<std::int64_t>(left.mp.size()),
                 static_cast<std::int64_t>(left.mp.size())};
  for (std::size_t p = 0; p < left.mp.size(); ++p) left.fp.porosity[p] = 0.35;
  prepare(sys, left);
  std::vector<std::uint8_t> old(c.grid.n_nodes());
  for (std::int64_t i = 0; i < c.grid.n_nodes(); ++i) old[i] = sys.unknown(liquid_phase, i) >= 0;
  prepare(sys, c);
  std::array<std::vector<double>, 2> reached{std::vector<double>(c.grid.n_nodes(), 9e9),
                                             std::vector<double>(c.grid.n_nodes(), 9e9)};
  int newly_active = 0;
  for (std::int64_t i = 0; i < c.grid.n_nodes(); ++i) {
    if (old[i])
      reached[0][i] = linear(c.grid.node_position(i)), reached[1][i] = 1e3;
    else
      newly_active += sys.unknown(liquid_phase, i) >= 0;
  }
  EXPECT_EQ(newly_active, 8);  // x = 1.5 and 2 m
  for (std::size_t p = 0; p < c.fp.size(); ++p)
    c.fp.liquid_pressure[p] = linear(c.mp.position[p]), c.fp.gas_pressure[p] = 1e3,
    c.fp.saturation[p] = 0.5;
  std::vector<double> y0(sys.n_unknowns());
  std::array<std::vector<double>, 2> nodal;
  sys.start(0.0, c.fp, y0, nodal, System::Prescribed::continuing, System::JumpBase::points,
            System::StartFrom::reached, &reached);
  for (std::int64_t i = 0; i < c.grid.n_nodes(); ++i) {
    if (sys.unknown(liquid_phase, i) < 0) continue;
    EXPECT_NEAR(nodal[0][i], linear(c.grid.node_position(i)), 1e-6) << "node " << i;
    EXPECT_NEAR(nodal[1][i], 1e3, 1e-6) << "node " << i;
  }
}

// Starting from a nodal field needs one, of the grid's size.
TEST(PressureSystem, AStartFromANodalFieldNeedsOne) {
  Column c(13);
  System sys(c.grid, {linear_soil(), linear_soil()}, MassBalance::full, Vec<2>(0.0, -9.81));
  prepare(sys, c);
  std::vector<double> y0(sys.n_unknowns());
  std::array<std::vector<double>, 2> nodal, short_field{std::vector<double>(3), {}};
  for (const auto from : {System::StartFrom::given, System::StartFrom::reached}) {
    EXPECT_THROW(sys.start(0.0, c.fp, y0, nodal, System::Prescribed::continuing,
                           System::JumpBase::points, from),
                 std::invalid_argument);
    EXPECT_THROW(sys.start(0.0, c.fp, y0, nodal, System::Prescribed::continuing,
                           System::JumpBase::points, from, &short_field),
                 std::invalid_argument);
  }
  // Starting from the reached field needs the nodes of the integration before, one per node.
  std::array<std::vector<double>, 2> field{std::vector<double>(c.grid.n_nodes()),
                                           std::vector<double>(c.grid.n_nodes())};
  const auto start = [&](StartFrom from) {
    start_values<2, LinearKernel>(from, c.grid, sys.quadrature(), c.fp, &field,
                                  std::vector<std::uint8_t>(3), nodal);
  };
  EXPECT_THROW(start(StartFrom::reached), std::invalid_argument);
  EXPECT_NO_THROW(start(StartFrom::given));  // needs no nodes of the integration before
}

}  // namespace test_start_values
}  // namespace unsatmpm::numerics

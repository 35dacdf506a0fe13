// The flow's relative permeabilities taken from the stencil nodes (solver.implicit.
// relative_permeability: nodes, numerics/pressure/nodal_permeability.hpp): the analytic Jacobian
// against central finite differences of the right-hand side in both forms; the nodes' weights
// give a uniform field the point's own value and give a point across a wetting front the wet
// node's share; under a wet top a dry column's pressures rise at least twice as fast with the
// option as with the laws at the points.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "numerics/pressure/nodal_permeability.hpp"
#include "numerics/pressure/pressure_system.hpp"
#include "tests/numerics/linear_soil.hpp"
#include "tests/numerics/pressure_column.hpp"

namespace unsatmpm::numerics {
namespace test_nodal_permeability {

using System = PressureSystem<2, LinearKernel>;

/// The column's top row held (liquid and gas), as tests/numerics/test_pressure_system.cpp does.
void hold_top(System& sys, const Column& c, double top_liquid) {
  std::vector<std::uint8_t> top(c.grid.n_nodes(), 0);
  for (std::int64_t i = 0; i < c.grid.n_nodes(); ++i)
    if (c.grid.node_ijk(i)[1] == 3) top[i] = 1;
  sys.set_prescribed(liquid_phase, top);
  sys.set_prescribed(gas_phase, top);
  sys.set_prescription([top_liquid](double, NodalPrescription& np) {
    for (std::size_t i = 0; i < np.prescribed[0].size(); ++i) {
      np.value[0][i] = top_liquid, np.rate[0][i] = 0.0;
      np.value[1][i] = 0.0, np.rate[1][i] = 0.0;
    }
  });
}

/// Unknowns: P_g = 2e3 (1 + 0.3 sin), P_l = P_g - s, s from s_low at the bottom to s_high at
/// y = 1.5 m, and a fifth of that span more across x: every free node's suction far from 0.
std::vector<double> state(const System& sys, const Grid<2>& grid, double s_low, double s_high) {
  std::vector<double> y(sys.n_unknowns(), 0.0);
  for (std::int64_t k = 0; k < sys.n_pressure_unknowns(); ++k) {
    const auto [node, fluid] = sys.unknown_location(k);
    const Vec<2> x = grid.node_position(node);
    const double pg = 2e3 * (1.0 + 0.3 * std::sin(5.0 * x[0] + 3.0 * x[1]));
    const double s = s_low + (s_high - s_low) * x[1] / 1.5 + 0.2 * (s_high - s_low) * x[0] / 2.0;
    y[k] = fluid == gas_phase ? pg : pg - s;
  }
  return y;
}

// The finite differences' error as in test_pressure_system.cpp (1 Pa steps, relative to each
// row's largest entry); leaving out the nodes' k_r derivative fails it (measured: errors of 0.011
// to 0.88 of a row's largest entry over the four cases).
constexpr double fd_tolerance = 1e-6;

TEST(NodalPermeability, JacobianMatchesFiniteDifferences) {
  for (const MassBalance form : {MassBalance::full, MassBalance::simplified})
    for (const auto [s_low, s_high] : {std::array{2e4, 1.5e5}, std::array{3e3, 4e5}}) {
      const Column c(5);
      System sys(c.grid, {van_genuchten_soil(), linear_soil()}, form, Vec<2>(0.0, -9.81));
      sys.set_nodal_permeability(true);
      hold_top(sys, c, -1e3);
      prepare(sys, c);
      const auto y = state(sys, c.grid, s_low, s_high);
      EXPECT_LT(jacobian_error(sys, y, 0.3), fd_tolerance)
          << (form == MassBalance::full ? "full" : "simplified") << " s " << s_low;
    }
}

TEST(NodalPermeability, UniformFieldGivesThePointsOwnValueAndAFrontTheWetNodesShare) {
  const Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(1.0, 1.0), {2, 2});
  const std::vector<physics::HydraulicModel> models{van_genuchten_soil()};
  const physics::HydraulicModel& hm = models[0];
  const auto all = [](std::int64_t) { return true; };
  NodalPermeability laws;
  PointStencil<2, LinearKernel> st;
  st.evaluate(grid, Vec<2>(0.7, 0.3), Vec<2>(0.25, 0.25));
  std::array<std::vector<double>, 2> p{std::vector<double>(9, -5e4), std::vector<double>(9, 0.0)};
  laws.fill(models, p, all);
  std::array<double, 2> k = laws.at(0, st);
  const double se = hm.effective_saturation(5e4);
  EXPECT_NEAR(k[0], hm.liquid_relative_permeability_value(se), 1e-14);
  EXPECT_NEAR(k[1], hm.gas_relative_permeability_value(se), 1e-14);
  // A front: the nodes on x = 1 wet (zero suction), those on x = 0 at 800 kPa. The point at
  // x = 0.3 of the cell takes 0.3 of the wet conductance; the law at its interpolated suction
  // (560 kPa) gives orders of magnitude less.
  st.evaluate(grid, Vec<2>(0.3, 0.5), Vec<2>(0.25, 0.25));
  for (std::int64_t i = 0; i < 9; ++i) p[0][i] = grid.node_position(i)[0] > 0.5 ? 0.0 : -8e5;
  laws.fill(models, p, all);
  k = laws.at(0, st);
  double wet = 0.0, suction = 0.0;
  for (int a = 0; a < st.n; ++a) {
    const bool is_wet = p[0][st.node[a]] == 0.0;
    wet += is_wet ? st.w[a] : 0.0;
    suction += st.w[a] * (is_wet ? 0.0 : 8e5);
  }
  EXPECT_NEAR(wet, 0.3, 1e-12);
  EXPECT_GE(k[0], wet * hm.liquid_relative_permeability_value(1.0));
  EXPECT_GT(k[0], 100.0 * hm.liquid_relative_permeability_value(hm.effective_saturation(suction)));
}

// A dry column (suction 300 kPa) under a top row held at zero suction: the liquid pressures of
// the row under the held one rise faster with the nodes' permeabilities (at least twice; the
// cell under the wet row holds points whose interpolated suction is dry, while their stencils
// reach the wet row).
TEST(NodalPermeability, DryColumnWetsFasterUnderAWetTop) {
  std::array<double, 2> rate{};
  for (const bool from_nodes : {false, true}) {
    const Column c(2);
    System sys(c.grid, {van_genuchten_soil(), van_genuchten_soil()}, MassBalance::full,
               Vec<2>(0.0, -9.81));
    sys.set_nodal_permeability(from_nodes);
    hold_top(sys, c, 0.0);
    prepare(sys, c);
    std::vector<double> y(sys.n_unknowns(), 0.0);  // P_g = 0, P_l = -300 kPa
    for (std::int64_t k = 0; k < sys.n_pressure_unknowns(); ++k)
      if (sys.unknown_location(k).second == liquid_phase) y[k] = -3e5;
    std::vector<double> f(sys.n_unknowns());
    ASSERT_EQ(sys.rhs(0.0, y, f), 0);
    double sum = 0.0;
    for (std::int64_t k = 0; k < sys.n_pressure_unknowns(); ++k) {
      const auto [node, fluid] = sys.unknown_location(k);
      if (fluid == liquid_phase && c.grid.node_ijk(node)[1] == 2)
        sum += f[k];  // dP_l/dt of the row under the held one
    }
    rate[from_nodes] = sum;
  }
  EXPECT_GT(rate[0], 0.0);
  EXPECT_GT(rate[1], 2.0 * rate[0]);
}

}  // namespace test_nodal_permeability
}  // namespace unsatmpm::numerics

// The main cycle's undrained update with an occluded gas (physics/retention.hpp, OccludedGas): a
// flat law compresses the gas with the liquid, a law giving way takes the compression at the
// gas's own stiffness (Boyle's law), and where the gas has given way to the water altogether the
// nodes around it hold its pressure (numerics::nodal_pressure_increments, HoldGasFree).
#include <gtest/gtest.h>

#include <cmath>

#include "cycles/undrained.hpp"
#include "tests/cycles/undrained_block.hpp"

namespace unsatmpm {
namespace test_undrained {

TEST(Undrained, AnOccludedGasIsCompressedWithTheLiquidAndKeepsItsMass) {
  // A law with S(0) = 0.95: at P_l > P_g the pores hold 5 % gas at its own pressure. Compressed
  // with both fluids free, each keeps its mass (nothing supplied), the liquid's pressure rises by
  // its own stiffness over its share of the pores and the gas's by its own: the fluids decouple.
  physics::HydraulicModel hm = soil();
  hm.retention = physics::VanGenuchten::create(2e4, 0.4, 0.0, 0.95);
  Block b({{1e4, 0.0}, {1e4, 0.0}, {1e4, 0.0}, {1e4, 0.0}}, hm);
  const auto before = fluid_masses<1>(b.points.points, b.fluids);
  const double eps = 1e-5;  // uniform compression: the pores shrink by eps / n
  const UndrainedReport r = compress_closed(b, hm, eps);
  ASSERT_EQ(r.first_bad, -1);
  EXPECT_EQ(r.supplied[0], 0.0);
  EXPECT_EQ(r.supplied[1], 0.0);
  const auto after = fluid_masses<1>(b.points.points, b.fluids);
  EXPECT_NEAR(after[0], before[0], 1e-12 * before[0]);
  EXPECT_NEAR(after[1], before[1], 1e-12 * before[1]);
  const double shrink = -std::log1p(-eps / 0.3);  // ln of the pores' contraction
  const double gas_absolute = 101325.0;           // IdealGas::create(1.2): 1.2 kg/m^3 at P_g = 0
  for (std::size_t p = 0; p < 4; ++p) {
    EXPECT_NEAR(b.fluids.saturation[p], 0.95, 1e-12);
    EXPECT_NEAR(b.fluids.liquid_pressure[p] - 1e4, 2e9 * shrink, 1e-3 * 2e9 * shrink);
    EXPECT_NEAR(b.fluids.gas_pressure[p], gas_absolute * std::expm1(shrink),
                1e-3 * gas_absolute * shrink);
  }
}

TEST(Undrained, AnOccludedGasGivingWayTakesTheCompressionAtItsOwnStiffness) {
  // The same block with the occluded gas giving way over 10 Pa (retention.hpp, OccludedGas).
  // Small against the gas's absolute pressure, the bubbles are then at the water's pressure
  // within a pascal, and the pores' fluids are compressed as one: the pressure P* at which
  // M_l / rho_l(P*) + M_g / rho_g(P*) fills the shrunk pores (Boyle's law for the gas), reached
  // here at 1e-3 of volume strain where the flat law drives the water to 6.7 MPa. The tangent
  // stiffness at s = 0 is Wood's, 1 / (n (S / K_l + (1 - S) / K_g)) with K_g the gas's absolute
  // pressure, within the scale's share of K_g / (1 - S).
  physics::HydraulicModel hm = soil();
  constexpr double scale = 10.0, n = 0.3, s0 = 0.95, k_l = 2e9, atmosphere = 101325.0;
  hm.retention = physics::VanGenuchten::create(2e4, 0.4, 0.0, s0, scale);
  const double wood = 1.0 / (n * (s0 / k_l + (1.0 - s0) / atmosphere));
  EXPECT_NEAR(undrained_stiffness(hm, n, 0.0, 0.0, false), wood, 1e-3 * wood);
  EXPECT_NEAR(undrained_stiffness(hm, n, 0.0, 0.0, false),
              stiffness_by_differences(hm, n, 0.0, 0.0, false), 1e-3 * wood);
  Block b({{0.0, 0.0}, {0.0, 0.0}, {0.0, 0.0}, {0.0, 0.0}}, hm);
  const auto before = fluid_masses<1>(b.points.points, b.fluids);
  const double eps = 1e-3;
  const UndrainedReport r = compress_closed(b, hm, eps);
  ASSERT_EQ(r.first_bad, -1);
  EXPECT_EQ(r.supplied[1], 0.0);
  // The update keeps the masses; the state's are within what undrained_pressure_tolerance moves
  // them by, the gas's at its content's slope n rho_g (1 - S0) / scale per pascal.
  const auto after = fluid_masses<1>(b.points.points, b.fluids);
  const double pores_volume = n * 4 * 0.25;
  EXPECT_NEAR(after[0], before[0], 1e-12 * before[0]);
  EXPECT_NEAR(after[1], before[1],
              pores_volume * 1.2 * (1.0 - s0) / scale * undrained_pressure_tolerance);
  // P* per unit volume of pores before: S0 rho_l(0) / rho_l(P) + (1 - S0) rho_g(0) / rho_g(P) =
  // the pores' new share, (n - eps) / n, by bisection.
  const double pores = (n - eps) / n;
  double lo = 0.0, hi = 1e6;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    const double filled = s0 * hm.liquid_density(0.0) / hm.liquid_density(mid) +
                          (1.0 - s0) * hm.gas_density(0.0) / hm.gas_density(mid);
    (filled > pores ? lo : hi) = mid;
  }
  const double p_star = 0.5 * (lo + hi);
  ASSERT_GT(p_star, 5e3);  // about eps / n / ((1 - S0) / P_atm): 6.8 kPa
  for (std::size_t p = 0; p < 4; ++p) {
    EXPECT_NEAR(b.fluids.liquid_pressure[p], p_star, 1.0);
    EXPECT_NEAR(b.fluids.gas_pressure[p], p_star, 1.0);
    EXPECT_GT(b.fluids.saturation[p], s0);
  }
}

TEST(Undrained, WhereTheGasHasGivenWayTheNodesHoldItsPressureAndSupplyTheFlowsGas) {
  // The give's block with the water 2 kPa above the gas: S_g = 0.05 exp(-20) = 1e-10, far below
  // physics::gas_free_saturation, but no node held (the flow found gas there at its interval's
  // start). The flow's share asks each point for 1e-6 kg of gas, which its 1e-10 of gas cannot
  // give: on the nodes' gas storage (about 1e-13 kg/Pa) that was some -1e7 Pa in one update,
  // below vacuum, and the update failed. The nodes free of gas now hold P_g, and the gas the share
  // asked is supplied (counted), so the masses close: the points keep their gas, and the supply
  // equals what the flow took.
  physics::HydraulicModel hm = soil();
  hm.retention = physics::VanGenuchten::create(2e4, 0.4, 0.0, 0.95, 100.0);
  Block b({{2e3, 0.0}, {2e3, 0.0}, {2e3, 0.0}, {2e3, 0.0}}, hm);
  ASSERT_LT(1.0 - b.fluids.saturation[0], 1e-9);
  const numerics::Grid<1> grid(numerics::Vec<1>(0.0), numerics::Vec<1>(0.25), {4});
  const std::vector<physics::HydraulicModel> models{hm};
  UndrainedPoints u;
  begin_undrained_interval<1>(grid, b.points.points, b.fluids, models, b.points.ranges, 1, u);
  for (auto& f : u.held) f.assign(grid.n_nodes(), 0);
  constexpr double taken = 1e-6;  // [kg per point]
  for (auto& m : u.flow_mass[1]) m = -taken;
  const auto before = fluid_masses<1>(b.points.points, b.fluids);
  const UndrainedReport r = undrained_update<1, numerics::LinearKernel>(
      grid, b.points.points, models, {1.35e7}, b.points.ranges, 1.0, 1, b.fluids, u);
  ASSERT_EQ(r.first_bad, -1);
  for (std::size_t p = 0; p < 4; ++p) {
    EXPECT_EQ(b.fluids.gas_pressure[p], 0.0) << p;
    EXPECT_NEAR(b.fluids.liquid_pressure[p], 2e3, 1e-6) << p;
  }
  EXPECT_NEAR(r.supplied[1], 4.0 * taken, 1e-12 * taken);
  const auto after = fluid_masses<1>(b.points.points, b.fluids);
  EXPECT_NEAR(after[1], before[1] - 4.0 * taken + r.supplied[1], 1e-12 * taken);
  EXPECT_NEAR(after[0], before[0], 1e-12 * before[0]);
}

}  // namespace test_undrained
}  // namespace unsatmpm

// physics::pressures_from_contents: the inverse of the fluid contents, for each retention law,
// from near and far starts, with the gas held and free, and through saturation.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "physics/fluid_contents.hpp"

namespace unsatmpm::physics {
namespace test_fluid_contents {

HydraulicModel soil(RetentionCurve retention, double k_l = 2e9) {
  return {CompressibleFluid::create(1000.0, 0.0, k_l),
          IdealGas::create(1.2),
          retention,
          ConstantRelPerm{},
          ConstantRelPerm{},
          2700.0,
          1e-11,
          1e-3,
          1.8e-5};
}

std::vector<HydraulicModel> soils() {
  return {soil(LinearRetention::create(1e-6, 0.0)),
          soil(VanGenuchten::create(2e4, 0.4, 0.05, 0.95)),
          soil(VanGenuchten::create(2e4, 0.4, 0.0, 1.0), 1e8),
          soil(TabulatedRetention::create({{0, 1}, {500, 0.9999}, {5e3, 0.98}, {2e4, 0.6}}))};
}

TEST(FluidContents, RecoverThePressuresOfTheirContentsWithBothFluidsFree) {
  for (const HydraulicModel& hm : soils())
    for (const auto& [pl, pg] : {std::pair{-5e4, 0.0}, {-2e3, 1e3}, {-8e4, -3e4}, {1e4, 2e4}}) {
      const auto [cl, cg] = fluid_contents(hm, pl, pg);
      for (const double shift : {1.0, 1e3, 3e4}) {  // near and far starts
        double x = pl + shift, y = pg - 0.5 * shift;
        const int it = pressures_from_contents(hm, cl, cg, false, x, y);
        ASSERT_GE(it, 0) << "P_l " << pl << " P_g " << pg << " shift " << shift;
        const auto [cl2, cg2] = fluid_contents(hm, x, y);
        EXPECT_LE(std::abs(cl2 - cl), content_tolerance * hm.liquid_density(x));
        EXPECT_LE(std::abs(cg2 - cg), content_tolerance * hm.gas_density(y));
        EXPECT_NEAR(x, pl, 1e-3 * std::max(1.0, std::abs(pl)));
        EXPECT_NEAR(y, pg, 1e-3 * std::max(1.0, std::abs(pg)));
      }
    }
}

// With a pressure tolerance the answer is within it of the exact pressures (the Newton step
// estimates the error to second order: a factor 2 is kept for that), and a start already that
// close stands without a second evaluation of the laws (0 iterations), with both fluids free
// and with the gas held; far starts still iterate.
TEST(FluidContents, APressureToleranceStopsWithinItOfTheExactPressures) {
  constexpr double tol = 1e-3;
  for (const HydraulicModel& hm : soils())
    for (const auto& [pl, pg] : {std::pair{-5e4, 0.0}, {-2e3, 1e3}, {1e4, 2e4}})
      for (const bool held : {false, true}) {
        const auto [cl, cg] = fluid_contents(hm, pl, pg);
        for (const double shift : {0.3 * tol, 1.0, 1e3}) {
          double x = pl + shift, y = held ? pg : pg - 0.5 * shift;
          const int it = pressures_from_contents(hm, cl, cg, held, x, y, nullptr, tol);
          ASSERT_GE(it, 0) << "P_l " << pl << " P_g " << pg << " shift " << shift;
          EXPECT_NEAR(x, pl, 2.0 * tol) << "P_l " << pl << " P_g " << pg << " shift " << shift;
          EXPECT_NEAR(y, pg, 2.0 * tol);
          if (shift < tol) {
            EXPECT_EQ(it, 0);
          } else {
            EXPECT_GT(it, 0);
          }
        }
      }
}

TEST(FluidContents, WithAnOccludedGasRecoverLiquidPressuresAboveTheGas) {
  // A law whose maximum saturation leaves gas in the pores (S(0) < 1): at s <= 0 the fluids
  // decouple, S = S(0), and contents whose liquid is compressed past S(0) rho_l(P_g) have P_l >
  // P_g. Both fluids' contents must be matched there, from starts on either side of s = 0 (a
  // positive-suction start is where the main cycle's sub-steps come from), without holding the gas.
  const std::vector<HydraulicModel> occluded = {
      soil(VanGenuchten::create(2e4, 0.4, 0.05, 0.95)),
      soil(VanGenuchten::create(1e6, 0.3, 0.0, 0.95)),
      soil(TabulatedRetention::create({{0, 0.9}, {500, 0.89}, {5e3, 0.8}, {2e4, 0.5}}))};
  for (const HydraulicModel& hm : occluded)
    for (const auto& [pl, pg] : {std::pair{6.5e5, 0.0}, {2e4, 1e4}, {1e3, 0.0}, {-5e3, -6e3}}) {
      const auto [cl, cg] = fluid_contents(hm, pl, pg);
      for (const auto& [x0, y0] : {std::pair{pg - 1.0, pg}, {pg - 5e3, pg + 100.0}, {pl, pg}}) {
        double x = x0, y = y0;
        const int it = pressures_from_contents(hm, cl, cg, false, x, y);
        ASSERT_GE(it, 0) << "P_l " << pl << " P_g " << pg << " start " << x0 << " " << y0;
        EXPECT_LE(it, 20);
        const auto [cl2, cg2] = fluid_contents(hm, x, y);
        EXPECT_LE(std::abs(cl2 - cl), content_tolerance * hm.liquid_density(x));
        EXPECT_LE(std::abs(cg2 - cg), content_tolerance * hm.gas_density(y));
        EXPECT_NEAR(x, pl, 1e-3 * std::max(1.0, std::abs(pl)));
        EXPECT_NEAR(y, pg, 1e-3 * std::max(1.0, std::abs(pg)));
      }
    }
}

TEST(FluidContents, WithAnOccludedGasGivingWayRecoverThePressures) {
  // The occluded gas gives way over 1 kPa or 10 Pa (retention.hpp, OccludedGas): S rises above
  // S(0) where the liquid is pressed above the gas. Contents from states on both sides of s = 0
  // are matched from starts on either side, without holding the gas.
  for (const double scale : {1e3, 10.0})
    for (const HydraulicModel& hm : {soil(VanGenuchten::create(2e4, 0.4, 0.05, 0.95, scale)),
                                     soil(VanGenuchten::create(4e5, 0.5, 0.0, 0.95, scale), 1e8)})
      // Liquid above the gas by 0.1 to 5 scales (at 5, S_g = 3.4e-4, near the gas-free
      // threshold 1e-4 below which the cycles hold the gas), and unsaturated states.
      for (const auto& [pl, pg] : {std::pair{2e4, 2e4 - 5.0 * scale},
                                   {3.0 * scale, 0.0},
                                   {1e3, 1e3 - 0.1 * scale},
                                   {-5e3, 0.0},
                                   {-1e4, -6e3}}) {
        const auto [cl, cg] = fluid_contents(hm, pl, pg);
        for (const auto& [x0, y0] : {std::pair{pg - 1.0, pg}, {pg - 5e3, pg + 100.0}, {pl, pg}}) {
          double x = x0, y = y0;
          const int it = pressures_from_contents(hm, cl, cg, false, x, y);
          ASSERT_GE(it, 0) << "P_l " << pl << " P_g " << pg << " start " << x0 << " " << y0;
          const auto [cl2, cg2] = fluid_contents(hm, x, y);
          EXPECT_LE(std::abs(cl2 - cl), content_tolerance * hm.liquid_density(x));
          EXPECT_LE(std::abs(cg2 - cg), content_tolerance * hm.gas_density(y));
          EXPECT_NEAR(x, pl, 1e-3 * std::max(1.0, std::abs(pl)));
          EXPECT_NEAR(y, pg, 1e-3 * std::max(1.0, std::abs(pg)));
        }
      }
}

TEST(FluidContents, WithTheGasHeldMatchTheLiquidAloneAcrossSaturation) {
  for (const HydraulicModel& hm : soils())
    for (const double pl : {2e4, 0.0, -300.0, -4e4}) {  // saturated and not, P_g held at 0
      const double cl = fluid_contents(hm, pl, 0.0).first;
      for (const double start : {pl + 5e4, pl - 5e4, pl}) {
        double x = start, y = 0.0;
        ASSERT_GE(pressures_from_contents(hm, cl, 123.0, true, x, y), 0) << pl << " " << start;
        EXPECT_EQ(y, 0.0);
        EXPECT_LE(std::abs(fluid_contents(hm, x, 0.0).first - cl),
                  content_tolerance * hm.liquid_density(x));
      }
    }
}

TEST(FluidContents, CompressingSaturatedWaterRaisesItsPressureByTheBulkModulus) {
  // A saturated pore volume shrinking by 1e-6 with its water kept: dP = K_l ln(1 / (1 - 1e-6)).
  const HydraulicModel hm = soil(LinearRetention::create(1e-6, 0.0));
  const double cl = fluid_contents(hm, 0.0, 0.0).first / (1.0 - 1e-6);
  double x = 0.0, y = 0.0;
  ASSERT_GE(pressures_from_contents(hm, cl, 0.0, true, x, y), 0);
  EXPECT_NEAR(x, 2e9 * -std::log1p(-1e-6), 1e-3);
}

TEST(FluidContents, TheOneEvaluationStateEqualsTheLawsTakenOneByOne) {
  // HydraulicModel::state, and the storage from it, must be the separate laws' values bit for
  // bit (the main cycle's results do not depend on which is called), for each retention law,
  // both gas laws, saturated and unsaturated, across the van Genuchten kink x = 1.
  std::vector<HydraulicModel> models = soils();
  HydraulicModel bulk_gas = models[1];
  bulk_gas.gas = CompressibleFluid::create(1.0, 0.0, 1e4);
  models.push_back(bulk_gas);
  for (const HydraulicModel& hm : models)
    for (const double pl : {-4e5, -2.5e4, -2e4, -1.9e4, -300.0, 0.0, 5e3})
      for (const double pg : {0.0, 2e3}) {
        const LocalFluidState f = hm.state(pl, pg);
        const double s = suction(pl, pg);
        EXPECT_EQ(f.s_l, hm.saturation(s)) << pl << " " << pg;
        EXPECT_EQ(f.ds, hm.d_saturation(s)) << pl << " " << pg;
        EXPECT_EQ(f.se, hm.effective_saturation(s)) << pl << " " << pg;
        EXPECT_EQ(f.rho_l, hm.liquid_density(pl));
        EXPECT_EQ(f.d_rho_l, hm.liquid_d_density(pl));
        EXPECT_EQ(f.rho_g, hm.gas_density(pg));
        EXPECT_EQ(f.d_rho_g, hm.gas_d_density(pg));
        const StorageMatrix a = storage_matrix(0.3, f);
        const double sl = hm.saturation(s), ds = hm.d_saturation(s);
        EXPECT_EQ(a.ll, 0.3 * (hm.liquid_d_density(pl) * sl - hm.liquid_density(pl) * ds));
        EXPECT_EQ(a.gg, 0.3 * (hm.gas_d_density(pg) * (1.0 - sl) - hm.gas_density(pg) * ds));
      }
}

TEST(FluidContents, TheStateReturnedIsTheStateAtThePressuresFound) {
  for (const HydraulicModel& hm : soils())
    for (const bool held : {false, true}) {
      const auto [cl, cg] = fluid_contents(hm, -3e4, 0.0);
      double x = -2e4, y = 0.0;
      LocalFluidState f{};
      ASSERT_GE(pressures_from_contents(hm, cl, cg, held, x, y, &f), 0);
      const LocalFluidState g = hm.state(x, y);
      EXPECT_EQ(f.s_l, g.s_l);
      EXPECT_EQ(f.rho_l, g.rho_l);
      EXPECT_EQ(f.rho_g, g.rho_g);
      EXPECT_EQ(f.ds, g.ds);
    }
}

TEST(FluidContents, ThePoresCanBeFreeOfGasWhereTheLawSaturatesThemOrItsGasGivesWay) {
  EXPECT_TRUE(soil(LinearRetention::create(1e-6, 0.0)).can_be_free_of_gas());
  EXPECT_TRUE(soil(VanGenuchten::create(2e4, 0.4, 0.0, 1.0)).can_be_free_of_gas());
  // Within gas_free_saturation (1e-4) of 1 at s <= 0, and just outside it.
  EXPECT_TRUE(soil(VanGenuchten::create(2e4, 0.4, 0.0, 1.0 - 0.5e-4)).can_be_free_of_gas());
  EXPECT_FALSE(soil(VanGenuchten::create(2e4, 0.4, 0.0, 1.0 - 2e-4)).can_be_free_of_gas());
  EXPECT_FALSE(soil(VanGenuchten::create(2e4, 0.4, 0.05, 0.95)).can_be_free_of_gas());
  EXPECT_TRUE(soil(VanGenuchten::create(2e4, 0.4, 0.05, 0.95, 1e3)).can_be_free_of_gas());
  TabulatedRetention table = TabulatedRetention::create({{0, 0.95}, {2e4, 0.6}});
  EXPECT_FALSE(soil(table).can_be_free_of_gas());
  table.occluded = OccludedGas::create(1e3, 0.95, "points");
  EXPECT_TRUE(soil(table).can_be_free_of_gas());
}

}  // namespace test_fluid_contents
}  // namespace unsatmpm::physics

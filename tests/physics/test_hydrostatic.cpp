// Fluids at rest under gravity (physics/hydrostatic.hpp): each profile satisfies dP/dz = -rho(P) g
// (central differences), passes through its reference, and the water table's liquid is at zero
// suction at the table, saturated below, and capped in suction above.
#include <gtest/gtest.h>

#include <cmath>

#include "physics/hydrostatic.hpp"

namespace unsatmpm::physics {
namespace test_hydrostatic {

constexpr double kG = 9.81;

template <class Law>
void expect_at_rest(const Law& law, double p_ref, double z_ref) {
  const double h = 1e-3;
  for (double z = z_ref - 50.0; z <= z_ref + 50.0; z += 7.3) {
    const auto p = [&](double x) { return hydrostatic_pressure(law, p_ref, z_ref, x, kG); };
    const double slope = (p(z + h) - p(z - h)) / (2.0 * h);
    // Central differences of a smooth profile: relative error ~ (h/L)^2, far below 1e-6.
    EXPECT_NEAR(slope, -law.density(p(z)) * kG, 1e-6 * law.density(p(z)) * kG) << "z = " << z;
  }
  EXPECT_NEAR(hydrostatic_pressure(law, p_ref, z_ref, z_ref, kG), p_ref, 1e-12 * std::abs(p_ref));
}

TEST(Hydrostatic, EachDensityLawIsAtRest) {
  expect_at_rest(CompressibleFluid::create(1000.0, 0.0, 2.2e9), 0.0, 3.0);
  // A soft liquid, far off its reference pressure: the curvature shows.
  expect_at_rest(CompressibleFluid::create(1000.0, 5e4, 1e6), -2e4, 0.0);
  expect_at_rest(IdealGas::create(1.2), 0.0, 1.0);
  expect_at_rest(IdealGas::create(1.2), -5e4, -2.0);
}

TEST(Hydrostatic, CompressibleFluidHasNoStateBelowItsDepthLimit) {
  const auto f = CompressibleFluid::create(1000.0, 0.0, 1e5);  // limit K / (rho g) = 10.19 m
  EXPECT_TRUE(std::isfinite(hydrostatic_pressure(f, 0.0, 0.0, -10.0, kG)));
  EXPECT_TRUE(std::isnan(hydrostatic_pressure(f, 0.0, 0.0, -10.5, kG)));
}

TEST(Hydrostatic, WaterTableIsSaturatedBelowAndCappedAbove) {
  const auto water = CompressibleFluid::create(1000.0, 0.0, 2.2e9);
  const GasLaw air = IdealGas::create(1.2);
  const WaterTable w{2.0, 100.0, 5e3};
  const auto at = [&](double z) { return water_table_pressures(water, air, w, kG, z); };
  EXPECT_NEAR(at(2.0).liquid, 100.0, 1e-9);
  EXPECT_NEAR(at(2.0).gas, 100.0, 1e-9);
  // 1 m below: rho_l g H within the liquid's compressibility (rho g H / K ~ 4e-6); the gas
  // pressure grows by rho_g g H, so the liquid exceeds it by (rho_l - rho_g) g H.
  EXPECT_NEAR(at(1.0).liquid - 100.0, 1000.0 * kG, 1e-5 * 1000.0 * kG);
  EXPECT_NEAR(at(1.0).liquid - at(1.0).gas, (1000.0 - 1.2) * kG, 1e-5 * 1000.0 * kG);
  // 0.3 m above: suction (rho_l - rho_g) g 0.3, under the cap.
  EXPECT_NEAR(at(2.3).gas - at(2.3).liquid, (1000.0 - 1.2) * kG * 0.3, 1e-5 * 300.0 * kG);
  // 2 m above: the cap holds.
  EXPECT_DOUBLE_EQ(at(4.0).gas - at(4.0).liquid, 5e3);
  // The gas is at rest too: its pressure falls by about rho_g g per metre.
  EXPECT_NEAR(at(3.0).gas - 100.0, -1.2 * (1.0 + 100.0 / 101325.0) * kG, 1e-3);
}

}  // namespace test_hydrostatic
}  // namespace unsatmpm::physics

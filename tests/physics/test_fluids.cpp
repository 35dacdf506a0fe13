// Pore-fluid densities: derivatives against central differences, monotonicity, reference values,
// the GasLaw variant, and validation of every factory.
#include <gtest/gtest.h>

#include "tests/physics/physics_test_support.hpp"

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "physics/fluids.hpp"
#include "physics/parameter_error.hpp"

namespace unsatmpm::physics {
namespace test_fluids {

using namespace test;
constexpr double kAtm = IdealGas::atmospheric_pressure;

std::vector<double> pressures(double lo, double hi, int count) {
  std::vector<double> p;
  for (int i = 0; i <= count; ++i) p.push_back(lo + (hi - lo) * i / count);
  return p;
}

TEST(FluidLaws, CompressibleDensityDerivativeMatchesCentralDifferences) {
  // The liquid of Table 1 (K_l = 80 MPa), a reference pressure off zero, and the gas of Table 2
  // given by a bulk modulus (K_g = 10 kPa, strongly curved over the range).
  for (const auto& fluid :
       {CompressibleFluid::create(1000.0, 0.0, 8e7), CompressibleFluid::create(998.0, 2e5, 2.2e9),
        CompressibleFluid::create(1.0, 0.0, 1e4)}) {
    const double h = 1e-3 * fluid.bulk_modulus;
    for (double p : pressures(-9e4, 1e5, 40)) {
      const double fd = central_difference([&](double x) { return fluid.density(x); }, p, h);
      EXPECT_NEAR(fluid.d_density(p), fd, 1e-6 * std::abs(fd)) << "p = " << p;
    }
  }
}

TEST(FluidLaws, IdealGasDensityDerivativeMatchesCentralDifferences) {
  const auto gas = IdealGas::create(1.2);
  for (double p : pressures(-0.99 * kAtm, 1e6, 50)) {
    const double fd = central_difference([&](double x) { return gas.density(x); }, p, 10.0);
    EXPECT_NEAR(gas.d_density(p), fd, 1e-6 * std::abs(fd)) << "p = " << p;
  }
}

TEST(FluidLaws, CompressibleDensitySecondDerivativeMatchesCentralDifferences) {
  // Central differences of d_density with h = 1e-3 K: truncation (h/K)^2 / 6 ~ 2e-7 and rounding
  // ~ 1e-16 K / h = 1e-13, relative, so 1e-6 relative holds with margin.
  for (const auto& fluid :
       {CompressibleFluid::create(1000.0, 0.0, 8e7), CompressibleFluid::create(998.0, 2e5, 2.2e9),
        CompressibleFluid::create(1.0, 0.0, 1e4)}) {
    const double h = 1e-3 * fluid.bulk_modulus;
    for (double p : pressures(-9e4, 1e5, 40)) {
      const double fd = central_difference([&](double x) { return fluid.d_density(x); }, p, h);
      EXPECT_NEAR(fluid.d2_density(p), fd, 1e-6 * std::abs(fd)) << "p = " << p;
      EXPECT_GT(fluid.d2_density(p), 0.0) << "p = " << p;  // convex in p
    }
  }
}

TEST(FluidLaws, IdealGasDensitySecondDerivativeMatchesCentralDifferences) {
  // The ideal gas is linear in p: the difference quotient of its slope is 0 (to rounding, well
  // below 1e-6 of rho0 / (P_atm (p + P_atm)), the size a curvature on the scale of the absolute
  // pressure would have).
  const auto gas = IdealGas::create(1.2);
  for (double p : pressures(-0.99 * kAtm, 1e6, 50)) {
    const double fd = central_difference([&](double x) { return gas.d_density(x); }, p, 10.0);
    EXPECT_NEAR(gas.d2_density(p), fd, 1e-6 * gas.d_density(p) / (p + kAtm)) << "p = " << p;
  }
}

TEST(FluidLaws, DensitiesIncreaseWithPressure) {
  const GasLaw laws[] = {CompressibleFluid::create(1000.0, 0.0, 8e7),
                         CompressibleFluid::create(1.0, 0.0, 1e4), IdealGas::create(1.2)};
  for (const GasLaw& law : laws) {
    double previous = gas_density(law, -0.99 * kAtm);
    for (double p : pressures(-0.98 * kAtm, 1e6, 200)) {
      const double rho = gas_density(law, p);
      EXPECT_GT(rho, previous) << "p = " << p;
      EXPECT_GT(gas_d_density(law, p), 0.0) << "p = " << p;
      previous = rho;
    }
  }
}

TEST(FluidLaws, ReferenceValues) {
  const auto liquid = CompressibleFluid::create(1000.0, 5e4, 8e7);
  EXPECT_DOUBLE_EQ(liquid.density(5e4), 1000.0);  // rho0 at p0
  EXPECT_DOUBLE_EQ(liquid.d_density(5e4), 1000.0 / 8e7);
  EXPECT_NEAR(liquid.density(5e4 + 8e7 * std::log(2.0)), 2000.0, 1e-9);  // e-folding with K
  const auto gas = IdealGas::create(1.2);
  EXPECT_DOUBLE_EQ(gas.density(0.0), 1.2);   // gauge 0 = atmospheric
  EXPECT_DOUBLE_EQ(gas.density(kAtm), 2.4);  // doubles at twice the absolute pressure
  EXPECT_DOUBLE_EQ(gas.density(-0.5 * kAtm), 0.6);
  EXPECT_DOUBLE_EQ(gas.density(-kAtm), 0.0);  // the validity bound p > -P_atm
  EXPECT_DOUBLE_EQ(gas.d_density(3e5), 1.2 / kAtm);
  EXPECT_EQ(kAtm, 101325.0);
}

TEST(FluidLaws, GasLawVariantDispatchesToTheHeldLaw) {
  const auto compressible = CompressibleFluid::create(1.0, 1e3, 1e4);
  const auto ideal = IdealGas::create(1.2);
  const GasLaw a = compressible, b = ideal;
  for (double p : {-5e4, 0.0, 3e4, 2e5}) {
    EXPECT_EQ(gas_density(a, p), compressible.density(p));
    EXPECT_EQ(gas_d_density(a, p), compressible.d_density(p));
    EXPECT_EQ(gas_density(b, p), ideal.density(p));
    EXPECT_EQ(gas_d_density(b, p), ideal.d_density(p));
    EXPECT_EQ(gas_d2_density(a, p), compressible.d2_density(p));
    EXPECT_EQ(gas_d2_density(b, p), ideal.d2_density(p));
  }
  EXPECT_NE(gas_d2_density(a, 3e4), gas_d2_density(b, 3e4));
  EXPECT_NE(gas_density(a, 3e4), gas_density(b, 3e4));
}

TEST(FluidLaws, FactoriesKeepValidParameters) {
  const auto liquid = CompressibleFluid::create(1000.0, -2e4, 8e7);
  EXPECT_EQ(liquid.reference_density, 1000.0);
  EXPECT_EQ(liquid.reference_pressure, -2e4);
  EXPECT_EQ(liquid.bulk_modulus, 8e7);
  EXPECT_EQ(IdealGas::create(1.2).reference_density, 1.2);
}

TEST(FluidLaws, FactoriesRejectOutOfRangeAndNonFiniteValues) {
  for (double bad : {0.0, -1.0, 2e5, kNaN, kInf, -kInf}) {
    expect_parameter_error([&] { CompressibleFluid::create(bad, 0.0, 8e7); }, "density");
    expect_parameter_error([&] { IdealGas::create(bad); }, "density");
  }
  for (double bad : {2e9, -2e9, kNaN, kInf, -kInf})
    expect_parameter_error([&] { CompressibleFluid::create(1000.0, bad, 8e7); },
                           "reference_pressure");
  for (double bad : {0.0, -8e7, 1e14, kNaN, kInf, -kInf})
    expect_parameter_error([&] { CompressibleFluid::create(1000.0, 0.0, bad); }, "bulk_modulus");
}

}  // namespace test_fluids
}  // namespace unsatmpm::physics

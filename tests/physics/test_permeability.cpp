// Relative permeabilities: derivatives against central differences, monotonicity, end values,
// clamping, the guarded Mualem-van Genuchten slope at S_e -> 1, and factory validation.
#include <gtest/gtest.h>

#include "tests/physics/physics_test_support.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <variant>
#include <vector>

#include "physics/parameter_error.hpp"
#include "physics/permeability.hpp"

namespace unsatmpm::physics {
namespace test_permeability {

using namespace test;

/// S_e in (0, 1): an even grid plus points crowding both ends.
std::vector<double> interior_saturations() {
  std::vector<double> se;
  for (int i = 1; i < 100; ++i) se.push_back(i / 100.0);
  for (double d : {1e-3, 1e-4, 1e-5}) se.push_back(d), se.push_back(1.0 - d);
  return se;
}

/// Central difference with a step small against the distance to either end of [0, 1].
template <class Law>
double central_difference(const Law& k, double se) {
  const double h = 1e-4 * std::min(se, 1.0 - se);
  return (k.value(se + h) - k.value(se - h)) / (2.0 * h);
}

template <class Law>
void expect_derivative_matches(const Law& k, const char* label) {
  for (double se : interior_saturations()) {
    const double fd = central_difference(k, se);
    EXPECT_NEAR(k.d_value(se), fd, 1e-6 * std::abs(fd) + 1e-14) << label << ", S_e = " << se;
  }
}

TEST(RelativePermeability, DerivativesMatchCentralDifferences) {
  for (double r : {1.0, 2.0, 3.5}) expect_derivative_matches(PowerRelPerm::create(r), "power");
  for (double r : {1.0, 2.0, 3.0}) expect_derivative_matches(GasPowerRelPerm::create(r), "gas");
  for (double lambda : {0.2, 0.5, 0.8})
    expect_derivative_matches(MualemVanGenuchten::create(lambda), "mualem");
  expect_derivative_matches(ConstantRelPerm{}, "constant");
}

TEST(RelativePermeability, EndValues) {
  for (const LiquidRelPerm& k :
       {LiquidRelPerm(PowerRelPerm::create(1.0)), LiquidRelPerm(PowerRelPerm::create(3.0)),
        LiquidRelPerm(MualemVanGenuchten::create(0.2)),
        LiquidRelPerm(MualemVanGenuchten::create(0.5)),
        LiquidRelPerm(MualemVanGenuchten::create(0.9))}) {
    std::visit(
        [](const auto& law) {
          EXPECT_DOUBLE_EQ(law.value(1.0), 1.0);
          EXPECT_DOUBLE_EQ(law.value(0.0), 0.0);
          // Continuous into S_e = 1 (slowly for Mualem: 1 - k ~ 2 ((1 - S_e)/lambda)^lambda).
          EXPECT_NEAR(law.value(1.0 - 1e-12), 1.0, 2e-2);
          EXPECT_NEAR(law.value(1e-12), 0.0, 1e-6);  // and into S_e = 0
        },
        k);
  }
  for (double r : {1.0, 2.5}) {
    const auto gas = GasPowerRelPerm::create(r);
    EXPECT_DOUBLE_EQ(gas.value(0.0), 1.0);
    EXPECT_DOUBLE_EQ(gas.value(1.0), 0.0);
  }
  for (double se : {0.0, 0.37, 1.0}) {
    EXPECT_EQ(ConstantRelPerm{}.value(se), 1.0);
    EXPECT_EQ(ConstantRelPerm{}.d_value(se), 0.0);
  }
  EXPECT_DOUBLE_EQ(PowerRelPerm::create(3.0).value(0.5), 0.125);
  // sqrt(S_e) [1 - (1 - S_e^2)^0.5]^2 at S_e = 0.6: 1 - sqrt(0.64) = 0.2.
  EXPECT_DOUBLE_EQ(MualemVanGenuchten::create(0.5).value(0.6), std::sqrt(0.6) * 0.04);
}

TEST(RelativePermeability, LiquidNonDecreasingAndGasNonIncreasing) {
  const std::vector<LiquidRelPerm> liquid = {
      ConstantRelPerm{}, PowerRelPerm::create(1.0), PowerRelPerm::create(4.0),
      MualemVanGenuchten::create(0.3), MualemVanGenuchten::create(0.7)};
  const std::vector<GasRelPerm> gas = {ConstantRelPerm{}, GasPowerRelPerm::create(1.0),
                                       GasPowerRelPerm::create(3.0)};
  for (const LiquidRelPerm& k : liquid) {
    std::visit(
        [](const auto& law) {
          for (int i = 0; i < 1000; ++i) {
            const double a = i / 1000.0, b = (i + 1) / 1000.0;
            EXPECT_LE(law.value(a), law.value(b)) << "S_e = " << a;
            EXPECT_GE(law.d_value(b), 0.0) << "S_e = " << b;
          }
        },
        k);
  }
  for (const GasRelPerm& k : gas) {
    std::visit(
        [](const auto& law) {
          for (int i = 0; i < 1000; ++i) {
            const double a = i / 1000.0, b = (i + 1) / 1000.0;
            EXPECT_GE(law.value(a), law.value(b)) << "S_e = " << a;
            EXPECT_LE(law.d_value(b), 0.0) << "S_e = " << b;
          }
        },
        k);
  }
}

TEST(RelativePermeability, ClampedOutsideTheUnitInterval) {
  const auto power = PowerRelPerm::create(3.0);
  const auto mualem = MualemVanGenuchten::create(0.5);
  const auto gas = GasPowerRelPerm::create(2.0);
  for (double se : {-0.5, -1e-9, -kInf}) {
    EXPECT_EQ(power.value(se), 0.0);
    EXPECT_EQ(mualem.value(se), 0.0);
    EXPECT_EQ(gas.value(se), 1.0);
    EXPECT_EQ(power.d_value(se), 0.0);
    EXPECT_EQ(mualem.d_value(se), 0.0);
    EXPECT_EQ(gas.d_value(se), 0.0);
  }
  for (double se : {1.0 + 1e-9, 1.7, kInf}) {
    EXPECT_EQ(power.value(se), 1.0);
    EXPECT_EQ(mualem.value(se), 1.0);
    EXPECT_EQ(gas.value(se), 0.0);
    EXPECT_EQ(power.d_value(se), 0.0);
    EXPECT_EQ(mualem.d_value(se), 0.0);
    EXPECT_EQ(gas.d_value(se), 0.0);
  }
  // One-sided derivatives from inside at the ends.
  EXPECT_DOUBLE_EQ(power.d_value(1.0), 3.0);
  EXPECT_DOUBLE_EQ(PowerRelPerm::create(1.0).d_value(0.0), 1.0);
  EXPECT_DOUBLE_EQ(gas.d_value(0.0), -2.0);
  EXPECT_DOUBLE_EQ(GasPowerRelPerm::create(1.0).d_value(1.0), -1.0);
}

TEST(RelativePermeability, MualemSlopeIsFiniteAndGuardedNearFullSaturation) {
  for (double lambda : {0.1, 0.5, 0.9, 0.999}) {
    const auto k = MualemVanGenuchten::create(lambda);
    const double cap = 1.0 - MualemVanGenuchten::mualem_derivative_cap;
    // Rising without bound towards S_e = 1 (slope ~ (1 - S_e)^(lambda - 1)) up to the guard...
    double previous = k.d_value(0.99);
    for (double se : {0.999, 0.9999, 0.99999, cap}) {
      EXPECT_GT(k.d_value(se), previous) << "lambda = " << lambda << ", S_e = " << se;
      previous = k.d_value(se);
    }
    // ...then held at its value at the guard: finite, positive, the same up to S_e = 1.
    for (double se : {cap + 1e-7, 1.0 - 1e-12, std::nextafter(1.0, 0.0), 1.0}) {
      EXPECT_TRUE(std::isfinite(k.d_value(se))) << "lambda = " << lambda << ", S_e = " << se;
      EXPECT_EQ(k.d_value(se), k.d_value(cap)) << "lambda = " << lambda << ", S_e = " << se;
      EXPECT_TRUE(std::isfinite(k.value(se)));
    }
    // At S_e -> 0 the slope vanishes (f ~ lambda S_e^(1/lambda)) without 0/0.
    for (double se : {0.0, 5e-324, 1e-300, 1e-12}) {
      EXPECT_TRUE(std::isfinite(k.d_value(se))) << "lambda = " << lambda << ", S_e = " << se;
      EXPECT_GE(k.d_value(se), 0.0);
      EXPECT_LT(k.d_value(se), 1e-6);
    }
  }
}

TEST(RelativePermeability, MualemKeepsFullPrecisionAtLowSaturation) {
  // u = S_e^(1/lambda) << 1: f = 1 - (1 - u)^lambda = lambda u (1 + O(u)), so
  // k = lambda^2 S_e^(2/lambda + 1/2) and dk/dS_e = (2/lambda + 1/2) k / S_e to O(u). A naive
  // 1 - (1 - u)^lambda would lose all digits here (1 - u rounds to 1 for u < 1e-16).
  for (double lambda : {0.3, 0.5, 0.8}) {
    const auto k = MualemVanGenuchten::create(lambda);
    for (double se : {1e-3, 1e-6, 1e-9}) {
      const double u = std::pow(se, 1.0 / lambda);
      const double expected = lambda * lambda * std::pow(se, 2.0 / lambda + 0.5);
      EXPECT_NEAR(k.value(se), expected, (1e-12 + 2.0 * u) * expected) << lambda << ", " << se;
      const double slope = (2.0 / lambda + 0.5) * expected / se;
      EXPECT_NEAR(k.d_value(se), slope, (1e-12 + 4.0 * u) * slope) << lambda << ", " << se;
    }
  }
}

TEST(RelativePermeability, FactoriesKeepValidParameters) {
  EXPECT_EQ(PowerRelPerm::create(3.0).exponent, 3.0);
  EXPECT_EQ(GasPowerRelPerm::create(1.0).exponent, 1.0);
  EXPECT_EQ(MualemVanGenuchten::create(0.4).lambda, 0.4);
}

TEST(RelativePermeability, FactoriesRejectOutOfRangeAndNonFiniteValues) {
  for (double bad : {0.5, 0.0, -2.0, 21.0, kNaN, kInf, -kInf}) {
    expect_parameter_error([&] { PowerRelPerm::create(bad); }, "exponent");
    expect_parameter_error([&] { GasPowerRelPerm::create(bad); }, "exponent");
  }
  for (double bad : {0.0, 1.0, -0.5, 2.0, kNaN, kInf, -kInf})
    expect_parameter_error([&] { MualemVanGenuchten::create(bad); }, "lambda");
}

}  // namespace test_permeability
}  // namespace unsatmpm::physics

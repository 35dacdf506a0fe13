// Properties of the unsaturated-soil laws: derivatives against central differences, monotonicity,
// limits, the paper's Table 1 value, the stress variables and the storage matrix.
#include <gtest/gtest.h>

#include <cmath>

#include "physics/fluids.hpp"
#include "physics/parameter_error.hpp"
#include "physics/permeability.hpp"
#include "physics/retention.hpp"
#include "physics/unsaturated_state.hpp"

namespace unsatmpm::physics {
namespace {

template <class F>
double central_difference(F f, double x, double h) {
  return (f(x + h) - f(x - h)) / (2.0 * h);
}

TEST(Fluids, DensityDerivativesMatchFiniteDifferences) {
  const auto liquid = CompressibleFluid::create(1000.0, 0.0, 8e7);
  const auto gas = IdealGas::create(1.2);
  for (double p : {-5e4, 0.0, 1e5, 3e6}) {
    EXPECT_NEAR(liquid.d_density(p),
                central_difference([&](double x) { return liquid.density(x); }, p, 1.0),
                1e-6 * liquid.d_density(p));
    EXPECT_NEAR(gas.d_density(p),
                central_difference([&](double x) { return gas.density(x); }, p, 1.0),
                1e-6 * gas.d_density(p));
    EXPECT_GT(liquid.density(p + 1.0), liquid.density(p));
  }
  EXPECT_DOUBLE_EQ(liquid.density(0.0), 1000.0);
  EXPECT_DOUBLE_EQ(gas.density(0.0), 1.2);
  EXPECT_DOUBLE_EQ(gas.density(IdealGas::atmospheric_pressure), 2.4);  // doubles at 2 atm absolute
}

TEST(Retention, LinearLawReproducesTable1) {
  const auto r = LinearRetention::create(1e-6, 0.0);  // a_s = 1e-3 1/kPa
  EXPECT_DOUBLE_EQ(r.saturation(0.5e6), 0.5);
  EXPECT_DOUBLE_EQ(r.saturation(0.0), 1.0);
  EXPECT_DOUBLE_EQ(r.d_saturation(0.3e6), -1e-6);
  EXPECT_DOUBLE_EQ(r.d_saturation(-10.0), 0.0);  // saturated: no retention storage
  const auto clamped = LinearRetention::create(1e-6, 0.2);
  EXPECT_DOUBLE_EQ(clamped.saturation(2e6), 0.2);
  EXPECT_DOUBLE_EQ(clamped.d_saturation(2e6), 0.0);
  EXPECT_DOUBLE_EQ(clamped.effective_saturation(2e6), 0.0);
}

TEST(Retention, VanGenuchtenDerivativeMonotonicityAndLimits) {
  const auto r = VanGenuchten::create(2e4, 0.4, 0.05, 0.95);
  double previous = r.saturation(0.0);
  EXPECT_DOUBLE_EQ(previous, 0.95);
  for (double s = 100.0; s < 1e7; s *= 1.5) {
    const double h = 1e-6 * s;
    EXPECT_NEAR(r.d_saturation(s),
                central_difference([&](double x) { return r.saturation(x); }, s, h),
                1e-5 * std::abs(r.d_saturation(s)) + 1e-15);
    EXPECT_LE(r.saturation(s), previous);
    EXPECT_LE(r.d_saturation(s), 0.0);
    previous = r.saturation(s);
  }
  EXPECT_NEAR(r.saturation(1e12), 0.05, 1e-3);
  EXPECT_NEAR(r.effective_saturation(1e12), 0.0, 1e-2);
}

TEST(Permeability, MonotoneWithTheRightEnds) {
  const auto power = PowerRelPerm::create(3.0);
  const auto mvg = MualemVanGenuchten::create(0.5);
  const auto gas = GasPowerRelPerm::create(2.0);
  EXPECT_DOUBLE_EQ(power.value(1.0), 1.0);
  EXPECT_DOUBLE_EQ(power.value(0.0), 0.0);
  EXPECT_NEAR(mvg.value(1.0), 1.0, 1e-12);
  EXPECT_DOUBLE_EQ(mvg.value(0.0), 0.0);
  EXPECT_DOUBLE_EQ(gas.value(0.0), 1.0);
  EXPECT_DOUBLE_EQ(gas.value(1.0), 0.0);
  EXPECT_DOUBLE_EQ(ConstantRelPerm{}.value(0.3), 1.0);
  for (double se = 0.01; se < 1.0; se += 0.01) {
    EXPECT_GE(power.value(se + 0.01), power.value(se));
    EXPECT_GE(mvg.value(std::min(1.0, se + 0.01)), mvg.value(se));
    EXPECT_LE(gas.value(se + 0.01), gas.value(se));
  }
  EXPECT_DOUBLE_EQ(power.value(1.7), 1.0);  // clamped
}

TEST(UnsaturatedState, NetStressRoundTripAndTerzaghi) {
  Vec6 sigma;
  sigma << -1e5, -2e5, -1.5e5, 1e4, -2e3, 3e3;
  for (auto [pl, pg] : {std::pair{-3e5, 0.0}, std::pair{5e4, 1e4}, std::pair{0.0, 0.0}}) {
    const Vec6 net = net_stress(sigma, pl, pg);
    EXPECT_LT((total_stress(net, pl, pg) - sigma).norm(), 1e-9);
    EXPECT_DOUBLE_EQ(net[3], sigma[3]);  // shear untouched
  }
  // Saturated (P_l >= P_g): net stress is Terzaghi's effective stress sigma + P_l I.
  EXPECT_DOUBLE_EQ(net_stress(sigma, 5e4, 1e4)[0], -1e5 + 5e4);
  EXPECT_DOUBLE_EQ(suction(5e4, 1e4), 0.0);
  EXPECT_DOUBLE_EQ(suction(-3e5, 1e4), 3.1e5);
}

/// n rho_a S_a as a function of (p_l, p_g): the quantity whose derivatives the storage matrix
/// holds.
struct Content {
  CompressibleFluid liquid;
  GasLaw gas;
  RetentionCurve retention;
  double n;
  double liquid_content(double pl, double pg) const {
    const double s =
        std::visit([&](const auto& r) { return r.saturation(suction(pl, pg)); }, retention);
    return n * liquid.density(pl) * s;
  }
  double gas_content(double pl, double pg) const {
    const double s =
        std::visit([&](const auto& r) { return r.saturation(suction(pl, pg)); }, retention);
    return n * gas_density(gas, pg) * (1.0 - s);
  }
};

TEST(UnsaturatedState, StorageMatrixMatchesFiniteDifferences) {
  for (const RetentionCurve& r : {RetentionCurve(LinearRetention::create(1e-6, 0.0)),
                                  RetentionCurve(VanGenuchten::create(2e4, 0.4, 0.05, 1.0))}) {
    const Content c{CompressibleFluid::create(1000.0, 0.0, 8e7), IdealGas::create(1.2), r, 0.3};
    for (auto [pl, pg] : {std::pair{-3e5, 0.0}, std::pair{-5e4, 2e4}, std::pair{-1e6, 1e3}}) {
      const StorageMatrix a = storage_matrix(c.n, pl, pg, c.liquid, c.gas, c.retention);
      const double h = 1.0;
      const auto d = [&](auto f, double x0, double y0, bool wrt_pl) {
        return wrt_pl ? (f(x0 + h, y0) - f(x0 - h, y0)) / (2 * h)
                      : (f(x0, y0 + h) - f(x0, y0 - h)) / (2 * h);
      };
      const auto lc = [&](double x, double y) { return c.liquid_content(x, y); };
      const auto gc = [&](double x, double y) { return c.gas_content(x, y); };
      EXPECT_NEAR(a.ll, d(lc, pl, pg, true), 1e-5 * std::abs(a.ll));
      EXPECT_NEAR(a.lg, d(lc, pl, pg, false), 1e-5 * std::abs(a.lg) + 1e-14);
      EXPECT_NEAR(a.gl, d(gc, pl, pg, true), 1e-5 * std::abs(a.gl) + 1e-14);
      EXPECT_NEAR(a.gg, d(gc, pl, pg, false), 1e-5 * std::abs(a.gg));
    }
  }
}

TEST(UnsaturatedState, SaturatedStorageIsTheLiquidCompressibility) {
  const auto liquid = CompressibleFluid::create(1000.0, 0.0, 8e7);
  const StorageMatrix a = storage_matrix(0.3, 1e4, 0.0, liquid, IdealGas::create(1.2),
                                         LinearRetention::create(1e-6, 0.0));
  EXPECT_DOUBLE_EQ(a.ll, 0.3 * liquid.d_density(1e4));
  EXPECT_DOUBLE_EQ(a.lg, 0.0);
  EXPECT_DOUBLE_EQ(a.gl, 0.0);
  EXPECT_DOUBLE_EQ(a.gg, 0.0);  // no gas left
}

TEST(UnsaturatedLaws, FactoriesRejectBadParametersNamingThem) {
  const auto expect_named = [](auto f, const char* name) {
    try {
      f();
      ADD_FAILURE() << "no error for " << name;
    } catch (const ParameterError& e) {
      EXPECT_EQ(e.parameter(), name);
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  };
  expect_named([] { CompressibleFluid::create(-1.0, 0.0, 1e8); }, "density");
  expect_named([] { CompressibleFluid::create(1000.0, 0.0, NAN); }, "bulk_modulus");
  expect_named([] { IdealGas::create(0.0); }, "density");
  expect_named([] { LinearRetention::create(0.0, 0.0); }, "a_s");
  expect_named([] { LinearRetention::create(1e-6, 1.0); }, "residual_saturation");
  expect_named([] { VanGenuchten::create(2e4, 1.0, 0.0, 1.0); }, "lambda");
  expect_named([] { VanGenuchten::create(-1.0, 0.5, 0.0, 1.0); }, "p0");
  expect_named([] { PowerRelPerm::create(0.5); }, "exponent");
  expect_named([] { MualemVanGenuchten::create(INFINITY); }, "lambda");
  expect_named([] { GasPowerRelPerm::create(-2.0); }, "exponent");
}

}  // namespace
}  // namespace unsatmpm::physics

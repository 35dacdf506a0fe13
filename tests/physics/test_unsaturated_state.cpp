// Stress variables and the storage matrix: suction, net stress <-> total stress, the Terzaghi
// limit, and the storage entries against central differences of n rho_l S_l and n rho_g S_g.
#include <gtest/gtest.h>

#include <cmath>
#include <utility>
#include <variant>
#include <vector>

#include "physics/fluids.hpp"
#include "physics/retention.hpp"
#include "physics/unsaturated_state.hpp"

namespace unsatmpm::physics {
namespace {

Vec6 some_stress() {
  Vec6 sigma;
  sigma << -1e5, -2e5, -1.5e5, 1e4, -2e3, 3e3;
  return sigma;
}

TEST(UnsaturatedStateVariables, SuctionIsGasOverLiquidPressureAndZeroWhenSaturated) {
  EXPECT_DOUBLE_EQ(suction(-3e5, 1e4), 3.1e5);
  EXPECT_DOUBLE_EQ(suction(-5e5, 0.0), 5e5);
  for (auto [p_l, p_g] : {std::pair{5e4, 1e4}, std::pair{0.0, 0.0}, std::pair{-1e3, -2e3}})
    EXPECT_EQ(suction(p_l, p_g), 0.0) << p_l << ", " << p_g;
}

TEST(UnsaturatedStateVariables, NetAndTotalStressRoundTrip) {
  const Vec6 sigma = some_stress();
  for (auto [p_l, p_g] : {std::pair{-3e5, 0.0}, std::pair{5e4, 1e4}, std::pair{0.0, 0.0},
                          std::pair{-2e4, -5e4}, std::pair{1e6, 2e6}}) {
    const Vec6 net = net_stress(sigma, p_l, p_g);
    EXPECT_LT((total_stress(net, p_l, p_g) - sigma).norm(), 1e-9);
    EXPECT_LT((net_stress(total_stress(sigma, p_l, p_g), p_l, p_g) - sigma).norm(), 1e-9);
    for (int i = 3; i < 6; ++i) EXPECT_EQ(net[i], sigma[i]);  // shear untouched
  }
}

TEST(UnsaturatedStateVariables, NetStressIsTerzaghiWhenSaturatedAndUsesGasOtherwise) {
  const Vec6 sigma = some_stress();
  // Saturated (P_l >= P_g): sigma + P_l I, tension positive.
  const Vec6 saturated = net_stress(sigma, 5e4, 1e4);
  for (int i = 0; i < 3; ++i) EXPECT_DOUBLE_EQ(saturated[i], sigma[i] + 5e4);
  // Unsaturated (P_g > P_l): sigma + P_g I.
  const Vec6 unsaturated = net_stress(sigma, -3e5, 2e4);
  for (int i = 0; i < 3; ++i) EXPECT_DOUBLE_EQ(unsaturated[i], sigma[i] + 2e4);
}

/// n rho_a S_a as a function of (P_l, P_g): the quantities whose derivatives the storage matrix
/// holds, written from the laws' values only.
struct Content {
  double n;
  CompressibleFluid liquid;
  GasLaw gas;
  RetentionCurve retention;

  double saturation(double p_l, double p_g) const {
    return std::visit([&](const auto& r) { return r.saturation(suction(p_l, p_g)); }, retention);
  }
  double liquid_content(double p_l, double p_g) const {
    return n * liquid.density(p_l) * saturation(p_l, p_g);
  }
  double gas_content(double p_l, double p_g) const {
    return n * gas_density(gas, p_g) * (1.0 - saturation(p_l, p_g));
  }
  StorageMatrix storage(double p_l, double p_g) const {
    return storage_matrix(n, p_l, p_g, liquid, gas, retention);
  }
};

std::vector<Content> contents() {
  const auto water = CompressibleFluid::create(1000.0, 0.0, 8e7);
  const GasLaw air = IdealGas::create(1.2);
  const GasLaw stiff_gas = CompressibleFluid::create(1.0, 0.0, 1e4);  // Table 2: K_g = 10 kPa
  return {{0.3, water, air, LinearRetention::create(1e-6, 0.0)},
          {0.3, water, stiff_gas, LinearRetention::create(1e-6, 0.2)},
          {0.35, water, air, VanGenuchten::create(2e4, 0.4, 0.05, 0.95)},
          {0.35, water, stiff_gas, VanGenuchten::create(1e5, 0.7, 0.0, 1.0)}};
}

/// Central differences of (liquid, gas) content with respect to P_l and P_g.
StorageMatrix finite_difference_storage(const Content& c, double p_l, double p_g, double h) {
  const auto d = [h](auto f) { return (f(+h) - f(-h)) / (2.0 * h); };
  return {d([&](double e) { return c.liquid_content(p_l + e, p_g); }),
          d([&](double e) { return c.liquid_content(p_l, p_g + e); }),
          d([&](double e) { return c.gas_content(p_l + e, p_g); }),
          d([&](double e) { return c.gas_content(p_l, p_g + e); })};
}

void expect_storage_near(const StorageMatrix& a, const StorageMatrix& fd, double rel) {
  EXPECT_NEAR(a.ll, fd.ll, rel * std::abs(fd.ll) + 1e-18);
  EXPECT_NEAR(a.lg, fd.lg, rel * std::abs(fd.lg) + 1e-18);
  EXPECT_NEAR(a.gl, fd.gl, rel * std::abs(fd.gl) + 1e-18);
  EXPECT_NEAR(a.gg, fd.gg, rel * std::abs(fd.gg) + 1e-18);
}

TEST(UnsaturatedStorage, MatrixMatchesFiniteDifferencesInUnsaturatedStates) {
  // Suctions from 1 kPa to 0.7 MPa (inside the linear law's sloping branch, 0.8 MPa with
  // s_min = 0.2), gas pressures around atmospheric.
  const std::vector<std::pair<double, double>> states = {{-1e3, 0.0},   {-5e4, 2e4},  {-3e5, 0.0},
                                                         {-6.9e5, 1e4}, {-2e4, -1e4}, {-1e5, 5e4}};
  for (const Content& c : contents()) {
    for (auto [p_l, p_g] : states) {
      SCOPED_TRACE(::testing::Message() << "retention " << c.retention.index() << ", gas "
                                        << c.gas.index() << ", P_l = " << p_l << ", P_g = " << p_g);
      ASSERT_GT(suction(p_l, p_g), 10.0);  // the stencil stays on the unsaturated side
      const StorageMatrix a = c.storage(p_l, p_g);
      expect_storage_near(a, finite_difference_storage(c, p_l, p_g, 1.0), 1e-6);
      EXPECT_GT(a.ll, 0.0);
      EXPECT_GT(a.gg, 0.0);
      EXPECT_LT(a.lg, 0.0);  // drying from a rise of P_g lowers the liquid content
      EXPECT_LT(a.gl, 0.0);  // wetting from a rise of P_l lowers the gas content
    }
  }
}

TEST(UnsaturatedStorage, SaturatedLimitIsTheFluidCompressibility) {
  for (const Content& c : contents()) {
    for (auto [p_l, p_g] : {std::pair{1e4, 0.0}, std::pair{0.0, 0.0}, std::pair{2e5, 1e5}}) {
      SCOPED_TRACE(::testing::Message() << "retention " << c.retention.index() << ", P_l = " << p_l
                                        << ", P_g = " << p_g);
      const StorageMatrix a = c.storage(p_l, p_g);
      const double s_l = c.saturation(p_l, p_g);  // 1 (linear) or s_max (van Genuchten)
      EXPECT_DOUBLE_EQ(a.ll, c.n * c.liquid.d_density(p_l) * s_l);
      EXPECT_EQ(a.lg, 0.0);
      EXPECT_EQ(a.gl, 0.0);
      EXPECT_DOUBLE_EQ(a.gg, c.n * gas_d_density(c.gas, p_g) * (1.0 - s_l));
    }
  }
  // Linear retention: S_l = 1, so ll = n rho_l'(P_l) and no gas storage is left.
  const Content linear = contents().front();
  const StorageMatrix a = linear.storage(1e4, 0.0);
  EXPECT_DOUBLE_EQ(a.ll, 0.3 * linear.liquid.d_density(1e4));
  EXPECT_EQ(a.gg, 0.0);
  // Strictly inside the saturated region the one-sided differences agree as well.
  expect_storage_near(a, finite_difference_storage(linear, 1e4, 0.0, 1.0), 1e-6);
}

}  // namespace
}  // namespace unsatmpm::physics

// Stress variables and the storage matrix: suction, net stress <-> total stress, the Terzaghi
// limit, the storage entries against central differences of n rho_l S_l and n rho_g S_g, and
// their derivatives in P_l and P_g against central differences of the storage matrix.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <tuple>
#include <utility>
#include <variant>
#include <vector>

#include "physics/fluids.hpp"
#include "physics/retention.hpp"
#include "physics/unsaturated_state.hpp"

namespace unsatmpm::physics {
namespace test_unsaturated_state {

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
    return std::visit([&](const auto& r) { return r.saturation(retention_suction(p_l, p_g)); },
                      retention);
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

/// The pressure over which a gas law's density curves [Pa]: K for a bulk-modulus gas; infinite
/// for the ideal gas, whose density is linear in p.
double curvature_scale(const GasLaw& gas) {
  if (const auto* law = std::get_if<CompressibleFluid>(&gas)) return law->bulk_modulus;
  return std::numeric_limits<double>::infinity();
}

/// Uniform in [lo, hi) from the raw mt19937 output, whose sequence the standard fixes (the
/// distributions' algorithms are implementation-defined): the same states on every platform.
double uniform(std::mt19937& rng, double lo, double hi) {
  return lo + (hi - lo) * (static_cast<double>(rng()) / 4294967296.0);
}

/// Central differences of storage_matrix with respect to P_l and to P_g.
StorageDerivatives finite_difference_derivatives(const Content& c, double p_l, double p_g,
                                                 double h) {
  const auto quotient = [h](const StorageMatrix& plus, const StorageMatrix& minus) {
    return StorageMatrix{(plus.ll - minus.ll) / (2.0 * h), (plus.lg - minus.lg) / (2.0 * h),
                         (plus.gl - minus.gl) / (2.0 * h), (plus.gg - minus.gg) / (2.0 * h)};
  };
  return {quotient(c.storage(p_l + h, p_g), c.storage(p_l - h, p_g)),
          quotient(c.storage(p_l, p_g + h), c.storage(p_l, p_g - h))};
}

/// Compares storage_matrix_derivatives at (P_l, P_g) with central differences of step h, entry
/// by entry, to within rel (|fd| + |X| / L) + rounding. X is the storage entry differentiated, L
/// the pressure over which it varies (scale_l for the liquid row, scale_g for the gas row): the
/// bound is relative where the derivative has its natural size |X| / L, and is not defeated
/// where terms of opposite sign cancel (van Genuchten's inflection point). rounding = 4 eps
/// (|X| + n rho_a') / h is the difference quotient's own floor: near s = 0, S_l = 1 - O(x) carries
/// an absolute error of eps, which 1 - S_l and rho_a' S_l pass on at the size n rho_a' eps.
void expect_derivatives_near(const Content& c, double p_l, double p_g, double h, double scale_l,
                             double scale_g) {
  constexpr double rel = 1e-6, eps = std::numeric_limits<double>::epsilon();
  const StorageDerivatives a =
      storage_matrix_derivatives(c.n, p_l, p_g, c.liquid, c.gas, c.retention);
  const StorageDerivatives fd = finite_difference_derivatives(c, p_l, p_g, h);
  const StorageMatrix x = c.storage(p_l, p_g);
  const double d_rho_l = c.liquid.d_density(p_l), d_rho_g = gas_d_density(c.gas, p_g);
  const auto check = [&](double analytic, double quotient, double entry, double scale, double d_rho,
                         const char* name) {
    const double rounding = 4.0 * eps * (std::abs(entry) + c.n * d_rho) / h;
    EXPECT_NEAR(analytic, quotient, rel * (std::abs(quotient) + std::abs(entry) / scale) + rounding)
        << name;
  };
  for (auto [d, q, name] :
       {std::tuple{a.d_p_l, fd.d_p_l, "d/dP_l"}, std::tuple{a.d_p_g, fd.d_p_g, "d/dP_g"}}) {
    SCOPED_TRACE(name);
    check(d.ll, q.ll, x.ll, scale_l, d_rho_l, "ll");
    check(d.lg, q.lg, x.lg, scale_l, d_rho_l, "lg");
    check(d.gl, q.gl, x.gl, scale_g, d_rho_g, "gl");
    check(d.gg, q.gg, x.gg, scale_g, d_rho_g, "gg");
  }
}

/// The storage-derivative cases: laws and the suction range [s_lo, s_hi] their random
/// unsaturated states sample (log-uniformly), kept clear of the linear law's kink where it
/// reaches s_min.
struct DerivativeCase {
  Content content;
  double s_lo, s_hi;  // [Pa]
};

std::vector<DerivativeCase> derivative_cases() {
  const auto water = CompressibleFluid::create(1000.0, 0.0, 8e7);
  const GasLaw air = IdealGas::create(1.2);
  const GasLaw stiff_gas = CompressibleFluid::create(1.0, 0.0, 1e4);  // Table 2: K_g = 10 kPa
  const auto linear = LinearRetention::create(1e-6, 0.2);             // reaches 0.2 at 0.8 MPa
  return {{{0.3, water, air, linear}, 10.0, 0.75e6},                  // sloping branch
          {{0.3, water, air, linear}, 0.85e6, 5e6},                   // residual branch
          {{0.35, water, air, VanGenuchten::create(2e4, 0.4, 0.05, 0.95)}, 10.0, 1e7},
          {{0.35, water, air, VanGenuchten::create(5e3, 0.1, 0.0, 1.0)}, 1.0, 1e7},
          {{0.35, water, stiff_gas, VanGenuchten::create(1e5, 0.7, 0.0, 1.0)}, 10.0, 1e7},
          {{0.4, water, stiff_gas, VanGenuchten::create(2e4, 0.4, 0.1, 0.9)}, 10.0, 1e7}};
}

TEST(UnsaturatedStorage, DerivativesMatchFiniteDifferencesInUnsaturatedStates) {
  // 200 random states per case, suction log-uniform in the case's range, P_g in [-20, 50] kPa.
  // Step h = 1e-4 min(s, K_g), the smallest pressure over which the entries vary: the
  // truncation error, ~ (h/L)^2 |X| / L times powers of the laws' exponents, is ~1e-8 of the
  // natural size |X| / L (3e-8 at most, measured), so rel = 1e-6 in expect_derivatives_near holds
  // with margin, while a wrong or missing term, O(1) of its entry's derivative somewhere in the
  // range, fails.
  std::mt19937 rng(20240611);
  for (const DerivativeCase& dc : derivative_cases()) {
    const Content& c = dc.content;
    for (int i = 0; i < 200; ++i) {
      const double s = dc.s_lo * std::pow(dc.s_hi / dc.s_lo, uniform(rng, 0.0, 1.0));
      const double p_g = uniform(rng, -2e4, 5e4), p_l = p_g - s;
      SCOPED_TRACE(::testing::Message() << "retention " << c.retention.index() << ", gas "
                                        << c.gas.index() << ", P_l = " << p_l << ", P_g = " << p_g);
      const double scale_l = std::min(s, c.liquid.bulk_modulus);
      const double scale_g = std::min(s, curvature_scale(c.gas));
      const double h = 1e-4 * std::min(scale_l, scale_g);
      ASSERT_GT(s - h, 0.0);  // the stencil stays on the unsaturated side
      expect_derivatives_near(c, p_l, p_g, h, scale_l, scale_g);
    }
  }
}

TEST(UnsaturatedStorage, DerivativesMatchFiniteDifferencesInSaturatedStates) {
  // P_l > P_g by 100 Pa to 100 kPa: suction 0, S_l constant, only the densities' curvature left.
  // h = 1 Pa keeps the stencil 100 times its width from the kink at s = 0; the liquid row varies
  // over K_l, the gas row over K_g (P_atm for the ideal gas, whose row is then constant).
  std::mt19937 rng(7);
  for (const DerivativeCase& dc : derivative_cases()) {
    const Content& c = dc.content;
    for (int i = 0; i < 50; ++i) {
      const double p_g = uniform(rng, -2e4, 5e4);
      const double p_l = p_g + 1e2 * std::pow(1e3, uniform(rng, 0.0, 1.0));
      SCOPED_TRACE(::testing::Message() << "retention " << c.retention.index() << ", gas "
                                        << c.gas.index() << ", P_l = " << p_l << ", P_g = " << p_g);
      const double h = 1.0;
      ASSERT_GT(p_l - p_g, 100.0 * h);
      expect_derivatives_near(c, p_l, p_g, h, c.liquid.bulk_modulus,
                              std::min(curvature_scale(c.gas), IdealGas::atmospheric_pressure));
      // The retention terms vanish: only d ll/dP_l = n rho_l'' S_l and d gg/dP_g survive.
      const StorageDerivatives a =
          storage_matrix_derivatives(c.n, p_l, p_g, c.liquid, c.gas, c.retention);
      EXPECT_EQ(a.d_p_l.lg, 0.0);
      EXPECT_EQ(a.d_p_l.gl, 0.0);
      EXPECT_EQ(a.d_p_l.gg, 0.0);
      EXPECT_EQ(a.d_p_g.ll, 0.0);
      EXPECT_EQ(a.d_p_g.lg, 0.0);
      EXPECT_EQ(a.d_p_g.gl, 0.0);
      EXPECT_DOUBLE_EQ(a.d_p_l.ll, c.n * c.liquid.d2_density(p_l) * c.saturation(p_l, p_g));
    }
  }
}

TEST(UnsaturatedStorage, AnOccludedGasGivingWayKeepsTheStorageAndItsDerivativesExact) {
  // Liquid pressed above the gas (s = P_g - P_l from -0.1 to -10 scales) under laws whose
  // occluded gas gives way (retention.hpp, OccludedGas): the storage matrix and its derivatives
  // against central differences (h = 1e-3 of the nearer of |s| and the scale, so the stencil
  // stays on the s < 0 side; truncation ~ (h / scale)^2 / 6), each entry within 1e-6 of it plus
  // the quotient's rounding 4 eps (content) / h; and with the signs of the unsaturated states:
  // S now moves with the pressures, so the fluids' rows couple.
  const auto water = CompressibleFluid::create(1000.0, 0.0, 8e7);
  const GasLaw air = IdealGas::create(1.2);
  auto vg = VanGenuchten::create(4e5, 0.5, 0.0, 0.95, 1e3);
  auto table = TabulatedRetention::create({{0, 0.9}, {500, 0.89}, {5e3, 0.8}, {2e4, 0.5}});
  table.occluded = OccludedGas::create(200.0, 0.9, "S(0)");
  constexpr double eps = std::numeric_limits<double>::epsilon();
  std::mt19937 rng(11);
  for (const auto& [c, scale] : {std::pair{Content{0.35, water, air, vg}, 1e3},
                                 std::pair{Content{0.4, water, air, table}, 200.0}})
    for (int i = 0; i < 50; ++i) {
      const double s = -scale * std::pow(10.0, uniform(rng, -1.0, 1.0));
      const double p_g = uniform(rng, -2e4, 5e4), p_l = p_g - s;
      SCOPED_TRACE(::testing::Message() << "retention " << c.retention.index() << ", P_l = " << p_l
                                        << ", P_g = " << p_g);
      const double h = 1e-3 * std::min(-s, scale);
      const StorageMatrix a = c.storage(p_l, p_g), fd = finite_difference_storage(c, p_l, p_g, h);
      const double round_l = 4.0 * eps * c.liquid_content(p_l, p_g) / h;
      const double round_g = 4.0 * eps * c.gas_content(p_l, p_g) / h;
      EXPECT_NEAR(a.ll, fd.ll, 1e-6 * std::abs(fd.ll) + round_l);
      EXPECT_NEAR(a.lg, fd.lg, 1e-6 * std::abs(fd.lg) + round_l);
      EXPECT_NEAR(a.gl, fd.gl, 1e-6 * std::abs(fd.gl) + round_g);
      EXPECT_NEAR(a.gg, fd.gg, 1e-6 * std::abs(fd.gg) + round_g);
      EXPECT_GT(a.ll, 0.0);
      EXPECT_GT(a.gg, 0.0);
      EXPECT_LT(a.lg, 0.0);
      EXPECT_LT(a.gl, 0.0);
      expect_derivatives_near(c, p_l, p_g, h, std::min(-s, scale), std::min(-s, scale));
    }
}

}  // namespace test_unsaturated_state
}  // namespace unsatmpm::physics

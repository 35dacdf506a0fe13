// Retention curves: first and second derivatives against central differences, monotonicity, limits,
// the paper's Table 1 value, saturated and residual branches, and validation of every factory.
#include <gtest/gtest.h>

#include "tests/physics/physics_test_support.hpp"

#include <cmath>
#include <limits>
#include <string>
#include <variant>
#include <vector>

#include "physics/parameter_error.hpp"
#include "physics/retention.hpp"

namespace unsatmpm::physics {
namespace test_retention {

using namespace test;

/// `count` + 1 points from lo to hi (both > 0), evenly spaced in log.
std::vector<double> log_points(double lo, double hi, int count) {
  std::vector<double> x;
  for (int i = 0; i <= count; ++i) x.push_back(lo * std::pow(hi / lo, double(i) / count));
  return x;
}

/// van Genuchten parameter sets: m = 1/(1 - lambda) from 1.11 (slope rising steeply off s = 0)
/// to 10, with and without residual and maximum saturations, and lambda = 1/2 (the embankment's,
/// which the law takes by a product and a square root instead of pow).
std::vector<VanGenuchten> van_genuchten_curves() {
  return {VanGenuchten::create(2e4, 0.1, 0.0, 1.0), VanGenuchten::create(2e4, 0.4, 0.05, 0.95),
          VanGenuchten::create(1e5, 0.6, 0.1, 1.0), VanGenuchten::create(5e3, 0.9, 0.2, 0.9),
          VanGenuchten::create(4e5, 0.5, 0.0, 0.95)};
}

TEST(RetentionCurves, LinearLawReproducesTable1) {
  const auto r = LinearRetention::create(1e-6, 0.0);  // a_s = 1e-3 1/kPa
  EXPECT_DOUBLE_EQ(r.saturation(0.5e6), 0.5);
  EXPECT_DOUBLE_EQ(r.effective_saturation(0.5e6), 0.5);
  EXPECT_DOUBLE_EQ(r.saturation(0.0), 1.0);
  EXPECT_DOUBLE_EQ(r.d_saturation(0.3e6), -1e-6);
}

TEST(RetentionCurves, LinearDerivativeMatchesCentralDifferences) {
  // s_min = 0.2: the law reaches its residual value at s = 0.8 MPa. Points approach both kinks
  // (s = 0 and s = 0.8 MPa) from either side without the difference stencil crossing them.
  const auto r = LinearRetention::create(1e-6, 0.2);
  const double h = 0.5;
  for (double s :
       {1.0, 10.0, 1e3, 1e5, 0.5e6, 0.79e6, 0.8e6 - 1.0, 0.8e6 + 1.0, 0.81e6, 5e6, -1.0, -1e4}) {
    const double fd = central_difference([&](double x) { return r.saturation(x); }, s, h);
    EXPECT_NEAR(r.d_saturation(s), fd, 1e-6 * std::abs(fd) + 1e-15) << "s = " << s;
    const double fd_e =
        central_difference([&](double x) { return r.effective_saturation(x); }, s, h);
    EXPECT_NEAR(r.d_effective_saturation(s), fd_e, 1e-6 * std::abs(fd_e) + 1e-15) << "s = " << s;
  }
}

TEST(RetentionCurves, LinearSecondDerivativeMatchesCentralDifferences) {
  // The slope is piecewise constant, so away from the kinks the difference quotient of
  // d_saturation is exactly 0; a stencil across a kink would give a_s / (2 h) = 1e-6 1/Pa^2,
  // far above the 1e-20 1/Pa^2 allowed. At the kinks themselves d2 is the one-sided 0.
  const auto r = LinearRetention::create(1e-6, 0.2);
  const double h = 0.5;
  for (double s :
       {1.0, 10.0, 1e3, 1e5, 0.5e6, 0.79e6, 0.8e6 - 1.0, 0.8e6 + 1.0, 0.81e6, 5e6, -1.0, -1e4}) {
    const double fd = central_difference([&](double x) { return r.d_saturation(x); }, s, h);
    EXPECT_NEAR(r.d2_saturation(s), fd, 1e-6 * std::abs(fd) + 1e-20) << "s = " << s;
    const double fd_e =
        central_difference([&](double x) { return r.d_effective_saturation(x); }, s, h);
    EXPECT_NEAR(r.d2_effective_saturation(s), fd_e, 1e-6 * std::abs(fd_e) + 1e-20) << "s = " << s;
  }
  for (double s : {0.0, 0.8e6, -1e5}) {
    EXPECT_EQ(r.d2_saturation(s), 0.0) << "s = " << s;
    EXPECT_EQ(r.d2_effective_saturation(s), 0.0) << "s = " << s;
  }
}

TEST(RetentionCurves, LinearSaturatedAndResidualBranches) {
  const auto r = LinearRetention::create(1e-6, 0.2);
  EXPECT_DOUBLE_EQ(r.saturation(-1e5), 1.0);  // negative suction is saturated
  EXPECT_DOUBLE_EQ(r.effective_saturation(-1e5), 1.0);
  EXPECT_EQ(r.d_saturation(0.0), 0.0);  // storage of a saturated soil: none from retention
  EXPECT_EQ(r.d_saturation(-1e5), 0.0);
  EXPECT_DOUBLE_EQ(r.d_saturation(1e-3), -1e-6);  // the slope jumps right after s = 0
  EXPECT_DOUBLE_EQ(r.saturation(0.4e6), 0.6);
  EXPECT_DOUBLE_EQ(r.effective_saturation(0.4e6), 0.5);
  EXPECT_DOUBLE_EQ(r.saturation(2e6), 0.2);  // clamped at s_min beyond s = 0.8 MPa
  EXPECT_EQ(r.d_saturation(2e6), 0.0);
  EXPECT_EQ(r.effective_saturation(2e6), 0.0);
  EXPECT_DOUBLE_EQ(r.saturation(1e300), 0.2);  // s -> inf
}

TEST(RetentionCurves, VanGenuchtenDerivativeMatchesCentralDifferences) {
  for (const VanGenuchten& r : van_genuchten_curves()) {
    // From x = (s/P0)^m = 1e-4 through the curved region to the tail; h small against s and the
    // curvature. Closer to s = 0, S_e = 1 - O(x) and its rounding (1e-16) swamps the difference
    // quotient; VanGenuchtenSlopeVanishesAtZeroSuction checks that part against the asymptote.
    const double s_lo = r.p0 * std::pow(1e-4, 1.0 - r.lambda);
    for (double s : log_points(s_lo, 1e3 * r.p0, 60)) {
      const double h = 1e-4 * s;
      const double fd_e =
          central_difference([&](double x) { return r.effective_saturation(x); }, s, h);
      EXPECT_NEAR(r.d_effective_saturation(s), fd_e, 1e-6 * std::abs(fd_e))
          << "p0 = " << r.p0 << ", lambda = " << r.lambda << ", s = " << s;
    }
    for (double s : log_points(s_lo, 1e1 * r.p0, 30)) {
      // S = s_min + tiny in the far tail: stop where S_e < 1e-4, before s_min's rounding shows.
      if (r.effective_saturation(s) < 1e-4) break;
      const double h = 1e-4 * s;
      const double fd = central_difference([&](double x) { return r.saturation(x); }, s, h);
      EXPECT_NEAR(r.d_saturation(s), fd, 1e-6 * std::abs(fd))
          << "p0 = " << r.p0 << ", lambda = " << r.lambda << ", s = " << s;
    }
  }
}

TEST(RetentionCurves, VanGenuchtenSecondDerivativeMatchesCentralDifferences) {
  // Central differences of the analytic slope D = dS_e/ds with h = 1e-5 s, from s = 1e-8 P0 to
  // 1e4 P0 (the slope itself is accurate to a few ulps there, unlike S_e = 1 - O(x) near 0).
  // With D varying on the scale s, the truncation error is ~ (h/s)^2 m^3 |D| / s ~ 1e-7 |D| / s
  // for m = 10, and rounding ~ 1e-15 |D| / h = 1e-10 |D| / s. The tolerance is 1e-6 of
  // |fd| + |D| / s: relative near the inflection point x = lambda, where d2 changes sign and
  // only an error measured against its natural size |D| / s is meaningful.
  for (const VanGenuchten& r : van_genuchten_curves()) {
    const double scale = r.s_max - r.s_min;
    for (double s : log_points(1e-8 * r.p0, 1e4 * r.p0, 96)) {
      const double h = 1e-5 * s;
      const double d_e = r.d_effective_saturation(s);
      const double fd_e =
          central_difference([&](double x) { return r.d_effective_saturation(x); }, s, h);
      EXPECT_NEAR(r.d2_effective_saturation(s), fd_e, 1e-6 * (std::abs(fd_e) + std::abs(d_e) / s))
          << "p0 = " << r.p0 << ", lambda = " << r.lambda << ", s = " << s;
      const double fd = central_difference([&](double x) { return r.d_saturation(x); }, s, h);
      EXPECT_NEAR(r.d2_saturation(s), fd, 1e-6 * (std::abs(fd) + scale * std::abs(d_e) / s))
          << "p0 = " << r.p0 << ", lambda = " << r.lambda << ", s = " << s;
    }
  }
}

TEST(RetentionCurves, VanGenuchtenSecondDerivativeChangesSignAtTheInflection) {
  // d2 S_e/ds^2 has the sign of x - lambda, x = (s/P0)^m: concave off saturation, convex tail.
  for (const VanGenuchten& r : van_genuchten_curves()) {
    const double m = 1.0 / (1.0 - r.lambda);
    const double s_inflection = r.p0 * std::pow(r.lambda, 1.0 / m);
    EXPECT_LT(r.d2_saturation(0.9 * s_inflection), 0.0) << "lambda = " << r.lambda;
    EXPECT_GT(r.d2_saturation(1.1 * s_inflection), 0.0) << "lambda = " << r.lambda;
    EXPECT_NEAR(r.d2_effective_saturation(s_inflection), 0.0,
                1e-12 * std::abs(r.d_effective_saturation(s_inflection)) / s_inflection);
  }
}

TEST(RetentionCurves, VanGenuchtenSecondDerivativeNearZeroSuction) {
  for (const VanGenuchten& r : van_genuchten_curves()) {
    // Leading term as s -> 0+: d2S/ds^2 = -(s_max - s_min) lambda^2 m^2 (s/P0)^(m - 2) / P0^2,
    // unbounded for m < 2 (lambda < 1/2), -> 0 for m > 2; finite at s = 1e-12 P0 either way.
    const double m = 1.0 / (1.0 - r.lambda), s = 1e-12 * r.p0;
    const double asymptote = -(r.s_max - r.s_min) * r.lambda * r.lambda * m * m *
                             std::pow(s / r.p0, m - 2.0) / (r.p0 * r.p0);
    EXPECT_TRUE(std::isfinite(r.d2_saturation(s))) << "lambda = " << r.lambda;
    EXPECT_NEAR(r.d2_saturation(s), asymptote, 1e-9 * std::abs(asymptote));
    // Its magnitude grows towards s = 0 for m < 2 and shrinks for m > 2; for m = 2 it rises to
    // its finite limit, which it reaches well before s = 1e-12 P0 and then keeps to the
    // rounding of the logarithms it is formed from (a few ulps).
    double previous = std::abs(r.d2_saturation(1e-2 * r.p0));
    for (double s_k : log_points(1e-3 * r.p0, 1e-12 * r.p0, 27)) {
      const double magnitude = std::abs(r.d2_saturation(s_k));
      if (m < 2.0) {
        EXPECT_GT(magnitude, previous) << "lambda = " << r.lambda << ", s = " << s_k;
      } else if (m == 2.0) {
        EXPECT_GE(magnitude, previous * (1.0 - 1e-14))
            << "lambda = " << r.lambda << ", s = " << s_k;
      } else {
        EXPECT_LT(magnitude, previous) << "lambda = " << r.lambda << ", s = " << s_k;
      }
      previous = magnitude;
    }
    // Saturated: 0, not the one-sided limit at 0+.
    for (double s_sat : {0.0, -1.0, -1e4}) {
      EXPECT_EQ(r.d2_saturation(s_sat), 0.0);
      EXPECT_EQ(r.d2_effective_saturation(s_sat), 0.0);
    }
  }
  // P0 = 1 mPa, m = 1.0101: at s = 1e-310 Pa, (s/P0)^m and s^2 are denormal or 0, yet the value
  // ~ -lambda^2 m^2 (s/P0)^(m - 2) / P0^2 = -1.8e305 is a double and must come out as such; at
  // s = 5e-324 the true value, ~ -1e319, is held at -DBL_MAX instead of -inf or NaN.
  const auto steep = VanGenuchten::create(1e-3, 0.01, 0.0, 1.0);
  for (double s : {5e-324, 1e-310, 1e-300, 1e-200, 1e-15}) {
    EXPECT_TRUE(std::isfinite(steep.d2_saturation(s))) << "s = " << s;
    EXPECT_TRUE(std::isfinite(steep.d2_effective_saturation(s))) << "s = " << s;
    EXPECT_LT(steep.d2_saturation(s), 0.0) << "s = " << s;
    const double m = 1.0 / 0.99;
    const double log_asymptote =
        2.0 * std::log(0.01 * m) + (m - 2.0) * std::log(s) - m * std::log(1e-3);
    if (log_asymptote < std::log(std::numeric_limits<double>::max())) {
      EXPECT_NEAR(steep.d2_saturation(s), -std::exp(log_asymptote), 1e-9 * std::exp(log_asymptote))
          << "s = " << s;
    }
  }
  EXPECT_EQ(steep.d2_saturation(5e-324), -std::numeric_limits<double>::max());
}

TEST(RetentionCurves, VanGenuchtenLimits) {
  for (const VanGenuchten& r : van_genuchten_curves()) {
    EXPECT_DOUBLE_EQ(r.saturation(0.0), r.s_max);
    EXPECT_DOUBLE_EQ(r.saturation(-1e4), r.s_max);  // negative suction is saturated
    EXPECT_EQ(r.effective_saturation(0.0), 1.0);
    EXPECT_EQ(r.d_saturation(0.0), 0.0);
    EXPECT_EQ(r.d_saturation(-1e4), 0.0);
    // S -> s_min as s -> inf: S_e ~ (s/P0)^(-lambda m), slowly for small lambda.
    EXPECT_NEAR(r.saturation(1e300), r.s_min, 1e-12);
    EXPECT_LT(r.effective_saturation(1e6 * r.p0), r.effective_saturation(1e3 * r.p0));
    EXPECT_GT(r.effective_saturation(1e6 * r.p0), 0.0);
    EXPECT_NEAR(r.effective_saturation(1e300), 0.0, 1e-12);
    EXPECT_DOUBLE_EQ(r.effective_saturation(r.p0), std::pow(2.0, -r.lambda));  // x = 1
  }
}

/// Laws whose occluded gas gives way (OccludedGas): van Genuchten at S_max = 0.95 over 1 kPa and
/// a table at S(0) = 0.9 over 200 Pa, each with its S(0) and scale.
struct OccludedCase {
  RetentionCurve law;
  double s0, scale;
};
std::vector<OccludedCase> occluded_cases() {
  auto table = TabulatedRetention::create({{0, 0.9}, {500, 0.89}, {5e3, 0.8}, {2e4, 0.5}});
  table.occluded = OccludedGas::create(200.0, 0.9, "S(0)");
  return {{VanGenuchten::create(4e5, 0.5, 0.0, 0.95, 1e3), 0.95, 1e3}, {table, 0.9, 200.0}};
}

TEST(RetentionCurves, AnOccludedGasGivesWayWithExactSlopes) {
  // At s < 0: dS/ds and d2S/ds2 against central differences (h = 1e-4 of the nearer of |s| and
  // the scale), S continuous at s = 0 and rising monotonically to 1 as the liquid's pressure
  // exceeds the gas's, S_e held at 1 with zero slopes (the relative permeabilities are the
  // saturated ones).
  for (const auto& [law, s0, scale] : occluded_cases())
    std::visit(
        [&, s0 = s0, scale = scale](const auto& r) {
          EXPECT_EQ(r.saturation(0.0), s0);
          EXPECT_NEAR(r.saturation(-1e-12 * scale), s0, 1e-12);
          EXPECT_NEAR(r.d_saturation(0.0), -(1.0 - s0) / scale, 1e-15 / scale);
          double previous = r.saturation(1e3);
          for (double x : log_points(1e-3, 30.0, 40)) {
            const double s = -x * scale, h = 1e-4 * std::min(-s, scale);
            SCOPED_TRACE(::testing::Message() << "S(0) = " << s0 << ", s = " << s);
            const double fd = central_difference([&](double y) { return r.saturation(y); }, s, h);
            EXPECT_NEAR(r.d_saturation(s), fd, 1e-6 * std::abs(fd) + 1e-14 / h);
            const double fd2 =
                central_difference([&](double y) { return r.d_saturation(y); }, s, h);
            EXPECT_NEAR(r.d2_saturation(s), fd2, 1e-6 * std::abs(fd2) + 1e-14 / (h * scale));
            const double sat = r.saturation(s);
            EXPECT_GT(sat, previous);
            EXPECT_LE(sat, 1.0);
            previous = sat;
            EXPECT_EQ(r.effective_saturation(s), 1.0);
            EXPECT_EQ(r.d_effective_saturation(s), 0.0);
            EXPECT_EQ(r.d2_effective_saturation(s), 0.0);
            const SaturationValues v = r.saturation_and_slope(s);
            EXPECT_EQ(v.s_l, sat);
            EXPECT_EQ(v.ds, r.d_saturation(s));
            EXPECT_EQ(v.se, 1.0);
          }
          EXPECT_NEAR(r.saturation(-40.0 * scale), 1.0, 1e-15);
        },
        law);
}

TEST(RetentionCurves, WithoutGiveTheOccludedGasBranchIsFlat) {
  // occluded_gas_scale 0 (the default): the paper's law, S = S_max and zero slopes at s <= 0.
  for (const double s0 : {0.95, 1.0}) {
    const auto r = VanGenuchten::create(4e5, 0.5, 0.0, s0);
    EXPECT_EQ(r.occluded.scale, 0.0);
    for (double s : {0.0, -1.0, -1e5}) {
      EXPECT_EQ(r.saturation(s), s0);
      EXPECT_EQ(r.d_saturation(s), 0.0);
      EXPECT_EQ(r.d2_saturation(s), 0.0);
    }
  }
}

TEST(RetentionCurves, VanGenuchtenSlopeVanishesAtZeroSuction) {
  // m = 1/(1 - lambda) > 1: dS/ds ~ -(s/P0)^(m - 1) -> 0 as s -> 0+, decreasing in magnitude.
  for (const VanGenuchten& r : van_genuchten_curves()) {
    double previous = std::abs(r.d_saturation(1e-2 * r.p0));
    for (double s : log_points(1e-3 * r.p0, 1e-12 * r.p0, 27)) {
      const double slope = std::abs(r.d_saturation(s));
      EXPECT_LT(slope, previous) << "lambda = " << r.lambda << ", s = " << s;
      previous = slope;
    }
    // Leading term as s -> 0+: |dS/ds| = (s_max - s_min) lambda m (s/P0)^(m - 1) / P0.
    const double m = 1.0 / (1.0 - r.lambda), s = 1e-12 * r.p0;
    const double asymptote =
        (r.s_max - r.s_min) * r.lambda * m * std::pow(s / r.p0, m - 1.0) / r.p0;
    EXPECT_NEAR(std::abs(r.d_saturation(s)), asymptote, 1e-9 * asymptote);
    EXPECT_TRUE(std::isfinite(r.d_saturation(5e-324)));  // no 0/0 at denormal suctions
    EXPECT_LE(r.d_saturation(5e-324), 0.0);
  }
}

TEST(RetentionCurves, VanGenuchtenAtLambdaOneHalfIsThePowersToTheirRounding) {
  // lambda = 1/2 is taken as x = r^2 and S_e = 1/sqrt(1 + x): the same numbers as the general
  // formula's pows to a few ulps, and continuous with the pow branch at its neighbours.
  const auto r = VanGenuchten::create(4e5, 0.5, 0.0, 0.95);
  const auto below = VanGenuchten::create(4e5, 0.5 - 1e-9, 0.0, 0.95);
  const auto above = VanGenuchten::create(4e5, 0.5 + 1e-9, 0.0, 0.95);
  for (double s : log_points(1e-6 * r.p0, 1e6 * r.p0, 60)) {
    const double x = std::pow(s / r.p0, 2.0), se = std::pow(1.0 + x, -0.5);
    const double slope = -0.5 * 2.0 * se * (x / (1.0 + x)) / s;
    EXPECT_NEAR(r.effective_saturation(s), se, 1e-15 * se) << s;
    EXPECT_NEAR(r.d_effective_saturation(s), slope, 1e-14 * std::abs(slope)) << s;
    const SaturationValues v = r.saturation_and_slope(s);
    EXPECT_EQ(v.s_l, r.saturation(s));
    EXPECT_EQ(v.ds, r.d_saturation(s));
    for (const VanGenuchten& n : {below, above}) {
      EXPECT_NEAR(r.saturation(s), n.saturation(s), 1e-7 * r.saturation(s)) << s;
      EXPECT_NEAR(r.d_saturation(s), n.d_saturation(s), 1e-7 * std::abs(r.d_saturation(s))) << s;
      // 1/s^2 is the second derivative's scale: it changes sign at the inflection.
      EXPECT_NEAR(r.d2_saturation(s), n.d2_saturation(s),
                  1e-7 * (std::abs(r.d2_saturation(s)) + 1.0 / (s * s)))
          << s;
    }
  }
}

TEST(RetentionCurves, VanGenuchtenStaysFiniteForExtremeSuctions) {
  // lambda = 0.9 gives m = 10: (s/P0)^m overflows for s > ~1e30 P0; the law must not give NaN.
  const auto r = VanGenuchten::create(5e3, 0.9, 0.2, 0.9);
  for (double s : {1e20, 1e40, 1e200, 1e308}) {
    EXPECT_TRUE(std::isfinite(r.saturation(s))) << s;
    EXPECT_TRUE(std::isfinite(r.d_saturation(s))) << s;
    EXPECT_LE(r.d_saturation(s), 0.0);
    EXPECT_TRUE(std::isfinite(r.d2_saturation(s))) << s;
    EXPECT_TRUE(std::isfinite(r.d2_effective_saturation(s))) << s;
    EXPECT_GE(r.d2_saturation(s), 0.0);  // the convex tail
    EXPECT_NEAR(r.saturation(s), 0.2, 1e-12);
  }
}

TEST(RetentionCurves, SaturationIsNonIncreasingInSuction) {
  std::vector<RetentionCurve> curves = {LinearRetention::create(1e-6, 0.0),
                                        LinearRetention::create(1e-4, 0.3)};
  for (const VanGenuchten& r : van_genuchten_curves()) curves.emplace_back(r);
  std::vector<double> s_values = {-1e5, -1.0, 0.0};
  for (double s : log_points(1e-3, 1e9, 600)) s_values.push_back(s);
  for (const RetentionCurve& curve : curves) {
    std::visit(
        [&](const auto& r) {
          double previous = r.saturation(s_values.front());
          for (double s : s_values) {
            EXPECT_LE(r.saturation(s), previous) << "s = " << s;
            EXPECT_LE(r.d_saturation(s), 0.0) << "s = " << s;
            EXPECT_GE(r.effective_saturation(s), 0.0) << "s = " << s;
            EXPECT_LE(r.effective_saturation(s), 1.0) << "s = " << s;
            previous = r.saturation(s);
          }
        },
        curve);
  }
}

TEST(RetentionCurves, FactoriesKeepValidParameters) {
  const auto linear = LinearRetention::create(1e-6, 0.1);
  EXPECT_EQ(linear.a_s, 1e-6);
  EXPECT_EQ(linear.s_min, 0.1);
  const auto vg = VanGenuchten::create(2e4, 0.4, 0.05, 0.95);
  EXPECT_EQ(vg.p0, 2e4);
  EXPECT_EQ(vg.lambda, 0.4);
  EXPECT_EQ(vg.s_min, 0.05);
  EXPECT_EQ(vg.s_max, 0.95);
}

TEST(RetentionCurves, FactoriesRejectOutOfRangeAndNonFiniteValues) {
  for (double bad : {0.0, -1e-6, 1.0, kNaN, kInf})
    expect_parameter_error([&] { LinearRetention::create(bad, 0.0); }, "a_s");
  for (double bad : {-0.1, 1.0, 0.995, kNaN, kInf})
    expect_parameter_error([&] { LinearRetention::create(1e-6, bad); }, "residual_saturation");
  for (double bad : {0.0, -2e4, 1e11, kNaN, kInf})
    expect_parameter_error([&] { VanGenuchten::create(bad, 0.4, 0.0, 1.0); }, "p0");
  for (double bad : {0.0, 1.0, -0.4, 1.5, kNaN, kInf})
    expect_parameter_error([&] { VanGenuchten::create(2e4, bad, 0.0, 1.0); }, "lambda");
  for (double bad : {0.0, 1.01, -1.0, kNaN, kInf})
    expect_parameter_error([&] { VanGenuchten::create(2e4, 0.4, 0.0, bad); }, "max_saturation");
  for (double bad : {-0.1, 0.9, 0.95, kNaN, kInf})
    expect_parameter_error([&] { VanGenuchten::create(2e4, 0.4, bad, 0.9); },
                           "residual_saturation");
  for (double bad : {-1.0, 0.5, 1.1e7, kNaN, kInf})
    expect_parameter_error([&] { VanGenuchten::create(2e4, 0.4, 0.0, 0.9, bad); },
                           "occluded_gas_scale");
  // A law that saturates the pores leaves no gas to occlude.
  expect_parameter_error([&] { VanGenuchten::create(2e4, 0.4, 0.0, 1.0, 1e3); },
                         "occluded_gas_scale");
  expect_parameter_error([&] { OccludedGas::create(1e3, 0.99995, "S(0)"); }, "occluded_gas_scale");
  EXPECT_EQ(VanGenuchten::create(2e4, 0.4, 0.0, 1.0, 0.0).occluded.scale, 0.0);
  EXPECT_EQ(VanGenuchten::create(2e4, 0.4, 0.0, 0.9, 1.0).occluded.scale, 1.0);
  EXPECT_EQ(OccludedGas::create(1e7, 0.9, "S(0)").scale, 1e7);
}

}  // namespace test_retention
}  // namespace unsatmpm::physics

// Measured curves (physics/monotone_table.hpp, TabulatedRetention, TabulatedRelPerm): through the
// data, monotone between them (no overshoot), exact for a straight line, slope and curvature the
// derivatives of the value (central differences), and errors naming the offending point.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "physics/parameter_error.hpp"
#include "physics/permeability.hpp"
#include "physics/retention.hpp"

namespace unsatmpm::physics {
namespace test_monotone_table {

using Points = std::vector<std::array<double, 2>>;

/// A van Genuchten curve sampled at uneven suctions: steep and curved, like measured data.
Points retention_data() {
  const VanGenuchten vg = VanGenuchten::create(2e4, 0.4, 0.1, 1.0);
  Points p;
  for (const double s : {0.0, 1e3, 3e3, 7e3, 1.5e4, 3e4, 6e4, 1.2e5, 3e5, 1e6})
    p.push_back({s, vg.saturation(s)});
  return p;
}

TEST(MonotoneTable, PassesThroughItsPointsAndNeverOvershoots) {
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 50; ++trial) {
    Points p;
    double x = 0.0, y = 1.0;
    for (int k = 0; k < 8; ++k) {
      p.push_back({x, y});
      x += 0.01 + u(gen) * (k % 3 == 0 ? 10.0 : 0.5);  // uneven spacing
      y -= (k % 2 == 0 ? 0.0 : u(gen) * 0.2);          // flat stretches between drops
    }
    const auto t =
        MonotoneTable::create(p, MonotoneTable::Direction::decreasing, 0.0, 1.0, "x", "y");
    for (const auto& [xk, yk] : p) EXPECT_NEAR(t.value(xk), yk, 1e-14);
    double previous = t.value(p.front()[0] - 1.0);
    for (double xs = p.front()[0] - 1.0; xs <= p.back()[0] + 1.0; xs += 1e-3) {
      const double v = t.value(xs);
      EXPECT_LE(v, previous + 1e-15) << "trial " << trial << " x = " << xs;
      EXPECT_LE(t.slope(xs), 1e-15);
      previous = v;
    }
  }
}

TEST(MonotoneTable, ReproducesAStraightLine) {
  const auto t = MonotoneTable::create({{0.0, 0.1}, {1.0, 0.3}, {3.0, 0.7}, {3.5, 0.8}},
                                       MonotoneTable::Direction::increasing, 0.0, 1.0, "x", "y");
  for (double x = 0.05; x < 3.5; x += 0.1) {
    EXPECT_NEAR(t.value(x), 0.1 + 0.2 * x, 1e-14);
    EXPECT_NEAR(t.slope(x), 0.2, 1e-13);
    EXPECT_NEAR(t.curvature(x), 0.0, 1e-12);
  }
}

TEST(MonotoneTable, SlopeAndCurvatureAreTheDerivatives) {
  const auto r = TabulatedRetention::create(retention_data());
  for (double s = 500.0; s < 9e5; s *= 1.37) {
    const double h = 1e-4 * s;
    const double fd1 = (r.saturation(s + h) - r.saturation(s - h)) / (2 * h);
    const double fd2 = (r.d_saturation(s + h) - r.d_saturation(s - h)) / (2 * h);
    EXPECT_NEAR(r.d_saturation(s), fd1, 1e-6 * std::abs(fd1) + 1e-15) << s;
    EXPECT_NEAR(r.d2_saturation(s), fd2, 1e-5 * std::abs(fd2) + 1e-18) << s;
    EXPECT_NEAR(r.d_effective_saturation(s), r.d_saturation(s) / (r.table.front() - r.table.back()),
                1e-15);
  }
  // Saturated side and the held tail.
  EXPECT_EQ(r.saturation(-5.0), r.table.front());
  EXPECT_EQ(r.d_saturation(-5.0), 0.0);
  EXPECT_EQ(r.saturation(2e6), r.table.back());
  EXPECT_EQ(r.d_saturation(2e6), 0.0);
  EXPECT_EQ(r.effective_saturation(0.0), 1.0);
  EXPECT_EQ(r.effective_saturation(2e6), 0.0);
}

TEST(MonotoneTable, CloseToTheCurveItSamples) {
  // Ten points of a van Genuchten curve: the interpolant stays within 0.02 of it everywhere.
  const VanGenuchten vg = VanGenuchten::create(2e4, 0.4, 0.1, 1.0);
  const auto r = TabulatedRetention::create(retention_data());
  for (double s = 10.0; s < 1e6; s *= 1.1)
    EXPECT_NEAR(r.saturation(s), vg.saturation(s), 0.02) << s;
}

TEST(MonotoneTable, RelativePermeabilitiesGoTheirWay) {
  const auto kl =
      TabulatedRelPerm::create({{0.0, 0.0}, {0.5, 0.05}, {0.8, 0.3}, {1.0, 1.0}}, false);
  const auto kg = TabulatedRelPerm::create({{0.0, 1.0}, {0.4, 0.3}, {0.9, 1e-3}, {1.0, 0.0}}, true);
  for (double se = 0.0; se <= 1.0; se += 0.01) {
    EXPECT_GE(kl.d_value(se), 0.0);
    EXPECT_LE(kg.d_value(se), 0.0);
  }
  EXPECT_EQ(kl.value(1.5), 1.0);
  EXPECT_EQ(kg.value(-0.5), 1.0);
  EXPECT_EQ(kl.d_value(1.5), 0.0);
}

std::string error_of(const Points& p, bool retention) {
  try {
    if (retention)
      TabulatedRetention::create(p);
    else
      TabulatedRelPerm::create(p, false);
  } catch (const ParameterError& e) {
    return e.parameter() + ": " + e.what();
  }
  return "";
}

TEST(MonotoneTable, ErrorsNameTheOffendingPoint) {
  EXPECT_NE(error_of({{0, 1}, {100, 0.9}, {100, 0.8}}, true).find("points[2]: point 2"),
            std::string::npos);
  EXPECT_NE(error_of({{0, 1}, {100, 0.9}, {200, 0.95}}, true).find("points[2]"), std::string::npos);
  EXPECT_NE(error_of({{0, 1}, {100, 0.9}, {200, 0.95}}, true).find("must not increase"),
            std::string::npos);
  EXPECT_NE(error_of({{0, 1}, {100, 1.2}}, true).find("points[1]"), std::string::npos);
  EXPECT_NE(error_of({{10, 1}, {100, 0.5}}, true).find("points[0]"), std::string::npos);
  EXPECT_NE(error_of({{0, 1}}, true).find("at least 2 points"), std::string::npos);
  EXPECT_NE(error_of({{0, 1}, {100, 0.995}}, true).find("at least 0.01"), std::string::npos);
  EXPECT_NE(error_of({{0, 0}, {0.5, 0.2}, {0.9, 1}}, false).find("points[2]"), std::string::npos);
  EXPECT_NE(error_of({{0, 0}, {0.5, 0.2}, {1, 0.1}}, false).find("must not decrease"),
            std::string::npos);
  EXPECT_NE(error_of({{0, 0}, {0.5, NAN}, {1, 1}}, false).find("not a finite number"),
            std::string::npos);
}

}  // namespace test_monotone_table
}  // namespace unsatmpm::physics

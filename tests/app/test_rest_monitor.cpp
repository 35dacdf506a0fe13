// When a run is at rest (app/rest_monitor.hpp): below a fraction of the kinetic energy's peak for
// the hold time, once the peak has passed its floor; the state survives a checkpoint.
#include "app/rest_monitor.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

namespace test_rest_monitor {

using unsatmpm::RestMonitor;
using unsatmpm::RestSpec;

constexpr RestSpec kSpec{1e-2, 0.5, 1.0};  // 1 % of the peak for 0.5 s, a peak above 1 J

/// Feeds energy(t) at steps of dt from t = 0; the time at which the monitor says "at rest", or
/// NaN if it never does before t_end.
template <class F>
double rest_time(RestMonitor& m, F energy, double dt, double t_end) {
  for (int k = 1; k * dt <= t_end; ++k)
    if (m.at_rest(k * dt, energy(k * dt))) return k * dt;
  return std::nan("");
}

TEST(RestMonitor, AtRestAfterHoldingBelowTheFractionOfThePeak) {
  RestMonitor m(kSpec);
  // A peak of 100 J at t = 1, then exponential decay: below 1 J (1 %) from t = 1 + ln(100)/2.
  const auto energy = [](double t) {
    return t < 1.0 ? 100.0 * t : 100.0 * std::exp(-2.0 * (t - 1.0));
  };
  const double below = 1.0 + std::log(100.0) / 2.0;
  const double t = rest_time(m, energy, 1e-3, 10.0);
  EXPECT_NEAR(t, below + kSpec.hold, 2e-3);
  EXPECT_TRUE(m.stopped());
  EXPECT_NE(m.message(t, energy(t)).find("at rest at t = "), std::string::npos);
}

TEST(RestMonitor, ARiseAboveTheFractionStartsTheHoldAgain) {
  RestMonitor m(kSpec);
  // Peak 100 J, then 0.5 J except for a burst of 5 J at t in [1.3, 1.4), 0.3 s into the hold: at
  // rest 0.5 s after 1.4, not after 1.0.
  const auto energy = [](double t) {
    if (t <= 1.0) return 100.0;
    return t >= 1.3 && t < 1.4 ? 5.0 : 0.5;
  };
  EXPECT_NEAR(rest_time(m, energy, 1e-3, 10.0), 1.4 + kSpec.hold, 2e-3);
}

TEST(RestMonitor, NeverAtRestWhileThePeakStaysBelowItsFloor) {
  RestMonitor m(kSpec);
  const auto energy = [](double t) { return t < 1.0 ? 0.9 : 1e-9; };  // peak 0.9 J < 1 J
  EXPECT_TRUE(std::isnan(rest_time(m, energy, 1e-2, 20.0)));
  EXPECT_FALSE(m.stopped());
}

TEST(RestMonitor, WithoutARuleNeverAtRest) {
  RestMonitor m;
  EXPECT_FALSE(m.active());
  EXPECT_FALSE(m.at_rest(1.0, 0.0));
  EXPECT_FALSE(m.at_rest(100.0, 0.0));
}

TEST(RestMonitor, ACheckpointKeepsThePeakAndTheStretchBelow) {
  const auto energy = [](double t) { return t < 1.0 ? 100.0 : 0.1; };
  RestMonitor whole(kSpec), first(kSpec), second(kSpec);
  const double t_whole = rest_time(whole, energy, 1e-2, 10.0);
  // Part-way through the stretch below: after t = 1.2 s (below since 1.01 s).
  for (int k = 1; k <= 120; ++k) ASSERT_FALSE(first.at_rest(k * 1e-2, energy(k * 1e-2)));
  const auto file = std::filesystem::temp_directory_path() / "unsatmpm_rest_monitor.bin";
  {
    unsatmpm::CheckpointWriter w(file, file.string());
    first.save(w);
    w.finish();
  }
  unsatmpm::CheckpointReader r(file);
  second.restore(r);
  r.finish();
  std::filesystem::remove(file);
  double t = std::nan("");
  for (int k = 121; k * 1e-2 <= 10.0; ++k)
    if (second.at_rest(k * 1e-2, energy(k * 1e-2))) {
      t = k * 1e-2;
      break;
    }
  EXPECT_EQ(t, t_whole);
  // A fresh monitor from t = 1.21 on never sees the 100 J peak: it would not stop then.
  RestMonitor fresh(kSpec);
  EXPECT_FALSE(fresh.at_rest(1.21, 0.1));
}

}  // namespace test_rest_monitor

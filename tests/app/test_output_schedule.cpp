// The run loop's schedule: output times with the end time appended, steps clipped onto them,
// histories at their interval.
#include "app/output_schedule.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace test_output_schedule {

using unsatmpm::Case;
using unsatmpm::OutputSchedule;

Case schedule_case(std::vector<double> times, double history_interval) {
  Case c;
  c.solver.end_time = 1.0;
  c.output.times = std::move(times);
  c.output.history_interval = history_interval;
  return c;
}

/// Steps of `dt` from 0 to the end; the times at which an output fell due.
std::vector<double> outputs_of(OutputSchedule& s, double dt) {
  std::vector<double> due;
  double t = 0.0;
  while (s.before_end(t)) {
    t += s.clip(t, dt);
    if (s.output_due(t)) due.push_back(t);
  }
  return due;
}

TEST(OutputSchedule, StepsLandOnEveryOutputTimeAndTheEnd) {
  OutputSchedule s(schedule_case({0.25, 0.6}, 0.0));
  const auto due = outputs_of(s, 0.1);
  ASSERT_EQ(due.size(), 3u);
  EXPECT_EQ(due[0], 0.25);
  EXPECT_EQ(due[1], 0.6);
  EXPECT_EQ(due[2], 1.0);
}

TEST(OutputSchedule, TheEndIsNotRepeated) {
  OutputSchedule s(schedule_case({0.5, 1.0}, 0.0));
  const auto due = outputs_of(s, 0.3);
  ASSERT_EQ(due.size(), 2u);
  EXPECT_EQ(due.back(), 1.0);
}

TEST(OutputSchedule, ATimeWithinRoundingSnapsOntoTheOutputTime) {
  OutputSchedule s(schedule_case({0.3}, 0.0));
  double t = 0.1 + 0.2;  // 0.30000000000000004
  ASSERT_NE(t, 0.3);
  EXPECT_TRUE(s.output_due(t));
  EXPECT_EQ(t, 0.3);
}

TEST(OutputSchedule, HistoriesAtTheirInterval) {
  OutputSchedule s(schedule_case({}, 0.25));
  int n = 0;
  for (double t = 0.05; t < 1.0 + 1e-12; t += 0.05) n += s.history_due(t);
  EXPECT_EQ(n, 4);  // at 0.25, 0.5, 0.75 (or within a step after) and 1.0
}

}  // namespace test_output_schedule

// The run loop's schedule: output times with the end time appended, steps clipped onto them,
// histories at their interval.
#include "app/output_schedule.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "checkpoint/checkpoint_file.hpp"

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

// Rows at the multiples of the interval, not an interval after the last row: steps of 0.004 s
// and rows every 0.01 s give one row per 0.01 s to the end (the end's included), each within a
// step after its multiple. An interval after the last row drifted by a step's overshoot per
// row: 83 rows, about one per 0.012 s, and none at the end.
TEST(OutputSchedule, HistoryRowsDoNotDriftAndTheEndHasOne) {
  OutputSchedule s(schedule_case({}, 0.01));
  std::vector<double> rows;
  for (double t = 0.0; s.before_end(t);) {
    t += s.clip(t, 0.004);
    if (s.history_due(t)) rows.push_back(t);
  }
  ASSERT_EQ(rows.size(), 100u);
  for (std::size_t k = 0; k < rows.size(); ++k) {
    EXPECT_GE(rows[k], 0.01 * static_cast<double>(k + 1) - 1e-12) << k;
    EXPECT_LT(rows[k], 0.01 * static_cast<double>(k + 1) + 0.004) << k;
  }
  EXPECT_EQ(rows.back(), 1.0);
  // An end time between multiples still gets its row.
  Case c = schedule_case({}, 0.3);
  OutputSchedule e(c);
  int n = 0;
  double last = 0.0;
  for (double t = 0.0; e.before_end(t);) {
    t += e.clip(t, 0.1);
    if (e.history_due(t)) ++n, last = t;
  }
  EXPECT_EQ(n, 4);  // 0.3, 0.6, 0.9, 1.0
  EXPECT_NEAR(last, 1.0, 1e-12);
}

/// Writes the schedule `from` after it reached `t_saved`, and restores it into `to` at `t_resumed`;
/// the reader's error message, empty when none.
std::string restored(OutputSchedule& from, double t_saved, OutputSchedule& to, double t_resumed) {
  for (double t = 0.0; t < t_saved;) {
    t += from.clip(t, t_saved - t);
    from.output_due(t);
  }
  const auto file = std::filesystem::temp_directory_path() /
                    ("unsatmpm_schedule_" +
                     std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + ".bin");
  {
    unsatmpm::CheckpointWriter w(file, file.string());
    from.save(w);
    w.finish();
  }
  std::string error;
  try {
    unsatmpm::CheckpointReader r(file);
    to.restore(r, t_resumed);
    r.finish();
  } catch (const unsatmpm::CheckpointError& e) {
    error = e.what();
  }
  std::filesystem::remove(file);
  return error;
}

TEST(OutputSchedule, ARestoredScheduleGoesOnToTheSameOutputs) {
  OutputSchedule saved(schedule_case({0.25, 0.6}, 0.0)), resumed(schedule_case({0.25, 0.6}, 0.0));
  ASSERT_EQ(restored(saved, 0.4, resumed, 0.4), "");
  double t = 0.4;
  t += resumed.clip(t, 1.0);
  EXPECT_EQ(t, 0.6);
  EXPECT_TRUE(resumed.output_due(t));
}

TEST(OutputSchedule, ANextOutputTimeNotAfterTheRunsTimeIsRefused) {
  // Saved at 0.25 s with 0.6 s next; resumed as if at 0.6 s (a case or time that does not fit):
  // the next step would be clipped to zero length.
  OutputSchedule saved(schedule_case({0.25, 0.6}, 0.0)), resumed(schedule_case({0.25, 0.6}, 0.0));
  const std::string e = restored(saved, 0.25, resumed, 0.6);
  EXPECT_NE(e.find("next output time (0.6 s) is not after its time (0.6 s)"), std::string::npos)
      << e;
  // At the end time there is no next step, and nothing to refuse.
  OutputSchedule ended(schedule_case({0.25}, 0.0)), at_end(schedule_case({0.25}, 0.0));
  EXPECT_EQ(restored(ended, 1.0, at_end, 1.0), "");
}

}  // namespace test_output_schedule

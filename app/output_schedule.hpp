// When the run loop writes: the case's output times (with the end time appended) and its history
// interval; and the last good state it keeps for a numerical failure.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include <fmt/format.h>

#include "checkpoint/point_state.hpp"
#include "input/case.hpp"
#include "numerics/fluid_points.hpp"
#include "numerics/material_points.hpp"

namespace unsatmpm {

class OutputSchedule {
 public:
  explicit OutputSchedule(const Case& c)
      : end_(c.solver.end_time),
        eps_(1e-12 * end_),
        times_(c.output.times),
        history_interval_(c.output.history_interval),
        next_history_(history_interval_) {
    if (times_.empty() || times_.back() < end_ - eps_) times_.push_back(end_);
  }

  double end_time() const { return end_; }

  /// The next output and history times (a checkpoint keeps them).
  void save(CheckpointWriter& w) const {
    w.value("schedule.next", static_cast<std::int64_t>(next_));
    w.value("schedule.next_history", next_history_);
  }
  /// Restores them for a run at time t [s]; a next output time not after t (which would clip
  /// the next step to zero length) is refused as a checkpoint that does not fit its case.
  void restore(CheckpointReader& r, double t) {
    const auto next = r.value<std::int64_t>("schedule.next");
    if (next < 0 || static_cast<std::size_t>(next) >= times_.size())
      r.fail("its next output time is not one of the case's");
    next_ = static_cast<std::size_t>(next);
    if (before_end(t) && times_[next_] <= t + eps_)
      r.fail(fmt::format("its next output time ({:.9g} s) is not after its time ({:.9g} s)",
                         times_[next_], t));
    next_history_ = r.value<double>("schedule.next_history");
  }
  /// True while t [s] is short of the end time.
  bool before_end(double t) const { return t < end_ - eps_; }
  /// The step dt from t, clipped so that it lands on the next output time.
  double clip(double t, double dt) const { return std::min(dt, times_[next_] - t); }

  /// True when t has reached the next history time, or the end time; the next is then the first
  /// multiple of the history interval after t (not an interval after t: the rows would drift,
  /// a step's overshoot at every row, and a run of 2 s at 0.01 s wrote 194 rows).
  bool history_due(double t) {
    if (t < next_history_ - eps_ && before_end(t)) return false;
    if (history_interval_ > 0.0)
      next_history_ = (std::floor((t + eps_) / history_interval_) + 1.0) * history_interval_;
    return true;
  }

  /// True when t has reached the next output time; t is then snapped onto it (when within
  /// 1e-9 of the end time) and the output time after it becomes the next.
  bool output_due(double& t) {
    if (t < times_[next_] - eps_) return false;
    if (std::abs(t - times_[next_]) < 1e-9 * end_) t = times_[next_];
    if (next_ + 1 < times_.size()) ++next_;
    return true;
  }

 private:
  double end_, eps_;
  std::vector<double> times_;  // [s], ascending, the last at the end time
  std::size_t next_ = 0;
  double history_interval_, next_history_;
};

/// The state written as points_last_good.vtu after a numerical failure.
template <int D>
struct LastGoodState {
  numerics::MaterialPoints<D> points;
  numerics::FluidPoints<D> fluids;
  double time = 0.0;  // [s]

  void take(double t, const numerics::MaterialPoints<D>& mp, const numerics::FluidPoints<D>& fp) {
    points = mp, time = t;
    if (fp.size() > 0) fluids = fp;
  }

  void save(CheckpointWriter& w) const {
    w.value("last_good.time", time);
    save_points<D>(w, "last_good.points.", points);
    save_fluids<D>(w, "last_good.fluids.", fluids);
  }
  /// Reads what save() wrote: `n_points` points, with `n_fluids` (n_points or 0) fluid states.
  void restore(CheckpointReader& r, std::size_t n_points, std::size_t n_fluids) {
    time = r.value<double>("last_good.time");
    points.id.resize(n_points);  // restore_points reads as many as the case has
    restore_points<D>(r, "last_good.points.", points);
    restore_fluids<D>(r, "last_good.fluids.", fluids, n_fluids);
  }
};

}  // namespace unsatmpm

// The time loop, the same for every cycle: claim the output folder, write t = 0, then step to the
// end time, writing histories and fields on their schedule (app/output_schedule.hpp), keeping a
// last good state, and on a numerical failure write that state and a failed summary (exit 3).
// SIGINT or SIGTERM (app/interrupt.hpp) end it after the current step: the state reached is
// written as an output frame and the summary says "interrupted" (exit 128 + the signal).
#pragma once

#include <fmt/core.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include "app/cycle_adapters.hpp"
#include "app/interrupt.hpp"
#include "app/output_schedule.hpp"
#include "app/run.hpp"
#include "writers/output_folder.hpp"
#include "writers/run_output.hpp"

namespace unsatmpm {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

/// Progress line every few seconds of wall time: simulated time, step, wall time, ETA.
class Progress {
 public:
  Progress(double end_time, bool quiet) : end_(end_time), quiet_(quiet) {}
  void update(double t, std::int64_t step, double dt, double wall) {
    if (quiet_ || wall < next_) return;
    next_ = wall + 2.0;
    const double eta = t > 0.0 ? wall * (end_ - t) / t : 0.0;
    spdlog::info(
        "t = {:.6g} s of {:.6g} s ({:.1f}%), step {}, dt = {:.3g} s, wall {:.1f} s, ETA {:.1f} s",
        t, end_, 100.0 * t / end_, step, dt, wall, eta);
  }

 private:
  double end_, next_ = 2.0;
  bool quiet_;
};

/// Runs `solver` from t = 0 to the case's end time; returns the exit code (0, or 3 on a
/// numerical failure). `gravity_loading` is the loading's JSON report, or empty;
/// `loading_failure`, if not empty, says how the loading failed: then the points' state (the
/// loading's last good one) is written as the last good state with a failed summary, and the run
/// ends there (exit 3).
template <int D, class Solver>
int run_loop(const Case& c, const RunOptions& options, Solver& solver,
             const std::string& gravity_loading, const std::string& loading_failure) {
  const auto& grid = solver.grid();
  const auto& mp = solver.points();
  if (!options.quiet)
    spdlog::info("{}: {} material points, {} grid nodes, {} thread(s), {}", c.name, mp.size(),
                 grid.n_nodes(), options.n_threads, cycle_name(solver));

  OutputFolder folder(options.output_dir);
  if (folder.found_stale_lock())
    fmt::print(stderr,
               "warning: output folder {}: the run that wrote it last did not end (it was killed "
               "or crashed); its files are replaced\n",
               options.output_dir.string());
  RunOutput<D> out(c, folder, mp, solver.has_plastic_model());
  RunSummary summary;
  summary.cycle = cycle_name(solver);
  summary.n_points = static_cast<std::int64_t>(mp.size());
  summary.n_nodes = grid.n_nodes();
  summary.n_threads = options.n_threads;
  summary.gravity_loading = gravity_loading;
  Scratch scratch;
  std::vector<double> suction;
  std::array<std::vector<numerics::Vec<D>>, 2> fluxes;
  const auto write = [&](double t, const numerics::MaterialPoints<D>& points,
                         const numerics::FluidPoints<D>& fluids, const std::string& tag) {
    const auto nodal = tag.empty() ? nodal_fields(solver, scratch) : std::vector<VtkField>{};
    auto fields = fluid_fields<D>(fluids, suction);
    for (auto& f : motion_fields<D>(solver, fluids, fluxes, tag.empty())) fields.push_back(f);
    out.write_fields(t, grid, nodal, points, fields, tag);
  };
  const auto record = [&](double t) {
    out.record_history(t, mp, solver.fluids());
    record_balance(solver, t, out);
  };
  const auto flush = [&](double t, std::int64_t step, const char* status) {
    summary.status = status;
    summary.steps = step, summary.simulated_time = t;
    summary.solver_statistics = solver_statistics(solver);
    out.flush(summary);
  };

  if (!loading_failure.empty()) {  // the points hold the loading's last good state
    summary.message = loading_failure;
    fmt::print(stderr,
               "error: numerical failure: {}; that state is written as points_last_good.vtu\n",
               loading_failure);
    write(0.0, mp, solver.fluids(), "last_good");
    summary.failure_step = 0, summary.failure_time = 0.0, summary.last_good_time = 0.0;
    flush(0.0, 0, "failed");
    return 3;
  }
  install_interrupt_handlers();
  OutputSchedule schedule(c);
  double t = 0.0;
  std::int64_t step = 0;
  // Every end leaves a summary: an output that cannot be written (a full disk, a permission)
  // ends the run as failed, its message naming the file and the reason, before it is reported.
  try {
    prepare_initial_output(solver);
    write(0.0, mp, solver.fluids(), "");
    record(0.0);
    flush(0.0, 0, "running");  // a summary from the start: a run killed later is still told
    LastGoodState<D> last_good{mp, solver.fluids(), 0.0};
    Progress progress(schedule.end_time(), options.quiet);
    const auto t0 = Clock::now();
    while (schedule.before_end(t)) {
      double dt = next_step(c, solver);
      summary.last_time_step = dt;  // the step the scheme chose, before clipping to an output time
      dt = schedule.clip(t, dt);
      try {
        solver.step(t, dt);
      } catch (const BlowUpError& e) {
        summary.message =
            fmt::format("step {} (t = {:.9g} s -> {:.9g} s): {}", step + 1, t, t + dt, e.what());
        fmt::print(stderr,
                   "error: numerical failure at {}; the last good state (t = {:.9g} s) is "
                   "written as points_last_good.vtu\n",
                   summary.message, last_good.time);
        write(last_good.time, last_good.points, last_good.fluids, "last_good");
        summary.wall_time = seconds_since(t0);
        summary.failure_step = step + 1, summary.failure_time = t;
        summary.last_good_time = last_good.time;
        flush(t, step, "failed");  // the steps completed and the time they reached
        return 3;
      }
      ++step;
      t += dt;
      const bool recorded = schedule.history_due(t);
      if (recorded) record(t);
      const bool written = schedule.output_due(t);
      if (written) {
        write(t, mp, solver.fluids(), "");
        summary.wall_time = seconds_since(t0);
        flush(t, step, "running");
      }
      if (step % snapshot_every(solver) == 0) last_good.take(t, mp, solver.fluids());
      progress.update(t, step, dt, seconds_since(t0));
      if (const int signal = interrupt_signal(); signal != 0 && schedule.before_end(t)) {
        summary.message = fmt::format("interrupted by {} after step {} (t = {:.9g} s)",
                                      signal_name(signal), step, t);
        fmt::print(stderr, "{}; the state reached is the last output frame\n", summary.message);
        if (!recorded) record(t);
        if (!written) write(t, mp, solver.fluids(), "");
        summary.wall_time = seconds_since(t0);
        flush(t, step, "interrupted");
        return 128 + signal;
      }
    }
    summary.wall_time = seconds_since(t0);
    flush(t, step, "completed");
    if (!options.quiet)
      spdlog::info("done: {} steps to t = {:.6g} s in {:.2f} s ({:.1f} ns per MP-step)", step, t,
                   summary.wall_time,
                   1e9 * summary.wall_time / std::max<double>(1.0, double(step) * mp.size()));
    return 0;
  } catch (const std::exception& e) {
    summary.message = fmt::format("at step {} (t = {:.9g} s): {}", step, t, e.what());
    try {
      flush(t, step, "failed");
    } catch (const std::exception&) {  // the summary cannot be written either: the error says why
    }
    throw;
  }
}

}  // namespace unsatmpm

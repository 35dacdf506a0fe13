// The time loop, the same for every cycle: claim the output folder, write t = 0, then step to the
// end time, writing histories and fields on their schedule (app/output_schedule.hpp) and a
// checkpoint at every output time (app/checkpoint.hpp), keeping a last good state, and on a
// numerical failure write that state and a failed summary (exit 3). With solver.stop_at_rest the
// run ends, completed, once the body has come to rest (app/rest_monitor.hpp), its state written
// as an output frame and a checkpoint, and the summary's message says when. SIGINT or SIGTERM
// (app/interrupt.hpp) end it after the current step: the state reached is written as an output
// frame and a checkpoint, and the summary says "interrupted" (exit 128 + the signal). In the main
// cycle a signal also ends the step's flow integration, and a second one its mechanics
// sub-cycle (app/cycle_adapters.hpp): that step is abandoned, its last good state written as
// after a failure, and a resumed run goes on from the last checkpoint. A resumed run (unsatmpm
// resume) starts from the checkpoint instead of t = 0 and goes on appending to the same series
// and histories.
#pragma once

#include <fmt/core.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "app/checkpoint.hpp"
#include "app/cycle_adapters.hpp"
#include "app/detached_planes.hpp"
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
  /// `start`: the simulated time the run (or its resumed part) starts from [s].
  Progress(double start, double end_time, bool quiet)
      : start_(start), end_(end_time), quiet_(quiet) {}
  void update(double t, std::int64_t step, double dt, double wall) {
    if (quiet_ || wall < next_) return;
    next_ = wall + 2.0;
    next_inside_ = std::max(next_inside_, wall + 1.0);
    const double eta = t > start_ ? wall * (end_ - t) / (t - start_) : 0.0;
    spdlog::info(
        "t = {:.6g} s of {:.6g} s ({:.1f}%), step {}, dt = {:.3g} s, wall {:.1f} s, ETA {:.1f} s",
        t, end_, 100.0 * t / end_, step, dt, wall, eta);
  }
  /// Inside step `step` over [t, t + dt] (the main cycle's, whose flow or mechanics can make it
  /// long): where it stands, `where()` giving a StepPosition, at the same pace as update().
  template <class Where>
  void inside_step(std::int64_t step, double t, double dt, Where&& where, double wall) {
    if (quiet_ || wall < next_inside_) return;
    next_inside_ = wall + 2.0;
    const StepPosition at = where();
    spdlog::info(
        "step {} (t = {:.6g} s -> {:.6g} s) in progress: the {} at t = {:.9g} s in steps of "
        "{:.3g} s, wall {:.1f} s",
        step, t, t + dt, at.part, at.t, at.h, wall);
  }

 private:
  // Each kind of line on its own pace, so that the lines inside long steps never crowd out the
  // line after a step (and its ETA).
  double start_, end_, next_ = 2.0, next_inside_ = 2.0;
  bool quiet_;
};

/// Runs `solver` from t = 0 (or, with `resume`, from the checkpoint it reads, its header read
/// already) to the case's end time; returns the exit code (0, or 3 on a numerical failure).
/// `gravity_loading` is the loading's JSON report, or empty; `loading_failure`, if not empty, says
/// how the loading failed: then the points' state (the loading's last good one) is written as the
/// last good state with a failed summary, and the run ends there (exit 3).
template <int D, class Solver>
int run_loop(const Case& c, const RunOptions& options, Solver& solver, std::string gravity_loading,
             const std::string& loading_failure, CheckpointReader* resume = nullptr) {
  const auto& grid = solver.grid();
  const auto& mp = solver.points();
  DetachedPlanes<D> detached(c, grid, mp);
  if (!options.quiet)
    spdlog::info("{}: {} material points, {} grid nodes, {} thread(s), {}", c.name, mp.size(),
                 grid.n_nodes(), options.n_threads, cycle_name(solver));

  OutputFolder folder(options.output_dir,
                      resume ? OutputFolder::Claim::resume : OutputFolder::Claim::new_run);
  if (folder.found_stale_lock() && !resume)
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
  RestMonitor rest(c.solver.stop_at_rest);
  LastGoodState<D> last_good{mp, solver.fluids(), 0.0};
  LoopPosition at;  // where the run starts: t = 0, or the checkpoint's
  if (resume) {
    at = read_checkpoint<D>(*resume, schedule, rest, last_good, gravity_loading, out, solver);
    summary.resumes = ++at.resumes, summary.resumed_from = at.time;
    summary.last_time_step = at.last_time_step;
    if (!schedule.before_end(at.time)) {
      fmt::print(stderr, "{}: the run reached its end time ({:.9g} s); nothing to resume\n",
                 options.output_dir.string(), at.time);
      return 0;
    }
    if (rest.stopped()) {
      fmt::print(stderr, "{}: the run came to rest at t = {:.9g} s; nothing to resume\n",
                 options.output_dir.string(), at.time);
      return 0;
    }
    if (!options.quiet)
      spdlog::info("resumed at t = {:.9g} s after step {} (resume {})", at.time, at.step,
                   at.resumes);
  }
  summary.gravity_loading = gravity_loading;
  double t = at.time;
  std::int64_t step = at.step;
  const auto t0 = Clock::now();
  const auto wall = [&] { return at.wall_time + seconds_since(t0); };
  auto last_checkpoint = t0;
  double checkpoint_time = at.time;
  const auto checkpoint = [&] {
    const LoopPosition now{t, step, summary.last_time_step, wall(), at.resumes};
    write_checkpoint<D>(folder, c, options.program_version, now, schedule, rest, last_good,
                        gravity_loading, out, solver);
    last_checkpoint = Clock::now(), checkpoint_time = t;
  };
  // The step that failed or was abandoned: its last good state, and the summary that says so.
  const auto end_in_step = [&](double dt, const std::string& what, const char* status) {
    summary.message =
        fmt::format("step {} (t = {:.9g} s -> {:.9g} s): {}", step + 1, t, t + dt, what);
    write(last_good.time, last_good.points, last_good.fluids, "last_good");
    summary.wall_time = wall();
    summary.failure_step = step + 1, summary.failure_time = t;
    summary.last_good_time = last_good.time;
    flush(t, step, status);  // the steps completed and the time they reached
  };
  Progress progress(t, schedule.end_time(), options.quiet);
  double step_dt = 0.0;         // the step being taken, for the progress inside it
  bool told = false;            // that a first signal lets the mechanics finish its step
  bool surface_warned = false;  // surface_warning given (once a run)
  watch_step(solver, [&](auto where) {
    progress.inside_step(step + 1, t, step_dt, where, seconds_since(t0));
    if (!told && interrupt_count() == 1 && std::string_view(where().part) == "mechanics") {
      told = true;
      fmt::print(stderr,
                 "{} received: the run stops after this step, at t = {:.9g} s, with a "
                 "checkpoint; a second one abandons the step\n",
                 signal_name(interrupt_signal()), t + step_dt);
    }
  });
  struct Unwatch {  // the solver outlives this loop: its check must not keep references here
    Solver& s;
    ~Unwatch() {
      watch_step(s, [](auto) {});
    }
  } unwatch{solver};
  // Every end leaves a summary: an output that cannot be written (a full disk, a permission)
  // ends the run as failed, its message naming the file and the reason, before it is reported.
  try {
    if (!resume) {
      prepare_initial_output(solver);
      write(0.0, mp, solver.fluids(), "");
      record(0.0);
    }
    flush(t, step, "running");  // a summary from the start: a run killed later is still told
    if (!resume) checkpoint();
    while (schedule.before_end(t)) {
      double dt = next_step(c, solver);
      summary.last_time_step = dt;  // the step the scheme chose, before clipping to an output time
      dt = schedule.clip(t, dt);
      step_dt = dt;
      try {
        solver.step(t, dt);
      } catch (const BlowUpError& e) {
        end_in_step(dt, e.what(), "failed");
        fmt::print(stderr,
                   "error: numerical failure at {}; the last good state (t = {:.9g} s) is "
                   "written as points_last_good.vtu\n",
                   summary.message, last_good.time);
        return 3;
      } catch (const numerics::StopRequested& e) {  // a signal inside the main cycle's step
        const int signal = interrupt_signal();
        const std::string where = e.where().empty() ? "" : " (" + e.where() + ")";
        end_in_step(dt,
                    fmt::format("interrupted by {} inside the step, which was abandoned{}; the "
                                "last good state (t = {:.9g} s) is written as "
                                "points_last_good.vtu, and a resumed run goes on from the "
                                "checkpoint at t = {:.9g} s",
                                signal_name(signal), where, last_good.time, checkpoint_time),
                    "interrupted");
        fmt::print(stderr, "{}\n", summary.message);
        return 128 + signal;
      }
      ++step;
      t += dt;
      if (!surface_warned)
        if (const std::string w = surface_warning(c, solver); !w.empty())
          spdlog::warn("{}", w), surface_warned = true;
      const double energy = rest.active() ? kinetic_energy<D>(mp) : 0.0;
      const bool at_rest = rest.at_rest(t, energy);  // before a checkpoint can keep it
      const bool recorded = schedule.history_due(t);
      if (recorded) {
        record(t);
        for (const std::string& w : detached.check(t, mp)) spdlog::warn("{}", w);
      }
      const bool written = schedule.output_due(t);
      if (step % snapshot_every(solver) == 0) last_good.take(t, mp, solver.fluids());
      if (written) {
        write(t, mp, solver.fluids(), "");
        summary.wall_time = wall();
        flush(t, step, "running");
      }
      if (written || (options.checkpoint_every > 0.0 &&
                      seconds_since(last_checkpoint) >= options.checkpoint_every)) {
        if (!written) {  // the histories and the summary up to date with the checkpoint
          summary.wall_time = wall();
          flush(t, step, "running");
        }
        checkpoint();
      }
      progress.update(t, step, dt, seconds_since(t0));
      if (at_rest) {  // the run's end: its state is the last output frame
        summary.message = rest.message(t, energy);
        if (!options.quiet) spdlog::info("{}", summary.message);
        if (!recorded) record(t);
        if (!written) write(t, mp, solver.fluids(), ""), checkpoint();
        break;
      }
      if (const int signal = interrupt_signal(); signal != 0 && schedule.before_end(t)) {
        summary.message = fmt::format("interrupted by {} after step {} (t = {:.9g} s)",
                                      signal_name(signal), step, t);
        fmt::print(stderr, "{}; the state reached is the last output frame\n", summary.message);
        if (!recorded) record(t);
        if (!written) write(t, mp, solver.fluids(), ""), checkpoint();
        summary.wall_time = wall();
        flush(t, step, "interrupted");
        return 128 + signal;
      }
    }
    summary.wall_time = wall();
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

#include "drivers/run.hpp"

#include <fmt/core.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>

#include "drivers/explicit_solver.hpp"
#include "drivers/run_output.hpp"

namespace unsatmpm::drivers {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
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

template <int D, class K>
int run(const Case& c, const RunOptions& options) {
  const auto grid = make_grid<D>(c);
  auto points = fill_bodies<D>(c, grid);
  ExplicitSolver<D, K> solver(c, grid, std::move(points), options.n_threads);
  const auto& mp = solver.points();
  if (!options.quiet)
    spdlog::info("{}: {} material points, {} grid nodes, {} thread(s)", c.name, mp.size(),
                 grid.n_nodes(), options.n_threads);

  prepare_output_folder(options.output_dir);
  RunOutput<D> out(c, options.output_dir, mp, solver.has_plastic_model());
  RunSummary summary;
  summary.n_points = static_cast<std::int64_t>(mp.size());
  summary.n_nodes = grid.n_nodes();
  summary.n_threads = options.n_threads;

  const double end = c.solver.end_time;
  const double t_eps = 1e-12 * end;
  std::vector<double> output_times = c.output.times;
  if (output_times.empty() || output_times.back() < end - t_eps) output_times.push_back(end);
  std::size_t next_output = 0;
  double t = 0.0, next_history = 0.0;
  std::int64_t step = 0;
  out.write_fields(0.0, grid, solver.nodes(), mp);
  out.record_history(0.0, mp);
  next_history = c.output.history_interval;

  // The last good state is a copy taken every `snapshot_every` steps: cheap next to the steps.
  constexpr std::int64_t snapshot_every = 100;
  auto last_good = mp;
  double last_good_time = 0.0;
  Progress progress(end, options.quiet);
  const auto t0 = Clock::now();
  while (t < end - t_eps) {
    double dt = c.solver.time_step.fixed
                    ? *c.solver.time_step.fixed
                    : c.solver.time_step.cfl_safety * solver.critical_time_step();
    summary.last_time_step = dt;  // the step the scheme chose, before clipping to an output time
    dt = std::min(dt, output_times[next_output] - t);
    try {
      solver.step(dt);
    } catch (const BlowUpError& e) {
      summary.status = "failed";
      summary.message =
          fmt::format("step {} (t = {:.9g} s -> {:.9g} s): {}", step + 1, t, t + dt, e.what());
      fmt::print(stderr,
                 "error: numerical failure at {}; the last good state (t = {:.9g} s) is "
                 "written as points_last_good.vtu\n",
                 summary.message, last_good_time);
      out.write_fields(last_good_time, grid, solver.nodes(), last_good, "last_good");
      summary.wall_time = seconds_since(t0);
      out.flush(summary);
      return 3;
    }
    ++step;
    t += dt;
    if (t >= next_history - t_eps) {
      out.record_history(t, mp);
      next_history = t + c.output.history_interval;
    }
    if (t >= output_times[next_output] - t_eps) {
      if (std::abs(t - output_times[next_output]) < 1e-9 * end) t = output_times[next_output];
      out.write_fields(t, grid, solver.nodes(), mp);
      summary.steps = step, summary.simulated_time = t, summary.wall_time = seconds_since(t0);
      out.flush(summary);
      if (next_output + 1 < output_times.size()) ++next_output;
    }
    if (step % snapshot_every == 0) last_good = mp, last_good_time = t;
    progress.update(t, step, dt, seconds_since(t0));
  }
  summary.steps = step;
  summary.simulated_time = t;
  summary.wall_time = seconds_since(t0);
  out.flush(summary);
  if (!options.quiet)
    spdlog::info("done: {} steps to t = {:.6g} s in {:.2f} s ({:.1f} ns per MP-step)", step, t,
                 summary.wall_time,
                 1e9 * summary.wall_time / std::max<double>(1.0, double(step) * mp.size()));
  return 0;
}

template <int D>
int run_dimension(const Case& c, const RunOptions& options) {
  switch (c.shape_function) {
    case ShapeFunctionKind::linear:
      return run<D, numerics::LinearKernel>(c, options);
    case ShapeFunctionKind::gimp:
      return run<D, numerics::GimpKernel>(c, options);
  }
  throw std::logic_error("unknown shape function");
}

}  // namespace

int run_case(const Case& c, const RunOptions& options) {
  switch (c.dimension) {
    case 1:
      return run_dimension<1>(c, options);
    case 2:
      return run_dimension<2>(c, options);
    case 3:
      return run_dimension<3>(c, options);
  }
  throw std::logic_error("dimension must be 1, 2 or 3");
}

}  // namespace unsatmpm::drivers

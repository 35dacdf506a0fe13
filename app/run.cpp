#include "app/run.hpp"

#include <fmt/core.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>

#include "cycles/explicit_solver.hpp"
#include "cycles/implicit_solver.hpp"
#include "cycles/three_phase_solver.hpp"
#include "output/run_output.hpp"

namespace unsatmpm {

namespace {

using Clock = std::chrono::steady_clock;
using Scratch = std::vector<std::vector<double>>;

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

/// The doubles of a vector of fixed-size Eigen vectors (stored contiguously, no padding).
template <int D>
std::span<const double> flat(const std::vector<numerics::Vec<D>>& v, int n_components) {
  if (v.empty()) return {};
  return {v.data()->data(), v.size() * n_components};
}

// Nodal fields of each cycle's grid output.
template <int D, class K>
std::vector<NodalField> nodal_fields(const ExplicitSolver<D, K>& s, Scratch& scratch) {
  const auto& nodes = s.nodes();
  const std::int64_t n = nodes.n_nodes();
  scratch.assign(2, std::vector<double>(n));
  for (std::int64_t i = 0; i < n; ++i)
    scratch[0][i] = nodes.mass(i), scratch[1][i] = nodes.fixed[i];
  return {{"mass", 1, scratch[0], false},
          {"velocity", D, flat(nodes.velocity, D), true},
          {"acceleration", D, flat(nodes.acceleration, D), true},
          {"fixed_components", 1, scratch[1], false}};
}

template <int D, class K>
std::vector<NodalField> nodal_fields(const ThreePhaseSolver<D, K>& s, Scratch& scratch) {
  const auto& nodes = s.nodes();
  const std::int64_t n = nodes.n_nodes();
  scratch.assign(1, std::vector<double>(n));
  for (std::int64_t i = 0; i < n; ++i) scratch[0][i] = nodes.solid_mass(i);
  return {{"solid_mass", 1, scratch[0], false},
          {"velocity_solid", D, flat(nodes.solid_velocity, D), true},
          {"velocity_liquid", D, flat(nodes.liquid_velocity, D), true},
          {"velocity_gas", D, flat(nodes.gas_velocity, D), true},
          {"liquid_theta", 1, nodes.liquid_theta, false},
          {"gas_theta", 1, nodes.gas_theta, false}};
}

template <int D, class K>
std::vector<NodalField> nodal_fields(const ImplicitSolver<D, K>& s, Scratch&) {
  const auto& p = s.nodal_pressures();
  if (p[0].empty()) return {};
  return {{"liquid_pressure", 1, p[0], false}, {"gas_pressure", 1, p[1], false}};
}

/// The fluid fields of the points (names and units: docs/output.md); none for a one-phase run.
template <int D>
std::vector<ExtraPointField> fluid_fields(const numerics::FluidPoints<D>& fp,
                                          std::vector<double>& suction) {
  if (fp.size() == 0) return {};
  suction.resize(fp.size());
  for (std::size_t p = 0; p < fp.size(); ++p)
    suction[p] = physics::suction(fp.liquid_pressure[p], fp.gas_pressure[p]);
  return {{"liquid_pressure", 1, fp.liquid_pressure, false},
          {"gas_pressure", 1, fp.gas_pressure, false},
          {"suction", 1, suction, false},
          {"degree_of_saturation", 1, fp.saturation, false},
          {"porosity", 1, fp.porosity, false},
          {"velocity_liquid", D, flat(fp.liquid_velocity, D), true},
          {"velocity_gas", D, flat(fp.gas_velocity, D), true}};
}

template <int D, class K>
void record_balance(const ExplicitSolver<D, K>&, double, RunOutput<D>&) {}
template <int D, class K>
void record_balance(const ThreePhaseSolver<D, K>& s, double t, RunOutput<D>& out) {
  out.record_balance(t, s.balance());
}

template <int D, class K>
void record_balance(const ImplicitSolver<D, K>& s, double t, RunOutput<D>& out) {
  out.record_balance(t, s.balance());
}

/// The step the run loop takes: the explicit cycles' CFL step (or the case's fixed step), the
/// implicit cycle's coupling interval.
template <class Solver>
double next_step(const Case& c, const Solver& solver) {
  return c.solver.time_step.fixed ? *c.solver.time_step.fixed
                                  : c.solver.time_step.cfl_safety * solver.critical_time_step();
}
template <int D, class K>
double next_step(const Case&, const ImplicitSolver<D, K>& solver) {
  return solver.interval();
}

template <class Solver>
std::string solver_statistics(const Solver&) {
  return "";
}
template <int D, class K>
std::string solver_statistics(const ImplicitSolver<D, K>& s) {
  return s.statistics_json();
}

template <int D, class K>
const char* cycle_name(const ImplicitSolver<D, K>&) {
  return "implicit_pressure_three_phase";
}
template <int D, class K>
const char* cycle_name(const ExplicitSolver<D, K>&) {
  return "explicit_dynamic_one_phase";
}
template <int D, class K>
const char* cycle_name(const ThreePhaseSolver<D, K>&) {
  return "explicit_dynamic_three_phase";
}

/// The time loop, the same for every cycle.
template <int D, class Solver>
int run_loop(const Case& c, const RunOptions& options, Solver& solver,
             const std::string& gravity_loading) {
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
  const auto write = [&](double t, const numerics::MaterialPoints<D>& points,
                         const numerics::FluidPoints<D>& fluids, const std::string& tag) {
    const auto nodal = tag.empty() ? nodal_fields(solver, scratch) : std::vector<NodalField>{};
    out.write_fields(t, grid, nodal, points, fluid_fields<D>(fluids, suction), tag);
  };

  const double end = c.solver.end_time;
  const double t_eps = 1e-12 * end;
  std::vector<double> output_times = c.output.times;
  if (output_times.empty() || output_times.back() < end - t_eps) output_times.push_back(end);
  std::size_t next_output = 0;
  double t = 0.0;
  std::int64_t step = 0;
  write(0.0, mp, solver.fluids(), "");
  out.record_history(0.0, mp, solver.fluids());
  record_balance(solver, 0.0, out);
  double next_history = c.output.history_interval;

  // The last good state is a copy taken every `snapshot_every` steps: cheap next to the steps.
  // An implicit-cycle step is a whole coupling interval (thousands of mechanics sub-steps and a
  // CVODE run), so it is copied after every step; the embankment's failure at 141.5 s with 0.5 s
  // intervals otherwise left its last good state at 100 s.
  constexpr std::int64_t snapshot_every = requires(const Solver& s) { s.interval(); }
  ? 1 : 100;
  auto last_good = mp;
  auto last_good_fluids = solver.fluids();
  double last_good_time = 0.0;
  Progress progress(end, options.quiet);
  const auto t0 = Clock::now();
  while (t < end - t_eps) {
    double dt = next_step(c, solver);
    summary.last_time_step = dt;  // the step the scheme chose, before clipping to an output time
    dt = std::min(dt, output_times[next_output] - t);
    try {
      solver.step(t, dt);
    } catch (const BlowUpError& e) {
      summary.status = "failed";
      summary.message =
          fmt::format("step {} (t = {:.9g} s -> {:.9g} s): {}", step + 1, t, t + dt, e.what());
      fmt::print(stderr,
                 "error: numerical failure at {}; the last good state (t = {:.9g} s) is "
                 "written as points_last_good.vtu\n",
                 summary.message, last_good_time);
      write(last_good_time, last_good, last_good_fluids, "last_good");
      summary.wall_time = seconds_since(t0);
      summary.solver_statistics = solver_statistics(solver);
      out.flush(summary);
      return 3;
    }
    ++step;
    t += dt;
    if (t >= next_history - t_eps) {
      out.record_history(t, mp, solver.fluids());
      record_balance(solver, t, out);
      next_history = t + c.output.history_interval;
    }
    if (t >= output_times[next_output] - t_eps) {
      if (std::abs(t - output_times[next_output]) < 1e-9 * end) t = output_times[next_output];
      write(t, mp, solver.fluids(), "");
      summary.steps = step, summary.simulated_time = t, summary.wall_time = seconds_since(t0);
      summary.solver_statistics = solver_statistics(solver);
      out.flush(summary);
      if (next_output + 1 < output_times.size()) ++next_output;
    }
    if (step % snapshot_every == 0) {
      last_good = mp, last_good_time = t;
      if (solver.fluids().size() > 0) last_good_fluids = solver.fluids();
    }
    progress.update(t, step, dt, seconds_since(t0));
  }
  summary.status = "completed";
  summary.steps = step;
  summary.simulated_time = t;
  summary.wall_time = seconds_since(t0);
  summary.solver_statistics = solver_statistics(solver);
  out.flush(summary);
  if (!options.quiet)
    spdlog::info("done: {} steps to t = {:.6g} s in {:.2f} s ({:.1f} ns per MP-step)", step, t,
                 summary.wall_time,
                 1e9 * summary.wall_time / std::max<double>(1.0, double(step) * mp.size()));
  return 0;
}

/// Gravity loading before t = 0, if the case asks for it; then the time loop. A loading that
/// does not balance ends the run before anything is written (exit 3).
template <int D, class Solver>
int load_and_run(const Case& c, const RunOptions& options, Solver& solver) {
  std::string loading;
  if (c.solver.gravity_loading) {
    if (!options.quiet) spdlog::info("gravity loading before t = 0");
    try {
      const GravityLoadingReport r = solver.load_gravity();
      loading = r.json();
      if (!options.quiet)
        spdlog::info(
            "gravity loading balanced: {} steps, {:.4g} s, force ratio {:.2e}; reset: largest "
            "displacement {:.3e} m, largest plastic strain {:.3e}",
            r.steps, r.time, r.force_ratio, r.max_displacement, r.max_plastic_strain);
    } catch (const BlowUpError& e) {
      fmt::print(stderr, "error: {}\n", e.what());
      return 3;
    }
  }
  return run_loop<D>(c, options, solver, loading);
}

template <int D, class K>
int run(const Case& c, const RunOptions& options) {
  const auto grid = make_grid<D>(c);
  auto points = fill_bodies<D>(c, grid);
  if (c.phases == Phases::solid_liquid_gas && c.solver.cycle == Cycle::implicit_pressure) {
    ImplicitSolver<D, K> solver(c, grid, std::move(points), options.n_threads);
    return load_and_run<D>(c, options, solver);
  }
  if (c.phases == Phases::solid_liquid_gas) {
    ThreePhaseSolver<D, K> solver(c, grid, std::move(points), options.n_threads);
    return load_and_run<D>(c, options, solver);
  }
  ExplicitSolver<D, K> solver(c, grid, std::move(points), options.n_threads);
  return load_and_run<D>(c, options, solver);
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

}  // namespace unsatmpm

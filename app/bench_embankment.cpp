// `unsatmpm bench embankment`: the verification embankment on the main cycle, from its gravity
// loading to an end time, without output, and where its wall time went (docs/performance.md).
// kernel_ratio = wall / (mechanics sub-steps x points x the column2d kernel's ns per point-step,
// measured in the same run on the same threads): the cost of a sub-step of the coupled cycle
// against the plainest explicit MPM step, a figure that carries between machines.
#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <stdexcept>

#include "app/bench.hpp"
#include "app/embedded_case.hpp"
#include "cycles/implicit_solver.hpp"
#include "input/case_parser.hpp"

namespace unsatmpm {

void bench_embankment(int n_threads, double end_time, const std::string& direct_solver) {
  using Clock = std::chrono::steady_clock;
  const auto since = [](Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
  };
  Case c = parse_case_text(embankment_case_text, embankment_case_file);
  if (c.dimension != 2 || c.shape_function != ShapeFunctionKind::gimp ||
      c.solver.cycle != Cycle::implicit_pressure)
    throw std::logic_error("the built-in embankment case must be 2D, GIMP and the main cycle");
  c.solver.end_time = end_time;
  if (direct_solver == "klu")
    c.solver.implicit.direct_solver = FlowDirectSolver::klu;
  else if (direct_solver == "umfpack")
    c.solver.implicit.direct_solver = FlowDirectSolver::umfpack;
  else if (!direct_solver.empty())
    throw std::invalid_argument("unknown sparse LU '" + direct_solver + "'; known: umfpack, klu");
  const auto grid = make_grid<2>(c);
  ImplicitSolver<2, numerics::GimpKernel> solver(c, grid, fill_bodies<2>(c, grid), n_threads);
  const auto t_load = Clock::now();
  solver.load_gravity();
  const double loading_s = since(t_load);

  const auto t0 = Clock::now();
  double t = 0.0, next_report = 30.0;
  while (t < end_time * (1.0 - 1e-12)) {
    const double dt = std::min(solver.interval(), end_time - t);
    solver.step(t, dt);
    t += dt;
    if (since(t0) >= next_report) {  // a long run shows it is alive, on stderr
      fmt::print(stderr, "bench embankment: t = {:.6g} s of {:.6g} s, wall {:.0f} s\n", t, end_time,
                 since(t0));
      next_report += 30.0;
    }
  }
  const double wall = since(t0);

  const double kernel_ns = column2d_kernel_ns(n_threads);
  const FlowCounters& k = solver.counters();
  const numerics::CvodeStatistics s = solver.cvode_statistics();
  const auto n_points = static_cast<double>(solver.points().size());
  const double point_substeps = static_cast<double>(k.mechanics_substeps) * n_points;
  fmt::print(
      "bench=embankment threads={} wall_s={:.2f} simulated_s={:.6g} points={} "
      "mechanics_substeps={} mechanics_s={:.2f} mechanics_ns_per_point_substep={:.1f} "
      "correction_s={:.2f} correction_gmres_iterations={} correction_klu_solves={} flow_s={:.2f} "
      "rhs_s={:.2f} lu_s={:.2f} coupling_intervals={} "
      "direct_solver={} lu_factorisations={} lu_analyses={} lu_ordering={} pressure_unknowns={} "
      "gravity_loading_s={:.2f} "
      "column2d_ns_per_mp_step={:.1f} kernel_ratio={:.2f}\n",
      n_threads, wall, t, solver.points().size(), k.mechanics_substeps, k.mechanics_seconds,
      point_substeps > 0.0 ? 1e9 * k.mechanics_seconds / point_substeps : 0.0, k.correction_seconds,
      k.correction_iterations, k.correction_direct_solves, k.flow_seconds, k.rhs_seconds,
      s.lu_seconds, k.coupling_intervals, direct_solver_name(s.direct_solver), s.lu_factorisations,
      s.lu_analyses, lu_ordering_name(s.lu_ordering), solver.pressure_unknowns(), loading_s,
      kernel_ns, point_substeps > 0.0 ? 1e9 * wall / (point_substeps * kernel_ns) : 0.0);
}

}  // namespace unsatmpm

#include "app/run.hpp"

#include <fmt/core.h>
#include <spdlog/spdlog.h>

#include <stdexcept>
#include <string>

#include "app/run_loop.hpp"

namespace unsatmpm {

namespace {

/// Gravity loading before t = 0, if the case asks for it; then the time loop. A loading that
/// fails ends the run (exit 3) with the loading's last good state written and a failed summary
/// (run_loop).
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
      return run_loop<D>(c, options, solver, "", e.what());
    }
  }
  return run_loop<D>(c, options, solver, loading, "");
}

/// A new run (from the gravity loading, if any), or with `resume` the run its checkpoint
/// continues: the solver is set up from the case as for a new run, then takes the saved state.
template <int D, class Solver>
int start(const Case& c, const RunOptions& options, Solver& solver, CheckpointReader* resume) {
  if (resume) return run_loop<D>(c, options, solver, "", "", resume);
  return load_and_run<D>(c, options, solver);
}

template <int D, class K>
int run(const Case& c, const RunOptions& options, CheckpointReader* resume) {
  const auto grid = make_grid<D>(c);
  auto points = fill_bodies<D>(c, grid);
  if (c.phases == Phases::solid_liquid_gas && c.solver.cycle == Cycle::implicit_pressure) {
    ImplicitSolver<D, K> solver(c, grid, std::move(points), options.n_threads);
    return start<D>(c, options, solver, resume);
  }
  if (c.phases == Phases::solid_liquid_gas) {
    ThreePhaseSolver<D, K> solver(c, grid, std::move(points), options.n_threads);
    return start<D>(c, options, solver, resume);
  }
  ExplicitSolver<D, K> solver(c, grid, std::move(points), options.n_threads);
  return start<D>(c, options, solver, resume);
}

template <int D>
int run_dimension(const Case& c, const RunOptions& options, CheckpointReader* resume) {
  switch (c.shape_function) {
    case ShapeFunctionKind::linear:
      return run<D, numerics::LinearKernel>(c, options, resume);
    case ShapeFunctionKind::gimp:
      return run<D, numerics::GimpKernel>(c, options, resume);
  }
  throw std::logic_error("unknown shape function");
}

int dispatch(const Case& c, const RunOptions& options, CheckpointReader* resume) {
  switch (c.dimension) {
    case 1:
      return run_dimension<1>(c, options, resume);
    case 2:
      return run_dimension<2>(c, options, resume);
    case 3:
      return run_dimension<3>(c, options, resume);
  }
  throw std::logic_error("dimension must be 1, 2 or 3");
}

}  // namespace

int run_case(const Case& c, const RunOptions& options) { return dispatch(c, options, nullptr); }

int resume_case(const Case& c, CheckpointReader& checkpoint, const RunOptions& options) {
  return dispatch(c, options, &checkpoint);
}

}  // namespace unsatmpm

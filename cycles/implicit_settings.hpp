// The main cycle's numerical settings that are not case keys (cycles/implicit_solver.hpp;
// docs/input.md states them): they change the cost or the default, not the equations.
#pragma once

#include <cstdint>

#include "input/case.hpp"
#include "numerics/cvode_integrator.hpp"

namespace unsatmpm {

/// Pressure unknowns from which `implicit.linear_solver: auto` takes the iterative solver: in 3D
/// where it became the faster in the scaling study of docs/performance.md ("The flow's linear
/// solvers"); in 2D never, since with UMFPACK the sparse LU was as fast from 3e4 to 1e5 unknowns
/// and faster at 3e5, where the iterative solver loses its grip (it was faster only around 1e4,
/// by a quarter, at a millisecond per simulated second); 1D patterns are banded, a sparse LU's fill
/// stays linear. Not a key: it changes the cost, not the solution.
inline constexpr std::int64_t iterative_from_3d = 1000;
inline constexpr std::int64_t iterative_from(int dimension) {
  return dimension == 3 ? iterative_from_3d : INT64_MAX;
}

/// The case's `implicit.linear_solver` as the CVODE wrapper's choice.
inline numerics::LinearSolverChoice linear_solver_choice(FlowLinearSolver s) {
  switch (s) {
    case FlowLinearSolver::direct:
      return numerics::LinearSolverChoice::direct;
    case FlowLinearSolver::iterative:
      return numerics::LinearSolverChoice::iterative;
    case FlowLinearSolver::automatic:
      break;
  }
  return numerics::LinearSolverChoice::automatic;
}

/// The case's `implicit.linear_solver` and `implicit.direct_solver` handed to `cvode`, with the
/// size from which `auto` takes the iterative solver in that dimension.
inline void choose_linear_solver(numerics::CvodeIntegrator& cvode, const ImplicitSpec& spec,
                                 int dimension) {
  cvode.set_linear_solver(linear_solver_choice(spec.linear_solver), iterative_from(dimension));
  cvode.set_direct_solver(spec.direct_solver == FlowDirectSolver::klu
                              ? numerics::DirectSolverChoice::klu
                              : numerics::DirectSolverChoice::umfpack);
}

/// Drop tolerance of the flow's Jacobian (numerics::PressureSystem::set_jacobian_drop_tolerance):
/// in 3D GIMP's stencil nodes a point barely touches (below 5 % of a full weight or gradient)
/// leave the Jacobian; in 1D and 2D none does. Dropping them spared KLU time while the soil
/// stood, but where a wetted face slides CVODE's Newton iteration then failed to converge
/// thousands of times and the flow stalled in steps of 1e-5 s; in 3D the exact Jacobian costs
/// the slice 86 % more time and 4 times the memory (docs/balance_laws.md, "The Jacobian's drop
/// tolerance"). Not a key: it changes the cost and the Newton iteration, not the solution (the
/// right-hand side is exact).
inline constexpr double jacobian_drop_tolerance(int dimension) {
  return dimension == 3 ? 0.05 : 0.0;
}
/// CVODE steps allowed per coupling interval: a flow that needs more is stuck, and is reported
/// (CV_TOO_MUCH_WORK, with its worst unknown) instead of running on for hours. Not a key: a
/// legitimate interval takes tens to hundreds of steps.
inline constexpr long max_cvode_steps_per_interval = 20000;
/// Default coupling intervals: with a deformable skeleton this many mechanics steps; with a rigid
/// one, the run's end time divided by `rigid_intervals_per_run` when no history interval is set.
inline constexpr double mechanics_steps_per_interval = 20.0;
inline constexpr double rigid_intervals_per_run = 200.0;

}  // namespace unsatmpm

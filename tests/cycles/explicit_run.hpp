// The explicit three-phase cycle's tests' common steps: a solver set up from a case on one
// thread, and a run to a time at half the stable step.
#pragma once

#include <algorithm>

#include "cycles/three_phase_solver.hpp"

namespace unsatmpm::explicit_run {

template <int D, class K>
ThreePhaseSolver<D, K> make_solver(const Case& c) {
  const auto grid = make_grid<D>(c);
  return ThreePhaseSolver<D, K>(c, grid, fill_bodies<D>(c, grid), 1);
}

/// Steps `s` from 0 to `end` [s] at half its critical step; returns the time reached.
template <class Solver>
double run(Solver& s, double end) {
  double t = 0.0;
  while (t < end) {
    const double dt = std::min(0.5 * s.critical_time_step(), end - t);
    s.step(t, dt);
    t += dt;
  }
  return t;
}

}  // namespace unsatmpm::explicit_run

// What the CVODE wrapper's sparse LU solvers (numerics/umfpack_keeper.hpp, numerics/klu_keeper.hpp)
// share across the keepers of one integrator: their counted work and the fill-reducing ordering
// chosen by trial. Both solvers offer the same two orderings: AMD on the pattern of A + A^T (KLU's
// ordering 0, UMFPACK's symmetric strategy) and COLAMD on the columns of A (KLU's ordering 1,
// UMFPACK's unsymmetric strategy). Neither wins everywhere (docs/performance.md): on the
// embankment's flow COLAMD needs 20 % fewer flops, on the scaling study's 2D block AMD three times
// fewer. The choice holds for the integrator's later patterns while their size stays within a
// fifth of the one it was tried on; above max_trial_unknowns AMD is taken untried: the trial's
// two factorisations would cost seconds there, and COLAMD's factors could take several times
// AMD's memory (three times the flops on the scaling study's 2D block).
#pragma once

#include <cstdlib>

namespace unsatmpm::numerics {

/// A sparse LU's work, summed over every keeper that shares it.
struct LuCounters {
  long analyses = 0, setups = 0;  // symbolic analyses, numeric factorisations
  double seconds = 0.0;           // wall time in setups and solves [s]
  double setup_seconds = 0.0;     // of which in setups [s]
};

/// The ordering the keepers of one integrator analyse with.
struct LuOrdering {
  static constexpr long max_trial_unknowns = 20000;
  int ordering = -1;  // 0 AMD, 1 COLAMD; -1 not tried yet
  long tried_on = 0;  // the unknowns of the matrix it was chosen on
  long trials = 0;

  /// Whether a matrix of n unknowns needs a trial; above the trial's bound it takes AMD at once.
  bool needs_trial(long n) {
    if (n > max_trial_unknowns) {
      ordering = 0, tried_on = n;
      return false;
    }
    return ordering < 0 || 5 * std::labs(n - tried_on) > tried_on;
  }
  /// Records the trial's outcome on a matrix of n unknowns.
  void chosen(int choice, long n) { ordering = choice, tried_on = n, ++trials; }
};

}  // namespace unsatmpm::numerics

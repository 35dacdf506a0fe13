// KLU for CVODE, keeping its symbolic analysis across CVodeReInit and counting its work (part of
// the CVODE wrapper: included through its private state, numerics/cvode_impl.hpp).
//
// CVODE calls SUNLinSolInitialize at the first CVode call after every CVodeInit/CVodeReInit, and
// SUNDIALS' KLU initialize forces a fresh symbolic analysis (first_factorize = 1). To keep the
// analysis when only the values change, CVODE talks to a thin forwarding SUNLinearSolver whose
// initialize is a no-op and whose setup counts the analyses KLU really performs (first_factorize
// 1 -> 0). A pattern change builds a new keeper, whose first setup analyses.
//
// The fill-reducing ordering is chosen by trial: before an analysis, KLU factorises the matrix
// with AMD and with COLAMD and the ordering with fewer flops is kept (KluOrdering). Neither wins
// everywhere (measured, docs/performance.md): on the embankment's flow (two fluids, GIMP's wide
// stencil) COLAMD needs 20 % fewer flops and refactorises in 31.7 ms against 45.7 ms; on the
// scaling study's 2D block (linear shape functions) AMD needs three times fewer (36 against
// 120 ms at 9,942 unknowns). The choice holds for the integrator's later patterns while their
// size stays within a fifth of the one it was tried on. Above max_trial_unknowns AMD is taken
// untried: there COLAMD's factors could take several times AMD's memory and time (three times
// the flops on the 2D block), and only a case that forces the direct solver gets there (`auto`
// takes GMRES from 12,000 unknowns in 2D and 1,000 in 3D, cycles/implicit_settings.hpp).
#pragma once

#include "numerics/sundials_handles.hpp"

namespace unsatmpm::numerics {

/// KLU's work, summed over every keeper that shares it.
struct KluCounters {
  long analyses = 0, setups = 0;  // symbolic analyses, numeric factorisations
  double seconds = 0.0;           // wall time in setups and solves [s]
  double setup_seconds = 0.0;     // of which in setups [s]
};

/// The ordering KLU analyses with, shared by the keepers of one integrator.
struct KluOrdering {
  static constexpr long max_trial_unknowns = 20000;
  int ordering = -1;  // KLU's: 0 AMD, 1 COLAMD; -1 not tried yet
  long tried_on = 0;  // the unknowns of the matrix it was chosen on
  long trials = 0;
};

class KluKeeper {
 public:
  /// KLU for `matrix`, sized like `y`; its work is added to `counters`, and it analyses with
  /// `ordering`'s choice (trying again where that does not fit), both of which must outlive it.
  KluKeeper(N_Vector y, SUNMatrix matrix, SUNContext context, KluCounters& counters,
            KluOrdering& ordering);
  KluKeeper(const KluKeeper&) = delete;
  KluKeeper& operator=(const KluKeeper&) = delete;

  /// The solver to hand to CVodeSetLinearSolver.
  SUNLinearSolver solver() const { return keeper_.get(); }

 private:
  static KluKeeper& owner(SUNLinearSolver s) { return *static_cast<KluKeeper*>(s->content); }
  static SUNLinearSolver_Type type(SUNLinearSolver) { return SUNLINEARSOLVER_DIRECT; }
  static SUNLinearSolver_ID id(SUNLinearSolver) { return SUNLINEARSOLVER_CUSTOM; }
  static int initialize(SUNLinearSolver) { return SUNLS_SUCCESS; }
  static int setup(SUNLinearSolver s, SUNMatrix A);
  static int solve(SUNLinearSolver s, SUNMatrix A, N_Vector x, N_Vector b, realtype tol);
  static sunindextype last_flag(SUNLinearSolver s);
  static int space(SUNLinearSolver s, long* lenrw, long* leniw);
  /// Sets KLU's ordering for the analysis of A, trying both where the choice does not fit A;
  /// returns SUNDIALS' flag.
  int choose_ordering(SUNMatrix A);

  KluCounters& counters_;
  KluOrdering& ordering_;
  sundials::LinearSolverPtr klu_;         // created first, destroyed last
  sundials::ForwardingSolverPtr keeper_;  // forwards to klu_
};

}  // namespace unsatmpm::numerics

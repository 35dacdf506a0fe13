// KLU for CVODE, keeping its symbolic analysis across CVodeReInit and counting its work (part of
// the CVODE wrapper: included through its private state, numerics/cvode_impl.hpp).
//
// CVODE calls SUNLinSolInitialize at the first CVode call after every CVodeInit/CVodeReInit, and
// SUNDIALS' KLU initialize forces a fresh symbolic analysis (first_factorize = 1). To keep the
// analysis when only the values change, CVODE talks to a thin forwarding SUNLinearSolver whose
// initialize is a no-op and whose setup counts the analyses KLU really performs (first_factorize
// 1 -> 0). A pattern change builds a new keeper, whose first setup analyses.
#pragma once

#include "numerics/sundials_handles.hpp"

namespace unsatmpm::numerics {

/// KLU's work, summed over every keeper that shares it.
struct KluCounters {
  long analyses = 0, setups = 0;  // symbolic analyses, numeric factorisations
  double seconds = 0.0;           // wall time in setups and solves [s]
  double setup_seconds = 0.0;     // of which in setups [s]
};

class KluKeeper {
 public:
  /// KLU (AMD ordering) for `matrix`, sized like `y`; its work is added to `counters`, which
  /// must outlive the keeper.
  KluKeeper(N_Vector y, SUNMatrix matrix, SUNContext context, KluCounters& counters);
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

  KluCounters& counters_;
  sundials::LinearSolverPtr klu_;         // created first, destroyed last
  sundials::ForwardingSolverPtr keeper_;  // forwards to klu_
};

}  // namespace unsatmpm::numerics

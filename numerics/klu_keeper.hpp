// KLU for CVODE, keeping its symbolic analysis across CVodeReInit and counting its work (part of
// the CVODE wrapper: included through its private state, numerics/cvode_impl.hpp).
//
// CVODE calls SUNLinSolInitialize at the first CVode call after every CVodeInit/CVodeReInit, and
// SUNDIALS' KLU initialize forces a fresh symbolic analysis (first_factorize = 1). To keep the
// analysis when only the values change, CVODE talks to a thin forwarding SUNLinearSolver whose
// initialize is a no-op and whose setup counts the analyses KLU really performs (first_factorize
// 1 -> 0). A pattern change builds a new keeper, whose first setup analyses.
//
// The fill-reducing ordering is chosen by trial (numerics/lu_work.hpp): before an analysis, KLU
// factorises the matrix with AMD and with COLAMD and the ordering with fewer flops is kept.
#pragma once

#include "numerics/lu_work.hpp"
#include "numerics/sundials_handles.hpp"

namespace unsatmpm::numerics {

class KluKeeper {
 public:
  /// KLU for `matrix`, sized like `y`; its work is added to `counters`, and it analyses with
  /// `ordering`'s choice (trying again where that does not fit), both of which must outlive it.
  KluKeeper(N_Vector y, SUNMatrix matrix, SUNContext context, LuCounters& counters,
            LuOrdering& ordering);
  KluKeeper(const KluKeeper&) = delete;
  KluKeeper& operator=(const KluKeeper&) = delete;

  /// The solver to hand to CVodeSetLinearSolver.
  SUNLinearSolver solver() const { return keeper_.get(); }

 private:
  static KluKeeper& owner(SUNLinearSolver s) { return *static_cast<KluKeeper*>(s->content); }
  static int setup(SUNLinearSolver s, SUNMatrix A);
  static int solve(SUNLinearSolver s, SUNMatrix A, N_Vector x, N_Vector b, realtype tol);
  static sunindextype last_flag(SUNLinearSolver s);
  static int space(SUNLinearSolver s, long* lenrw, long* leniw);
  /// Sets KLU's ordering for the analysis of A, trying both where the choice does not fit A;
  /// returns SUNDIALS' flag.
  int choose_ordering(SUNMatrix A);

  LuCounters& counters_;
  LuOrdering& ordering_;
  sundials::LinearSolverPtr klu_;         // created first, destroyed last
  sundials::ForwardingSolverPtr keeper_;  // forwards to klu_
};

}  // namespace unsatmpm::numerics

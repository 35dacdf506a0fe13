// UMFPACK for CVODE: the flow's default sparse direct solver (part of the CVODE wrapper: included
// through its private state, numerics/cvode_impl.hpp). UMFPACK (Davis, ACM TOMS 30 (2004) 196) is
// multifrontal: it factorises the Newton matrix in dense frontal blocks with the BLAS, where KLU's
// left-looking kernel (numerics/klu_keeper.hpp) works column by column. KLU is made for circuit
// matrices, which fill little; the flow's matrices fill four to five times over (two fluids,
// GIMP's 5 x 5 node coupling), and there the blocks pay. Measured on an embankment Newton matrix
// (3,636 unknowns, 173,269 nonzeros, COLAMD, Debian's serial OpenBLAS): 21 ms per factorisation
// and 0.55 ms per solve against KLU's 31 ms and 0.8 ms (docs/performance.md). With the reference
// BLAS UMFPACK takes 52 ms: scripts/setup.sh installs OpenBLAS's serial build, which leaves the
// cores to OpenMP and gives the same results whatever the thread count.
//
// One keeper serves one sparsity pattern (a pattern change builds a new one, as for KLU): its
// first setup analyses (with the ordering of numerics/lu_work.hpp, chosen by trial: the matrix
// factorised with both and the one with fewer flops kept), every later setup factorises the values
// anew with the kept analysis; UMFPACK pivots afresh at each factorisation. SUNDIALS' sparse
// matrices are compressed rows, read here as the columns of the transpose, whose transposed system
// is the one solved.
#pragma once

#include <vector>

#include "numerics/lu_work.hpp"
#include "numerics/sundials_handles.hpp"

namespace unsatmpm::numerics {

class UmfpackKeeper {
 public:
  /// UMFPACK for Newton matrices of one pattern; its work is added to `counters` and it analyses
  /// with `ordering`'s choice (trying again where that does not fit), both of which must outlive
  /// it.
  UmfpackKeeper(SUNContext context, LuCounters& counters, LuOrdering& ordering);
  ~UmfpackKeeper();
  UmfpackKeeper(const UmfpackKeeper&) = delete;
  UmfpackKeeper& operator=(const UmfpackKeeper&) = delete;

  /// The solver to hand to CVodeSetLinearSolver.
  SUNLinearSolver solver() const { return solver_.get(); }

 private:
  static UmfpackKeeper& owner(SUNLinearSolver s) {
    return *static_cast<UmfpackKeeper*>(s->content);
  }
  static int setup(SUNLinearSolver s, SUNMatrix A);
  static int solve(SUNLinearSolver s, SUNMatrix A, N_Vector x, N_Vector b, realtype tol);
  static sunindextype last_flag(SUNLinearSolver s) { return owner(s).status_; }

  /// Analyses A with ordering (0 AMD, 1 COLAMD) and factorises it; returns UMFPACK's status and
  /// leaves the analysis and factors in `symbolic` and `numeric` (to be freed by the caller).
  int analyse_and_factorise(SUNMatrix A, int ordering, void*& symbolic, void*& numeric,
                            double& flops) const;
  /// The first setup: the analysis, with the ordering's trial where it needs one.
  int first_setup(SUNMatrix A);
  void free_factors();

  LuCounters& counters_;
  LuOrdering& ordering_;
  std::vector<double> control_;  // UMFPACK's control parameters
  void* symbolic_ = nullptr;     // UMFPACK's analysis, kept for the keeper's life
  void* numeric_ = nullptr;      // the last factorisation
  std::vector<double> rhs_;      // the right-hand side (UMFPACK solves out of place)
  int status_ = 0;               // UMFPACK's last status
  sundials::ForwardingSolverPtr solver_;
};

}  // namespace unsatmpm::numerics

#include "numerics/klu_keeper.hpp"

#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include <chrono>
#include <limits>

namespace unsatmpm::numerics {

namespace {

/// KLU's flops to factorise A with `ordering` (A's compressed rows read as the columns of its
/// transpose, as SUNDIALS' KLU reads them); infinity where KLU fails.
double factorisation_flops(SUNMatrix A, int ordering) {
  klu_l_common common;
  klu_l_defaults(&common);
  common.ordering = ordering;
  sunindextype* starts = SUNSparseMatrix_IndexPointers(A);
  sunindextype* indices = SUNSparseMatrix_IndexValues(A);
  klu_l_symbolic* symbolic = klu_l_analyze(SUNSparseMatrix_NP(A), starts, indices, &common);
  if (symbolic == nullptr) return std::numeric_limits<double>::infinity();
  klu_l_numeric* numeric =
      klu_l_factor(starts, indices, SUNSparseMatrix_Data(A), symbolic, &common);
  double flops = std::numeric_limits<double>::infinity();
  if (numeric != nullptr && klu_l_flops(symbolic, numeric, &common) != 0) flops = common.flops;
  klu_l_free_numeric(&numeric, &common);
  klu_l_free_symbolic(&symbolic, &common);
  return flops;
}

}  // namespace

KluKeeper::KluKeeper(N_Vector y, SUNMatrix matrix, SUNContext context, LuCounters& counters,
                     LuOrdering& ordering)
    : counters_(counters), ordering_(ordering) {
  klu_.reset(sundials::check_created(SUNLinSol_KLU(y, matrix, context), "SUNLinSol_KLU"));
  keeper_ = sundials::direct_solver(context, this, setup, solve, last_flag);
  keeper_->ops->space = space;
}

int KluKeeper::setup(SUNLinearSolver s, SUNMatrix A) {
  KluKeeper& self = owner(s);
  const auto* content = static_cast<SUNLinearSolverContent_KLU>(self.klu_->content);
  const bool analyses = content->first_factorize != 0;
  const auto t0 = std::chrono::steady_clock::now();
  if (analyses) {
    if (const int flag = self.choose_ordering(A); flag != SUNLS_SUCCESS) return flag;
  }
  const int flag = SUNLinSolSetup(self.klu_.get(), A);
  const double seconds = sundials::seconds_since(t0);
  self.counters_.seconds += seconds;
  self.counters_.setup_seconds += seconds;
  ++self.counters_.setups;
  if (analyses && content->first_factorize == 0) ++self.counters_.analyses;
  return flag;
}

int KluKeeper::solve(SUNLinearSolver s, SUNMatrix A, N_Vector x, N_Vector b, realtype tol) {
  KluKeeper& self = owner(s);
  const auto t0 = std::chrono::steady_clock::now();
  const int flag = SUNLinSolSolve(self.klu_.get(), A, x, b, tol);
  self.counters_.seconds += sundials::seconds_since(t0);
  return flag;
}

int KluKeeper::choose_ordering(SUNMatrix A) {
  const long n = SUNSparseMatrix_NP(A);
  if (ordering_.needs_trial(n))
    ordering_.chosen(factorisation_flops(A, 1) < factorisation_flops(A, 0) ? 1 : 0, n);
  return SUNLinSol_KLUSetOrdering(klu_.get(), ordering_.ordering);
}

sunindextype KluKeeper::last_flag(SUNLinearSolver s) {
  return SUNLinSolLastFlag(owner(s).klu_.get());
}

int KluKeeper::space(SUNLinearSolver s, long* lenrw, long* leniw) {
  return SUNLinSolSpace(owner(s).klu_.get(), lenrw, leniw);
}

}  // namespace unsatmpm::numerics

#include "numerics/umfpack_keeper.hpp"

#include <sunmatrix/sunmatrix_sparse.h>
#include <umfpack.h>

#include <array>
#include <chrono>
#include <limits>

namespace unsatmpm::numerics {

namespace {

/// SUNDIALS' flag for UMFPACK's status: a singular matrix is recoverable (CVODE retries with a
/// smaller step, as it does for KLU's), any other failure (memory, a malformed matrix) is not.
int sundials_flag(int status) {
  if (status == UMFPACK_OK) return SUNLS_SUCCESS;
  return status == UMFPACK_WARNING_singular_matrix ? SUNLS_PACKAGE_FAIL_REC
                                                   : SUNLS_PACKAGE_FAIL_UNREC;
}

/// UMFPACK's strategy for the ordering (numerics/lu_work.hpp): AMD on A + A^T is its symmetric
/// strategy, COLAMD its unsymmetric one.
double strategy(int ordering) {
  return ordering == 1 ? UMFPACK_STRATEGY_UNSYMMETRIC : UMFPACK_STRATEGY_SYMMETRIC;
}

}  // namespace

UmfpackKeeper::UmfpackKeeper(SUNContext context, LuCounters& counters, LuOrdering& ordering)
    : counters_(counters), ordering_(ordering), control_(UMFPACK_CONTROL) {
  umfpack_dl_defaults(control_.data());
  // No iterative refinement: CVODE's Newton iteration refines, and each refinement step costs a
  // product with A and a solve.
  control_[UMFPACK_IRSTEP] = 0;
  solver_ = sundials::direct_solver(context, this, setup, solve, last_flag);
}

UmfpackKeeper::~UmfpackKeeper() {
  free_factors();
  if (symbolic_ != nullptr) umfpack_dl_free_symbolic(&symbolic_);
}

void UmfpackKeeper::free_factors() {
  if (numeric_ != nullptr) umfpack_dl_free_numeric(&numeric_);
}

int UmfpackKeeper::analyse_and_factorise(SUNMatrix A, int ordering, void*& symbolic, void*& numeric,
                                         double& flops) const {
  std::vector<double> control = control_;
  control[UMFPACK_STRATEGY] = strategy(ordering);
  double info[UMFPACK_INFO];
  const long n = SUNSparseMatrix_NP(A);
  const long* starts = SUNSparseMatrix_IndexPointers(A);
  const long* indices = SUNSparseMatrix_IndexValues(A);
  const double* values = SUNSparseMatrix_Data(A);
  int status = umfpack_dl_symbolic(n, n, starts, indices, values, &symbolic, control.data(), info);
  if (status != UMFPACK_OK) return status;
  status = umfpack_dl_numeric(starts, indices, values, symbolic, &numeric, control.data(), info);
  flops = status == UMFPACK_OK ? info[UMFPACK_FLOPS] : std::numeric_limits<double>::infinity();
  return status;
}

int UmfpackKeeper::first_setup(SUNMatrix A) {
  const long n = SUNSparseMatrix_NP(A);
  const bool trial = ordering_.needs_trial(n);
  std::array<void*, 2> symbolic{nullptr, nullptr}, numeric{nullptr, nullptr};
  std::array<double, 2> flops{0.0, 0.0};
  std::array<int, 2> status{UMFPACK_OK, UMFPACK_OK};
  for (int o = 0; o < 2; ++o)
    if (trial || o == ordering_.ordering)
      status[o] = analyse_and_factorise(A, o, symbolic[o], numeric[o], flops[o]);
  if (trial) ordering_.chosen(flops[1] < flops[0] ? 1 : 0, n);  // fewer flops kept
  const int kept = ordering_.ordering;
  for (int o = 0; o < 2; ++o) {
    if (o == kept) continue;
    if (numeric[o] != nullptr) umfpack_dl_free_numeric(&numeric[o]);
    if (symbolic[o] != nullptr) umfpack_dl_free_symbolic(&symbolic[o]);
  }
  symbolic_ = symbolic[kept], numeric_ = numeric[kept];
  control_[UMFPACK_STRATEGY] = strategy(kept);
  return status[kept];
}

int UmfpackKeeper::setup(SUNLinearSolver s, SUNMatrix A) {
  UmfpackKeeper& self = owner(s);
  const auto t0 = std::chrono::steady_clock::now();
  self.free_factors();
  if (self.symbolic_ == nullptr) {
    self.status_ = self.first_setup(A);
    if (self.symbolic_ != nullptr) ++self.counters_.analyses;
  } else {
    double info[UMFPACK_INFO];
    self.status_ = umfpack_dl_numeric(SUNSparseMatrix_IndexPointers(A),
                                      SUNSparseMatrix_IndexValues(A), SUNSparseMatrix_Data(A),
                                      self.symbolic_, &self.numeric_, self.control_.data(), info);
  }
  const double seconds = sundials::seconds_since(t0);
  self.counters_.seconds += seconds;
  self.counters_.setup_seconds += seconds;
  ++self.counters_.setups;
  return sundials_flag(self.status_);
}

int UmfpackKeeper::solve(SUNLinearSolver s, SUNMatrix A, N_Vector x, N_Vector b, realtype) {
  UmfpackKeeper& self = owner(s);
  if (self.numeric_ == nullptr) return SUNLS_MEM_FAIL;
  const auto t0 = std::chrono::steady_clock::now();
  const auto n = static_cast<std::size_t>(SUNSparseMatrix_NP(A));
  const double* rhs = N_VGetArrayPointer(b);
  self.rhs_.assign(rhs, rhs + n);  // x and b may be one vector
  double info[UMFPACK_INFO];
  // The compressed rows of A are the columns of A^T: solving (A^T)^T x = b solves A x = b.
  self.status_ =
      umfpack_dl_solve(UMFPACK_At, SUNSparseMatrix_IndexPointers(A), SUNSparseMatrix_IndexValues(A),
                       SUNSparseMatrix_Data(A), N_VGetArrayPointer(x), self.rhs_.data(),
                       self.numeric_, self.control_.data(), info);
  self.counters_.seconds += sundials::seconds_since(t0);
  return sundials_flag(self.status_);
}

}  // namespace unsatmpm::numerics

#include "numerics/sparse_gmres.hpp"

#include <sunlinsol/sunlinsol_spgmr.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "numerics/sundials_handles.hpp"

namespace unsatmpm::numerics {

// The context, the solver and its vectors (b, x, the weights), made for one size.
struct SparseGmres::Spgmr {
  sundials::ContextPtr context;
  sundials::VectorPtr b, x, w;
  sundials::LinearSolverPtr solver;
  std::int64_t n = -1;

  Spgmr() {
    SUNContext c = nullptr;
    if (SUNContext_Create(nullptr, &c) != 0 || c == nullptr)
      throw std::runtime_error("SparseGmres: SUNContext_Create failed");
    context.reset(c);
  }
};

namespace {

int times_callback(void* data, N_Vector v, N_Vector z) {
  const auto* s = static_cast<const SparseGmres*>(data);
  s->multiply(N_VGetArrayPointer(v), N_VGetArrayPointer(z));
  return 0;
}

int precondition_callback(void* data, N_Vector r, N_Vector z, realtype /*tol*/, int /*lr*/) {
  const auto* s = static_cast<const SparseGmres*>(data);
  s->precondition(N_VGetArrayPointer(r), N_VGetArrayPointer(z));
  return 0;
}

}  // namespace

SparseGmres::SparseGmres(int max_iterations)
    : spgmr_(std::make_unique<Spgmr>()), max_iterations_(max_iterations) {
  if (max_iterations < 1)
    throw std::invalid_argument("SparseGmres: max_iterations must be >= 1, got " +
                                std::to_string(max_iterations));
}

SparseGmres::~SparseGmres() = default;

void SparseGmres::set(const SparsePattern& pattern, std::span<const double> values,
                      std::span<const std::int64_t> partner) {
  const auto n = static_cast<std::size_t>(pattern.n);
  if (static_cast<std::int64_t>(values.size()) != pattern.n_nonzeros() || partner.size() != n)
    throw std::invalid_argument("SparseGmres: " + std::to_string(values.size()) + " values and " +
                                std::to_string(partner.size()) + " partners for a pattern of " +
                                std::to_string(pattern.n_nonzeros()) + " entries, " +
                                std::to_string(n) + " unknowns");
  pattern_ = nullptr;  // until the blocks are inverted: a failed set leaves nothing to solve with
  partner_.assign(partner.begin(), partner.end());
  own_.resize(n), cross_.resize(n);
  const auto entry = [&](std::int64_t r, std::int64_t c) {
    const std::int64_t e = pattern.position(r, c);
    return e < pattern.row_ptr[r + 1] && pattern.col[e] == c ? values[e] : 0.0;
  };
  for (std::int64_t k = 0; k < pattern.n; ++k) {
    const std::int64_t p = partner_[k];
    const double a = entry(k, k);
    if (p < 0) {
      if (!(std::abs(a) > 0.0))
        throw std::runtime_error("SparseGmres: zero diagonal in row " + std::to_string(k));
      own_[k] = 1.0 / a, cross_[k] = 0.0;
      continue;
    }
    if (p >= pattern.n || partner_[p] != k)
      throw std::invalid_argument("SparseGmres: the partner of " + std::to_string(k) +
                                  " is not mutual");
    // Row k of the inverse of [[a, b], [c, d]] (k first): (d, -b) / det.
    const double b = entry(k, p), c = entry(p, k), d = entry(p, p);
    const double det = a * d - b * c;
    if (!(std::abs(det) > 0.0) || !std::isfinite(det))
      throw std::runtime_error("SparseGmres: singular diagonal block at rows " + std::to_string(k) +
                               ", " + std::to_string(p));
    own_[k] = d / det, cross_[k] = -b / det;
  }
  pattern_ = &pattern, values_ = values;
  Spgmr& s = *spgmr_;
  if (s.n != pattern.n) {
    s.solver.reset();
    const auto make = [&] {
      return sundials::VectorPtr(sundials::check_created(
          N_VNew_Serial(static_cast<sunindextype>(pattern.n), s.context.get()), "N_VNew_Serial"));
    };
    s.b = make(), s.x = make(), s.w = make();
    for (N_Vector v : {s.b.get(), s.x.get(), s.w.get()}) sundials::use_blocked_dot(v);
    s.solver.reset(sundials::check_created(
        SUNLinSol_SPGMR(s.x.get(), SUN_PREC_RIGHT, max_iterations_, s.context.get()),
        "SUNLinSol_SPGMR"));
    SUNLinearSolver ls = s.solver.get();
    if (SUNLinSolSetATimes(ls, this, times_callback) != 0 ||
        SUNLinSolSetPreconditioner(ls, this, nullptr, precondition_callback) != 0 ||
        SUNLinSolSetScalingVectors(ls, s.w.get(), s.w.get()) != 0 || SUNLinSolInitialize(ls) != 0 ||
        SUNLinSolSetup(ls, nullptr) != 0)
      throw std::runtime_error("SparseGmres: setting up SPGMR failed");
    s.n = pattern.n;
  }
}

bool SparseGmres::solve(std::span<const double> b, std::span<const double> w, std::span<double> x,
                        int n_threads) {
  if (pattern_ == nullptr) throw std::logic_error("SparseGmres: solve before set");
  const auto n = static_cast<std::size_t>(pattern_->n);
  if (b.size() != n || w.size() != n || x.size() != n)
    throw std::invalid_argument("SparseGmres: vectors of " + std::to_string(b.size()) + ", " +
                                std::to_string(w.size()) + ", " + std::to_string(x.size()) +
                                " entries for " + std::to_string(n) + " unknowns");
  n_threads_ = std::max(1, n_threads);
  Spgmr& s = *spgmr_;
  std::copy(b.begin(), b.end(), N_VGetArrayPointer(s.b.get()));
  std::copy(x.begin(), x.end(), N_VGetArrayPointer(s.x.get()));
  std::copy(w.begin(), w.end(), N_VGetArrayPointer(s.w.get()));
  const int flag = SUNLinSolSolve(s.solver.get(), nullptr, s.x.get(), s.b.get(), 1.0);
  iterations_ += SUNLinSolNumIters(s.solver.get());
  if (flag != SUNLS_SUCCESS) return false;
  const double* xs = N_VGetArrayPointer(s.x.get());
  std::copy(xs, xs + n, x.begin());
  return true;
}

void SparseGmres::multiply(const double* v, double* z) const {
  const auto n = static_cast<std::size_t>(pattern_->n);
  numerics::multiply(*pattern_, values_, {v, n}, {z, n}, n_threads_);
}

void SparseGmres::precondition(const double* r, double* z) const {
  for (std::size_t k = 0; k < own_.size(); ++k) {
    const std::int64_t p = partner_[k];
    z[k] = own_[k] * r[k] + (p >= 0 ? cross_[k] * r[p] : 0.0);
  }
}

}  // namespace unsatmpm::numerics

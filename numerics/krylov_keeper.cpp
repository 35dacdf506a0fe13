#include "numerics/krylov_keeper.hpp"

#include <sunlinsol/sunlinsol_spgmr.h>

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <string>

namespace unsatmpm::numerics {

KrylovKeeper::KrylovKeeper(N_Vector y, SUNContext context, const SparsePattern& pattern,
                           KrylovCounters& counters)
    : pattern_(pattern),
      counters_(counters),
      jacobian_(static_cast<std::size_t>(pattern.n_nonzeros()), 0.0),
      newton_(jacobian_.size(), 0.0),
      diagonal_(static_cast<std::size_t>(pattern.n), -1) {
  for (std::int64_t i = 0; i < pattern.n; ++i)
    diagonal_[static_cast<std::size_t>(i)] = pattern.position(i, i);
  // Right preconditioning: GMRES then measures the unpreconditioned residual, which is what
  // CVODE's linear tolerance is set against.
  gmres_.reset(sundials::check_created(
      SUNLinSol_SPGMR(y, SUN_PREC_RIGHT, max_krylov_dimension, context), "SUNLinSol_SPGMR"));
}

int KrylovKeeper::setup(bool jok, bool* fresh, double gamma, const Evaluate& evaluate) {
  if (!jok) {
    std::fill(jacobian_.begin(), jacobian_.end(), 0.0);
    if (const int flag = evaluate(jacobian_); flag != 0) return flag;
  }
  *fresh = !jok;
  const auto t0 = std::chrono::steady_clock::now();
  for (std::size_t k = 0; k < jacobian_.size(); ++k) newton_[k] = -gamma * jacobian_[k];
  for (const std::int64_t k : diagonal_) newton_[static_cast<std::size_t>(k)] += 1.0;
  amg_.setup(pattern_, newton_);
  counters_.setup_seconds += sundials::seconds_since(t0);
  ++counters_.setups;
  return 0;
}

void KrylovKeeper::precondition(std::span<const double> r, std::span<double> z) {
  const auto t0 = std::chrono::steady_clock::now();
  amg_.apply(r, z);
  counters_.apply_seconds += sundials::seconds_since(t0);
}

void KrylovKeeper::multiply(std::span<const double> v, std::span<double> jv) const {
  numerics::multiply(pattern_, jacobian_, v, jv);
}

}  // namespace unsatmpm::numerics

// The iterative alternative to KLU inside CVODE's Newton iteration (part of the CVODE wrapper:
// included through its private state, numerics/cvode_impl.hpp): GMRES without restarts
// (SUNDIALS' SPGMR; Saad & Schultz, SIAM J. Sci. Stat. Comput. 7 (1986) 856) on
// (I - gamma J) x = b, right-preconditioned by algebraic-multigrid V-cycles of the same matrix
// (numerics/amg_preconditioner.hpp).
//
// The Jacobian J is assembled into the pattern when CVODE asks for a fresh one (the
// preconditioner setup with jok false) and kept: its products J v are exact products with the
// kept matrix, as the direct solver's Newton matrix is kept between setups; the Newton residual
// is always the exact rhs.
#pragma once

#include <functional>
#include <span>
#include <vector>

#include "numerics/amg_preconditioner.hpp"
#include "numerics/sparse_pattern.hpp"
#include "numerics/sundials_handles.hpp"

namespace unsatmpm::numerics {

/// The preconditioner's work, summed over every keeper that shares it.
struct KrylovCounters {
  long setups = 0;             // preconditioner setups (AMG hierarchies built)
  double setup_seconds = 0.0;  // wall time in them [s]
  double apply_seconds = 0.0;  // wall time in the V-cycles [s]
};

class KrylovKeeper {
 public:
  /// Fills `values` (zeroed, the pattern's entry order) with J at the state CVODE passes; returns
  /// the Jacobian callback's flag.
  using Evaluate = std::function<int(std::span<double> values)>;

  /// GMRES (at most `max_krylov_dimension` iterations per solve, no restarts) for vectors like
  /// `y`, the matrix's pattern `pattern`; work is added to `counters`, which must outlive it.
  KrylovKeeper(N_Vector y, SUNContext context, const SparsePattern& pattern,
               KrylovCounters& counters);
  KrylovKeeper(const KrylovKeeper&) = delete;
  KrylovKeeper& operator=(const KrylovKeeper&) = delete;

  /// The solver to hand to CVodeSetLinearSolver (with no matrix).
  SUNLinearSolver solver() const { return gmres_.get(); }

  /// CVODE's preconditioner setup: J evaluated anew unless `jok` (then *fresh = false), and the
  /// multigrid hierarchy of I - gamma J built. Returns the Jacobian's flag (0, >0 recoverable).
  int setup(bool jok, bool* fresh, double gamma, const Evaluate& evaluate);
  /// z = the multigrid V-cycles of I - gamma J applied to r.
  void precondition(std::span<const double> r, std::span<double> z);
  /// Jv = J v with the kept J.
  void multiply(std::span<const double> v, std::span<double> jv) const;

  static constexpr int max_krylov_dimension = 30;

 private:
  const SparsePattern& pattern_;
  KrylovCounters& counters_;
  std::vector<double> jacobian_;        // J in the pattern's entry order
  std::vector<double> newton_;          // I - gamma J
  std::vector<std::int64_t> diagonal_;  // entry index of each row's diagonal
  AmgPreconditioner amg_;
  sundials::LinearSolverPtr gmres_;
};

}  // namespace unsatmpm::numerics

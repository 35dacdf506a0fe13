// Two V-cycles of algebraic multigrid (hypre's BoomerAMG: Henson & Yang, Appl. Numer. Math. 41
// (2002) 155) as the preconditioner of the flow's Krylov solver (numerics/krylov_keeper.hpp):
// z ~= M^-1 r for a sparse M given in CSR form. Only amg_preconditioner.cpp includes hypre.
//
// hypre is built with MPI in Debian: the first preconditioner initialises MPI (as a singleton
// process, no launcher needed) and hypre once per process, and both are finalised at exit. Runs
// that never choose the iterative solver never touch MPI.
#pragma once

#include <memory>
#include <span>

#include "numerics/sparse_pattern.hpp"

namespace unsatmpm::numerics {

class AmgPreconditioner {
 public:
  AmgPreconditioner();
  ~AmgPreconditioner();
  AmgPreconditioner(const AmgPreconditioner&) = delete;
  AmgPreconditioner& operator=(const AmgPreconditioner&) = delete;

  /// Builds the multigrid hierarchy of M (pattern and values, values in the pattern's entry
  /// order). Throws std::runtime_error if hypre reports an error.
  void setup(const SparsePattern& pattern, std::span<const double> values);
  /// z = the V-cycles applied to r from z = 0 (spans of length n). Needs a setup() first.
  void apply(std::span<const double> r, std::span<double> z);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace unsatmpm::numerics

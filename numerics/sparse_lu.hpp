// A sparse LU factorisation (SuiteSparse's KLU, 32-bit indices) of a square matrix given in the
// compressed sparse row form of numerics/sparse_pattern.hpp, for repeated solves with one matrix:
// the main cycle's flow correction (cycles/flow_correction.hpp) factorises once per coupling
// interval and solves at every mechanics sub-step. KLU rather than another solver: it is already
// a dependency (CVODE's linear solver) and the matrices are the pressure system's, for which it
// was measured (numerics/klu_keeper.cpp). The symbolic analysis is kept while the pattern stays
// the same; only its values are factorised again.
#pragma once

#include <memory>
#include <span>

#include "numerics/sparse_pattern.hpp"

namespace unsatmpm::numerics {

class SparseLu {
 public:
  SparseLu();
  ~SparseLu();
  SparseLu(const SparseLu&) = delete;
  SparseLu& operator=(const SparseLu&) = delete;

  /// Factorises the matrix with `pattern` and `values` (in the pattern's order); analyses the
  /// pattern first if it differs from the last one. Throws std::runtime_error if the matrix is
  /// singular or KLU fails.
  void factorise(const SparsePattern& pattern, std::span<const double> values);

  /// Solves A x = b in place (b in, x out) with the last factorisation.
  void solve(std::span<double> b) const;

  long n_analyses() const { return analyses_; }
  long n_factorisations() const { return factorisations_; }

 private:
  struct Klu;  // KLU's handles: only sparse_lu.cpp includes klu.h
  std::unique_ptr<Klu> klu_;
  SparsePattern pattern_;
  long analyses_ = 0, factorisations_ = 0;
};

}  // namespace unsatmpm::numerics

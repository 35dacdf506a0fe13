// GMRES for a sparse matrix in the compressed sparse row form of numerics/sparse_pattern.hpp, for
// many solves with one matrix: the main cycle's flow correction (cycles/flow_correction.hpp)
// solves at every mechanics sub-step with a matrix renewed about once per coupling interval.
// GMRES (Saad & Schultz, SIAM J. Sci. Stat. Comput. 7 (1986) 856; Saad, Iterative Methods for
// Sparse Linear Systems, 2nd ed., 2003, algorithm 6.9), without restarts: modified Gram-Schmidt
// and Givens rotations, right-preconditioned by the inverses of the matrix's 2 x 2 diagonal blocks
// (the two fluids of a node, strongly coupled through the storage), so that the residual it
// measures is the unpreconditioned one. The weights w of that residual scale both sides,
// W A P^-1 W^-1: the iterations then do not depend on the unit of each node's equations, which
// spans decades between dry and wetted nodes (with W on the left alone, W A P^-1, the Krylov
// space was skewed by them and GMRES stalled where two iterations suffice; docs/performance.md).
// The products with the matrix run on the given threads, each row summed in its own order, and
// the dot products in a fixed order (numerics::dot): the same bits on any number of threads.
//
// Ours rather than SUNDIALS' SPGMR, which it replaced with the same iteration (the same iteration
// counts): the solves here take one or two iterations on a few thousand unknowns, where SPGMR's
// own vector operations, one pass over the vectors each, took about four times the samples of the
// products with the matrix (perf on the embankment; docs/performance.md, "The flow correction's
// solve").
//
// Why beside a direct solve: a sparse LU's triangular solves read every entry of its factors,
// whose fill grows faster than the matrix, while the correction's matrix, storage plus a
// sub-step's conductance, is close to its block diagonal while the sub-step is short against the
// nodes' drainage time, and then a few products with the matrix solve it. Where it needs more,
// the caller falls back to the LU (docs/performance.md, "The flow correction's solve").
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "numerics/sparse_pattern.hpp"

namespace unsatmpm::numerics {

class SparseGmres {
 public:
  /// At most `max_iterations` (>= 1) Krylov iterations per solve.
  explicit SparseGmres(int max_iterations = 30);

  /// The matrix of the next solves: `pattern` and `values` (its entries in the pattern's order)
  /// are referenced, not copied, and must outlive them unchanged. `partner[k]`: the unknown that
  /// forms a 2 x 2 diagonal block with k (mutual), or -1 for a 1 x 1 block. Throws
  /// std::invalid_argument on a size mismatch or a partner that is not mutual, std::runtime_error
  /// naming the row if a diagonal block is singular.
  void set(const SparsePattern& pattern, std::span<const double> values,
           std::span<const std::int64_t> partner);

  /// Solves A x = b: `x` holds the initial guess on entry and the solution on return, reached
  /// when ||w * (b - A x)||_2 <= 1 (w > 0 per unknown, the weights of the residual). Returns
  /// false, x then unchanged, if max_iterations did not reach it. `n_threads` (>= 1) for the
  /// products.
  bool solve(std::span<const double> b, std::span<const double> w, std::span<double> x,
             int n_threads);

  /// Iterations over all solves so far.
  long n_iterations() const { return iterations_; }

  /// z = A v, and z = the block-diagonal inverse applied to r (the preconditioner): n values each.
  void multiply(const double* v, double* z) const;
  void precondition(const double* r, double* z) const;

 private:
  /// x += P^-1 W^-1 (sum_i y_i v_i) over the first `k` basis vectors: the solution's update.
  void add_update(int k, std::span<const double> w, std::span<double> x);

  int max_iterations_ = 30;
  const SparsePattern* pattern_ = nullptr;
  std::span<const double> values_;
  std::vector<std::int64_t> partner_;
  std::vector<double> own_, cross_;  // z_k = own_k r_k + cross_k r_partner(k)
  // The solves' scratch: the Krylov basis, (max_iterations + 1) vectors of n one after the other;
  // two vectors; the Hessenberg matrix by columns, (max_iterations + 1) rows each; the rotations
  // and the rotated right-hand side.
  std::vector<double> basis_, scratch_, product_, hessenberg_, cosine_, sine_, rotated_;
  int n_threads_ = 1;
  long iterations_ = 0;
};

}  // namespace unsatmpm::numerics

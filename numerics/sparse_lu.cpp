#include "numerics/sparse_lu.hpp"

#include <klu.h>

#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace unsatmpm::numerics {

// KLU takes compressed sparse columns. The pattern's rows handed over as columns describe A^T, so
// KLU factorises A^T and klu_tsolve, which solves with the transpose of what was factorised,
// solves A x = b. KLU's 32-bit interface: its factors store an index beside each value, and a
// solve reads all of them (memory-bound: docs/performance.md), so 4-byte indices read a quarter
// less than 8-byte ones.
struct SparseLu::Klu {
  klu_common common;
  klu_symbolic* symbolic = nullptr;
  klu_numeric* numeric = nullptr;
  std::vector<int> starts, indices;  // the pattern in KLU's index type

  Klu() {
    klu_defaults(&common);
    common.ordering = 0;  // AMD, as for CVODE's KLU (numerics/klu_keeper.cpp says why)
  }
  ~Klu() { release(); }
  void release() {
    if (numeric) klu_free_numeric(&numeric, &common);
    if (symbolic) klu_free_symbolic(&symbolic, &common);
  }
};

SparseLu::SparseLu() : klu_(std::make_unique<Klu>()) {}
SparseLu::~SparseLu() = default;

void SparseLu::factorise(const SparsePattern& pattern, std::span<const double> values) {
  if (static_cast<std::int64_t>(values.size()) != pattern.n_nonzeros())
    throw std::invalid_argument("SparseLu: " + std::to_string(values.size()) +
                                " values for a pattern of " + std::to_string(pattern.n_nonzeros()) +
                                " entries");
  Klu& k = *klu_;
  if (!k.symbolic || !(pattern == pattern_)) {
    if (pattern.n_nonzeros() > std::numeric_limits<int>::max())
      throw std::runtime_error("SparseLu: " + std::to_string(pattern.n_nonzeros()) +
                               " entries, beyond KLU's 32-bit indices");
    k.release();
    pattern_ = pattern;
    k.starts.assign(pattern.row_ptr.begin(), pattern.row_ptr.end());
    k.indices.assign(pattern.col.begin(), pattern.col.end());
    k.symbolic =
        klu_analyze(static_cast<int>(pattern.n), k.starts.data(), k.indices.data(), &k.common);
    if (!k.symbolic)
      throw std::runtime_error("SparseLu: KLU analysis failed (status " +
                               std::to_string(k.common.status) + ")");
    ++analyses_;
  }
  if (k.numeric) klu_free_numeric(&k.numeric, &k.common);
  // klu_factor does not write the values; its signature is not const.
  k.numeric = klu_factor(k.starts.data(), k.indices.data(), const_cast<double*>(values.data()),
                         k.symbolic, &k.common);
  if (!k.numeric || k.common.status != KLU_OK)
    throw std::runtime_error(k.common.status == KLU_SINGULAR
                                 ? std::string("SparseLu: the matrix is singular")
                                 : "SparseLu: KLU factorisation failed (status " +
                                       std::to_string(k.common.status) + ")");
  ++factorisations_;
}

void SparseLu::solve(std::span<double> b) const {
  Klu& k = *klu_;
  if (!k.numeric) throw std::logic_error("SparseLu: solve before factorise");
  if (static_cast<std::int64_t>(b.size()) != pattern_.n)
    throw std::invalid_argument("SparseLu: right-hand side of " + std::to_string(b.size()) +
                                " entries for " + std::to_string(pattern_.n) + " unknowns");
  if (klu_tsolve(k.symbolic, k.numeric, static_cast<int>(pattern_.n), 1, b.data(), &k.common) != 1)
    throw std::runtime_error("SparseLu: KLU solve failed (status " +
                             std::to_string(k.common.status) + ")");
}

}  // namespace unsatmpm::numerics

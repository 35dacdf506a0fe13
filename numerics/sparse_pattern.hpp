// The sparsity pattern of a square sparse matrix in compressed sparse row form: what the pressure
// system assembles its Jacobian into and what the CVODE/KLU wrapper factorises.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

namespace unsatmpm::numerics {

/// Sparsity pattern of the n x n Jacobian df/dy in compressed sparse row form. Columns sorted and
/// unique in each row; every diagonal entry present (CVODE forms I - gamma J in place).
struct SparsePattern {
  std::int64_t n = 0;
  std::vector<std::int64_t> row_ptr;  // n + 1 offsets into col, row_ptr[0] = 0
  std::vector<std::int64_t> col;      // column index of each stored entry

  std::int64_t n_nonzeros() const { return row_ptr.empty() ? 0 : row_ptr.back(); }
  bool operator==(const SparsePattern&) const = default;

  /// Index in the value array of entry (row, column), which must be in the pattern.
  std::int64_t position(std::int64_t row, std::int64_t column) const {
    const auto first = col.begin() + row_ptr[row];
    const auto last = col.begin() + row_ptr[row + 1];
    return std::lower_bound(first, last, column) - col.begin();
  }
};

}  // namespace unsatmpm::numerics

// The sparsity pattern of a square sparse matrix in compressed sparse row form: what the pressure
// system assembles its Jacobian into and what the CVODE wrapper's sparse LU factorises.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
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

  /// Throws std::invalid_argument unless the pattern is well formed: n >= 1, n + 1 offsets from
  /// 0, columns in range, sorted and unique in each row, every diagonal entry present.
  void validate() const {
    auto fail = [](const std::string& what) {
      throw std::invalid_argument("SparsePattern: " + what);
    };
    if (n < 1) fail("n must be >= 1, got " + std::to_string(n));
    if (static_cast<std::int64_t>(row_ptr.size()) != n + 1)
      fail("row_ptr needs n + 1 = " + std::to_string(n + 1) + " entries, got " +
           std::to_string(row_ptr.size()));
    if (row_ptr.front() != 0) fail("row_ptr[0] must be 0");
    if (static_cast<std::int64_t>(col.size()) != row_ptr.back())
      fail("col has " + std::to_string(col.size()) + " entries, row_ptr[n] says " +
           std::to_string(row_ptr.back()));
    for (std::int64_t i = 0; i < n; ++i) {
      const std::int64_t begin = row_ptr[i], end = row_ptr[i + 1];
      if (end < begin) fail("row_ptr decreases at row " + std::to_string(i));
      bool has_diagonal = false;
      for (std::int64_t k = begin; k < end; ++k) {
        const std::int64_t j = col[k];
        if (j < 0 || j >= n)
          fail("column " + std::to_string(j) + " out of range in row " + std::to_string(i));
        if (k > begin && j <= col[k - 1])
          fail("columns not sorted and unique in row " + std::to_string(i));
        has_diagonal = has_diagonal || j == i;
      }
      if (!has_diagonal) fail("diagonal entry missing in row " + std::to_string(i));
    }
  }

  /// Index in the value array of entry (row, column), which must be in the pattern.
  std::int64_t position(std::int64_t row, std::int64_t column) const {
    const auto first = col.begin() + row_ptr[row];
    const auto last = col.begin() + row_ptr[row + 1];
    return std::lower_bound(first, last, column) - col.begin();
  }
};

/// The pattern of the rows' column lists (any order, repeats allowed, columns in [0, n)), each
/// row's diagonal added. Repeats are dropped by marking each column with the last row it entered,
/// so that a row sorts its distinct columns only: the pressure systems list every pair of a
/// point's stencil nodes, about 14 entries per kept one with GIMP in 2D, and sorting them all was
/// 3 % of the samples of the embankment's bench to 15 s (docs/performance.md). Throws
/// std::invalid_argument for a column out of range.
inline SparsePattern pattern_from_rows(const std::vector<std::vector<std::int64_t>>& rows) {
  SparsePattern pattern;
  pattern.n = static_cast<std::int64_t>(rows.size());
  pattern.row_ptr.assign(1, 0);
  std::vector<std::int64_t> entered(rows.size(), -1);  // the last row each column entered
  for (std::int64_t r = 0; r < pattern.n; ++r) {
    const auto first = static_cast<std::ptrdiff_t>(pattern.col.size());
    const auto add = [&](std::int64_t j) {
      if (j < 0 || j >= pattern.n)
        throw std::invalid_argument("pattern_from_rows: column " + std::to_string(j) +
                                    " out of range in row " + std::to_string(r));
      if (entered[j] != r) entered[j] = r, pattern.col.push_back(j);
    };
    add(r);
    for (const auto j : rows[r]) add(j);
    std::sort(pattern.col.begin() + first, pattern.col.end());
    pattern.row_ptr.push_back(static_cast<std::int64_t>(pattern.col.size()));
  }
  return pattern;
}

/// x . y over the shorter length, in eight independent sums: SUNDIALS' serial dot product adds
/// into one sum, a chain of dependent additions that held SPGMR's Gram-Schmidt at about 4 cycles
/// per entry (perf: 4 % of the embankment's samples on one thread, more than the products with
/// the matrix; docs/performance.md). Fixed order: the same bits on every run. CVODE's GMRES takes
/// it through sundials::use_blocked_dot, the flow correction's (numerics/sparse_gmres.hpp)
/// directly.
inline double dot(std::span<const double> x, std::span<const double> y) {
  const std::size_t n = std::min(x.size(), y.size());
  double s[8] = {};
  std::size_t i = 0;
  for (; i + 8 <= n; i += 8)
    for (std::size_t k = 0; k < 8; ++k) s[k] += x[i + k] * y[i + k];
  for (; i < n; ++i) s[0] += x[i] * y[i];
  return ((s[0] + s[1]) + (s[2] + s[3])) + ((s[4] + s[5]) + (s[6] + s[7]));
}

/// y = A x for the matrix with `pattern` and `values` (its entries in the pattern's order), rows
/// shared among `n_threads` threads, each row summed in its own order: the same bits on any number
/// of threads.
inline void multiply(const SparsePattern& pattern, std::span<const double> values,
                     std::span<const double> x, std::span<double> y, int n_threads = 1) {
#pragma omp parallel for num_threads(n_threads) schedule(static) if (n_threads > 1)
  for (std::int64_t r = 0; r < pattern.n; ++r) {
    double s = 0.0;
    for (auto k = pattern.row_ptr[r]; k < pattern.row_ptr[r + 1]; ++k)
      s += values[k] * x[pattern.col[k]];
    y[r] = s;
  }
}

}  // namespace unsatmpm::numerics

// The sparse LU wrapper: solves non-symmetric systems to round-off, keeps its analysis while the
// pattern stays, analyses again when it changes, and refuses singular matrices and misfitting
// sizes with a message.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "numerics/sparse_lu.hpp"

namespace unsatmpm::numerics {
namespace test_sparse_lu {

/// A band pattern (offsets -2 .. 2, plus one far entry per row) of n unknowns.
SparsePattern band_pattern(std::int64_t n) {
  SparsePattern p;
  p.n = n;
  p.row_ptr.assign(1, 0);
  for (std::int64_t r = 0; r < n; ++r) {
    std::vector<std::int64_t> c;
    for (std::int64_t j = std::max<std::int64_t>(0, r - 2); j <= std::min(n - 1, r + 2); ++j)
      c.push_back(j);
    const std::int64_t far = (r + n / 2) % n;
    if (far < r - 2 || far > r + 2) c.push_back(far);
    std::sort(c.begin(), c.end());
    p.col.insert(p.col.end(), c.begin(), c.end());
    p.row_ptr.push_back(static_cast<std::int64_t>(p.col.size()));
  }
  p.validate();
  return p;
}

/// Random values, non-symmetric, with a diagonal that dominates each row.
std::vector<double> values(const SparsePattern& p, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> v(p.n_nonzeros());
  for (std::int64_t r = 0; r < p.n; ++r) {
    double off = 0.0;
    for (auto k = p.row_ptr[r]; k < p.row_ptr[r + 1]; ++k)
      if (p.col[k] != r) off += std::abs(v[k] = u(gen));
    v[p.position(r, r)] = off + 0.5 + std::abs(u(gen));
  }
  return v;
}

double residual(const SparsePattern& p, const std::vector<double>& v, const std::vector<double>& x,
                const std::vector<double>& b) {
  double worst = 0.0;
  for (std::int64_t r = 0; r < p.n; ++r) {
    double s = 0.0;
    for (auto k = p.row_ptr[r]; k < p.row_ptr[r + 1]; ++k) s += v[k] * x[p.col[k]];
    worst = std::max(worst, std::abs(s - b[r]));
  }
  return worst;
}

TEST(SparseLu, SolvesANonSymmetricSystemAndKeepsItsAnalysis) {
  const SparsePattern p = band_pattern(40);
  SparseLu lu;
  for (unsigned seed : {1u, 2u, 3u}) {
    const auto v = values(p, seed);
    lu.factorise(p, v);
    std::vector<double> b(p.n), x(p.n);
    for (std::int64_t r = 0; r < p.n; ++r) b[r] = x[r] = std::sin(0.3 * r + seed);
    lu.solve(x);
    EXPECT_LT(residual(p, v, x, b), 1e-12);
  }
  EXPECT_EQ(lu.n_analyses(), 1);
  EXPECT_EQ(lu.n_factorisations(), 3);
  const SparsePattern q = band_pattern(41);
  lu.factorise(q, values(q, 4));
  EXPECT_EQ(lu.n_analyses(), 2);
}

TEST(SparseLu, RefusesSingularMatricesAndMisfittingSizes) {
  const SparsePattern p = band_pattern(10);
  SparseLu lu;
  std::vector<double> x(10, 1.0);
  EXPECT_THROW(lu.solve(x), std::logic_error);
  std::vector<double> v = values(p, 5);
  for (auto k = p.row_ptr[3]; k < p.row_ptr[4]; ++k) v[k] = 0.0;  // an empty row
  try {
    lu.factorise(p, v);
    FAIL() << "a singular matrix was factorised";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("singular"), std::string::npos) << e.what();
  }
  EXPECT_THROW(lu.factorise(p, std::vector<double>(3, 1.0)), std::invalid_argument);
  lu.factorise(p, values(p, 6));
  std::vector<double> short_b(9, 1.0);
  EXPECT_THROW(lu.solve(short_b), std::invalid_argument);
}

}  // namespace test_sparse_lu
}  // namespace unsatmpm::numerics

// numerics::pattern_from_rows against a plain reference (each row's columns sorted and made
// unique, its diagonal added), on random rows with many repeats; and its refusal of a column out
// of range.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <set>
#include <stdexcept>
#include <vector>

#include "numerics/sparse_pattern.hpp"

namespace unsatmpm::numerics {
namespace {

TEST(SparsePattern, FromRowsKeepsEachRowsDistinctColumnsSortedWithItsDiagonal) {
  std::mt19937_64 random(7);
  for (const std::int64_t n : {1, 2, 17, 300}) {
    std::uniform_int_distribution<std::int64_t> column(0, n - 1);
    std::uniform_int_distribution<int> length(0, 60);
    std::vector<std::vector<std::int64_t>> rows(static_cast<std::size_t>(n));
    for (auto& r : rows) {
      const int m = length(random);
      for (int k = 0; k < m; ++k) r.push_back(column(random));
    }
    const SparsePattern p = pattern_from_rows(rows);
    ASSERT_NO_THROW(p.validate()) << "n = " << n;
    for (std::int64_t i = 0; i < n; ++i) {
      std::set<std::int64_t> expected(rows[i].begin(), rows[i].end());
      expected.insert(i);
      const std::vector<std::int64_t> got(p.col.begin() + p.row_ptr[i],
                                          p.col.begin() + p.row_ptr[i + 1]);
      EXPECT_EQ(got, std::vector<std::int64_t>(expected.begin(), expected.end()))
          << "n = " << n << ", row " << i;
    }
  }
}

TEST(SparsePattern, FromRowsRefusesAColumnOutOfRange) {
  EXPECT_THROW(pattern_from_rows({{0, 1}, {2}}), std::invalid_argument);
  EXPECT_THROW(pattern_from_rows({{-1}, {0}}), std::invalid_argument);
  EXPECT_NO_THROW(pattern_from_rows({{1}, {0}}));
}

}  // namespace
}  // namespace unsatmpm::numerics

// parallel_region (numerics/parallel.hpp): every index once, reductions on the body's loops, and
// on one thread no OpenMP team at all.
#include <omp.h>

#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "numerics/parallel.hpp"

namespace unsatmpm::numerics {
namespace {

constexpr std::int64_t n = 1001;

// The body's loop covers [0, n) once, its reductions see every index, and it runs inside a team of
// the threads asked for (omp_in_parallel) only when more than one is asked for.
TEST(Parallel, RegionRunsItsLoopsOnceAndNoTeamOnOneThread) {
  for (const int threads : {1, 2}) {
    std::vector<int> visits(n, 0);
    std::int64_t sum = 0, largest = -1;
    int in_team = 0, team_size = 0;
    parallel_region(threads, [&] {
#pragma omp single
      in_team = omp_in_parallel(), team_size = omp_get_num_threads();
#pragma omp for schedule(static) reduction(+ : sum) reduction(max : largest)
      for (std::int64_t i = 0; i < n; ++i) {
        ++visits[i];
        sum += i;
        largest = i > largest ? i : largest;
      }
    });
    for (std::int64_t i = 0; i < n; ++i) EXPECT_EQ(visits[i], 1) << "index " << i;
    EXPECT_EQ(sum, n * (n - 1) / 2);
    EXPECT_EQ(largest, n - 1);
    EXPECT_EQ(in_team, threads > 1 ? 1 : 0) << threads << " threads";
    EXPECT_EQ(team_size, threads);
  }
}

}  // namespace
}  // namespace unsatmpm::numerics

// The points' stencils kept for the offsets' relaxation (numerics/offset_stencils.hpp): each
// point's cached entries are the transfer stencil's, bit for bit, in 1D, 2D and 3D with both
// kernels, and the cache follows the points when they move and are filled again.
#include <gtest/gtest.h>

#include <random>

#include "numerics/offset_stencils.hpp"

namespace unsatmpm::numerics {
namespace test_offset_stencils {

template <int D>
MaterialPoints<D> random_points(const Grid<D>& g, int n, std::mt19937& rng) {
  MaterialPoints<D> mp;
  const Vec<D> half = g.spacing / 4.0;
  for (int p = 0; p < n; ++p) {
    Vec<D> x;
    for (int d = 0; d < D; ++d)
      x[d] = std::uniform_real_distribution<double>(g.origin[d], g.upper()[d])(rng);
    mp.push_back(0, x, half, 1.0, half.prod());
  }
  // Points on a node line and half a GIMP width off it, where supports start within a cell.
  for (int p = 0; p < 4; ++p) {
    Vec<D> x;
    for (int d = 0; d < D; ++d) x[d] = g.origin[d] + g.spacing[d] * (2.0 + (p % 2) * 0.25);
    mp.push_back(0, x, half, 1.0, half.prod());
  }
  return mp;
}

template <int D, class K>
void expect_cache_matches_stencils() {
  Vec<D> origin = Vec<D>::Constant(-0.3), spacing;
  std::array<int, D> cells;
  for (int d = 0; d < D; ++d) spacing[d] = 0.1 + 0.05 * d, cells[d] = 6 + d;
  const Grid<D> g(origin, spacing, cells);
  std::mt19937 rng(7);
  MaterialPoints<D> mp = random_points<D>(g, 50, rng);
  StencilCache cache;
  TransferStencil<D, K, false> st;
  for (int round = 0; round < 2; ++round) {
    fill_stencils<D, K>(g, mp, 1, cache);
    for (std::int64_t p = 0; p < static_cast<std::int64_t>(mp.size()); ++p) {
      evaluate_stencil<D, K>(st, g, mp, p);
      const CachedStencil c = cache[p];
      ASSERT_EQ(c.n, st.n) << D << "D, point " << p;
      for (int k = 0; k < st.n; ++k) {
        EXPECT_EQ(c.node(k), st.node[k]) << D << "D, point " << p << ", entry " << k;
        EXPECT_EQ(c.slot(k), st.slot(k));
        EXPECT_TRUE(c.w[k] == st.w[k]);
      }
      const Vec<D> offset = (mp.position[p] - g.node_position(st.node[0])).cwiseQuotient(g.spacing);
      for (int a = 0; a < D; ++a) EXPECT_TRUE(cache.offset_of(p, a) == offset[a]);
    }
    for (auto& x : mp.position) x += 0.37 * g.spacing;  // moved: the next fill must follow
    for (auto& x : mp.position) x = x.cwiseMin(g.upper() - 1e-9 * g.spacing);
  }
}

TEST(OffsetStencils, TheCacheHoldsTheTransferStencilsBitForBit) {
  expect_cache_matches_stencils<1, LinearKernel>();
  expect_cache_matches_stencils<2, LinearKernel>();
  expect_cache_matches_stencils<3, LinearKernel>();
  expect_cache_matches_stencils<1, GimpKernel>();
  expect_cache_matches_stencils<2, GimpKernel>();
  expect_cache_matches_stencils<3, GimpKernel>();
}

// A cache filled for other points is refused, not read out of its bounds.
TEST(OffsetStencils, ACacheOfOtherPointsIsRefused) {
  const Grid<2> g(Vec<2>(0.0, 0.0), Vec<2>(0.2, 0.2), {10, 10});
  std::mt19937 rng(5);
  const MaterialPoints<2> mp = random_points<2>(g, 30, rng);
  StencilCache cache;
  EXPECT_THROW(cache.require(mp.size()), std::logic_error);
  fill_stencils<2, GimpKernel>(g, mp, 1, cache);
  EXPECT_NO_THROW(cache.require(mp.size()));
  EXPECT_THROW(cache.require(mp.size() + 1), std::logic_error);
}

// Filled on two threads, the cache is the one thread's.
TEST(OffsetStencils, TwoThreadsFillTheSameCache) {
  const Grid<2> g(Vec<2>(0.0, 0.0), Vec<2>(0.2, 0.2), {10, 10});
  std::mt19937 rng(3);
  const MaterialPoints<2> mp = random_points<2>(g, 300, rng);
  StencilCache one, two;
  fill_stencils<2, GimpKernel>(g, mp, 1, one);
  fill_stencils<2, GimpKernel>(g, mp, 2, two);
  EXPECT_EQ(one.w, two.w);
  EXPECT_EQ(one.slots, two.slots);
  EXPECT_EQ(one.count, two.count);
  EXPECT_EQ(one.first, two.first);
  EXPECT_EQ(one.offset, two.offset);
}

}  // namespace test_offset_stencils
}  // namespace unsatmpm::numerics

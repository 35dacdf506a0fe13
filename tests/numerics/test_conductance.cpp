// The Darcy conductance of the flow correction (numerics/pressure/conductance.hpp) on randomly
// placed points, linear and GIMP: symmetric, its quadratic form the points' sum of V c |grad x|^2
// (so positive semi-definite), its rows summing to zero over all nodes (no mass created), and
// with prescribed nodes the restriction of the full operator to the free ones.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <type_traits>
#include <vector>

#include "numerics/pressure/conductance.hpp"
#include "numerics/pressure/pressure_system.hpp"
#include "tests/numerics/linear_soil.hpp"

namespace unsatmpm::numerics {
namespace test_conductance {

template <class K>
struct Block {
  Grid<2> grid{Vec<2>(0.0, 0.0), Vec<2>(0.5, 0.5), {4, 4}};
  MaterialPoints<2> mp;
  FluidPoints<2> fp;
  std::vector<std::int64_t> ranges{0};
  std::array<std::vector<double>, 2> conductivity;

  explicit Block(unsigned seed) {
    std::mt19937 gen(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    // 3 x 3 cells of material in the middle of the grid, 2 x 2 points each, shaken.
    for (int cx = 0; cx < 3; ++cx)
      for (int cy = 0; cy < 3; ++cy)
        for (int k = 0; k < 4; ++k)
          mp.push_back(0,
                       Vec<2>(0.25 + 0.5 * cx + 0.125 + 0.25 * (k % 2) + 0.05 * (u(gen) - 0.5),
                              0.25 + 0.5 * cy + 0.125 + 0.25 * (k / 2) + 0.05 * (u(gen) - 0.5)),
                       Vec<2>(0.125, 0.125), 100.0, 0.0625 * (0.8 + 0.4 * u(gen)));
    ranges.push_back(static_cast<std::int64_t>(mp.size()));
    fp.resize(mp.size());
    for (auto& c : conductivity) {
      c.resize(mp.size());
      for (auto& v : c) v = 1e-6 * (0.1 + u(gen));
    }
    for (auto& n : fp.porosity) n = 0.35;
  }
};

template <class K>
class ConductanceTest : public ::testing::Test {};
using Kernels = ::testing::Types<LinearKernel, GimpKernel>;
TYPED_TEST_SUITE(ConductanceTest, Kernels);

/// The conductance's values of a block, prescribed where `prescribed` says (per fluid, per node).
template <class K>
struct Assembled {
  PressureSystem<2, K> system;
  SparsePattern pattern;
  std::vector<double> values;

  Assembled(const Block<K>& b, const std::array<std::vector<std::uint8_t>, 2>& prescribed,
            double drop = 0.0)
      : system(b.grid, {linear_soil()}, physics::MassBalance::full, Vec<2>(0.0, 0.0)) {
    for (int a = 0; a < 2; ++a) system.set_prescribed(a, prescribed[a]);
    system.set_jacobian_drop_tolerance(drop);
    system.prepare(b.mp, b.fp, b.ranges);
    pattern = conductance_pattern<2, K>(system.quadrature(), system.unknowns());
    pattern.validate();
    values.resize(pattern.n_nonzeros());
    assemble_conductance<2, K>(system.quadrature(), system.unknowns(), b.conductivity, pattern,
                               values);
  }
};

TYPED_TEST(ConductanceTest, IsSymmetricPositiveAndMovesNoMassBetweenAllNodes) {
  using K = TypeParam;
  const Block<K> b(7);
  const std::vector<std::uint8_t> none(b.grid.n_nodes(), 0);
  // Without and with the Jacobian's drop tolerance (GIMP drops nodes; linear drops none).
  std::vector<std::int64_t> nonzeros;
  for (const double drop : {0.0, 0.05}) {
    const Assembled<K> l(b, {none, none}, drop);
    nonzeros.push_back(l.pattern.n_nonzeros());
    const auto& u = l.system.unknowns();
    ASSERT_EQ(l.pattern.n, l.system.n_pressure_unknowns());
    double scale = 0.0;
    for (const double v : l.values) scale = std::max(scale, std::abs(v));
    for (std::int64_t r = 0; r < l.pattern.n; ++r) {
      double row = 0.0;
      for (auto k = l.pattern.row_ptr[r]; k < l.pattern.row_ptr[r + 1]; ++k) {
        row += l.values[k];
        const auto c = l.pattern.col[k];
        EXPECT_NEAR(l.values[k], l.values[l.pattern.position(c, r)], 1e-14 * scale);
      }
      EXPECT_NEAR(row, 0.0, 1e-13 * scale) << "row " << r << ", drop " << drop;
    }
    // x^T L x against the points' sum of V c |g . x|^2 (with the full gradients where nothing
    // is dropped), for a random nodal field per fluid.
    std::mt19937 gen(3);
    std::uniform_real_distribution<double> rnd(-1.0, 1.0);
    std::vector<double> x(l.pattern.n), lx(l.pattern.n);
    for (auto& v : x) v = rnd(gen);
    multiply(l.pattern, l.values, x, lx);
    double form = 0.0, energy = 0.0, full = 0.0;
    for (std::int64_t k = 0; k < l.pattern.n; ++k) form += x[k] * lx[k];
    const auto& q = l.system.quadrature();
    for (std::size_t p = 0; p < q.size(); ++p) {
      const auto g = kept_gradients<2, K>(q, p);
      for (int f = 0; f < 2; ++f) {
        Vec<2> gk = Vec<2>::Zero(), gf = Vec<2>::Zero();
        for (int a = 0; a < q.stencil[p].n; ++a) {
          gk += g[a] * x[u(f, q.stencil[p].node[a])];
          gf += q.stencil[p].grad[a] * x[u(f, q.stencil[p].node[a])];
        }
        energy += q.volume[p] * b.conductivity[f][p] * gk.squaredNorm();
        full += q.volume[p] * b.conductivity[f][p] * gf.squaredNorm();
      }
    }
    EXPECT_GT(energy, 0.0);
    EXPECT_NEAR(form, energy, 1e-12 * energy);
    if (drop == 0.0) {
      EXPECT_NEAR(form, full, 1e-12 * full);
    }
  }
  if constexpr (std::is_same_v<K, GimpKernel>) {
    EXPECT_LT(nonzeros[1], nonzeros[0]);
  } else {
    EXPECT_EQ(nonzeros[1], nonzeros[0]);
  }
}

TYPED_TEST(ConductanceTest, WithPrescribedNodesIsTheFreeNodesPartOfTheFullOperator) {
  using K = TypeParam;
  const Block<K> b(11);
  const std::vector<std::uint8_t> none(b.grid.n_nodes(), 0);
  std::array<std::vector<std::uint8_t>, 2> held{none, none};
  for (std::int64_t i = 0; i < b.grid.n_nodes(); ++i)
    if (b.grid.node_ijk(i)[1] >= 3) held[0][i] = 1;  // the liquid on the top rows
  held[1][2 + 2 * b.grid.stride[1]] = 1;
  const Assembled<K> full(b, {none, none}), part(b, held);
  const auto& uf = full.system.unknowns();
  const auto& up = part.system.unknowns();
  int compared = 0;
  for (const auto i : up.nodes())
    for (const auto j : up.nodes())
      for (int f = 0; f < 2; ++f) {
        const auto r = up(f, i), c = up(f, j);
        if (r < 0 || c < 0) continue;
        const auto& pp = part.pattern;
        const auto first = pp.col.begin() + pp.row_ptr[r],
                   last = pp.col.begin() + pp.row_ptr[r + 1];
        const auto it = std::lower_bound(first, last, c);
        const double v = it != last && *it == c ? part.values[it - pp.col.begin()] : 0.0;
        const auto& fpat = full.pattern;
        const auto rf = uf(f, i), cf = uf(f, j);
        const auto ff = fpat.col.begin() + fpat.row_ptr[rf],
                   lf = fpat.col.begin() + fpat.row_ptr[rf + 1];
        const auto jt = std::lower_bound(ff, lf, cf);
        const double w = jt != lf && *jt == cf ? full.values[jt - fpat.col.begin()] : 0.0;
        EXPECT_EQ(v, w) << "node " << i << ", " << j << ", fluid " << f;
        compared += v != 0.0;
      }
  EXPECT_GT(compared, 50);
}

}  // namespace test_conductance
}  // namespace unsatmpm::numerics

// A fluid's free-surface condition as a penalty on the face's trace
// (numerics/pressure/surface_penalty.hpp) in the pressure system: the coupling's total is
// (γ / h) λ |Γ| on a straight face between node lines, the surface nodes become unknowns, the
// Jacobian matches finite differences (the liquid alone, and both fluids), what the nodes
// store equals what enters, the penalty's mass included, and the flow correction's conductance
// gains the coupling between the free unknowns.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <utility>
#include <vector>

#include "numerics/pressure/conductance.hpp"
#include "numerics/pressure/pressure_system.hpp"
#include "tests/numerics/pressure_column.hpp"

namespace unsatmpm::numerics {
namespace test_surface_penalty {

constexpr double kGamma = 16.0;

/// A block on a 4 x 4 grid of 0.5 m cells: 2 x 2 points per cell filling y < 1.25, its top a
/// free face half a cell past the node line y = 1 (points jittered by `jitter` [m]).
struct Block {
  Grid<2> grid{Vec<2>(0.0, 0.0), Vec<2>(0.5, 0.5), {4, 4}};
  MaterialPoints<2> mp;
  FluidPoints<2> fp;
  std::vector<std::int64_t> ranges{0};

  Block(double jitter, unsigned seed) {
    std::mt19937 gen(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int ix = 0; ix < 8; ++ix)
      for (int iy = 0; iy < 5; ++iy)
        mp.push_back(
            0, Vec<2>(0.125 + 0.25 * ix + jitter * u(gen), 0.125 + 0.25 * iy + jitter * u(gen)),
            Vec<2>(0.125, 0.125), 100.0, 0.0625);
    ranges.push_back(static_cast<std::int64_t>(mp.size()));
    fp.resize(mp.size());
    for (std::size_t p = 0; p < mp.size(); ++p) fp.porosity[p] = 0.35 + 0.05 * u(gen);
  }
};

/// The liquid penalised towards P̄_l = -3e4 + 100 t, the gas held on the surface at 5e3 - 20 t
/// (or penalised too), and one more node's gas held at the base.
template <class S>
void configure(S& sys, const Block& b, bool penalise_gas) {
  std::vector<std::uint8_t> gas(b.grid.n_nodes(), 0);
  gas[2] = 1;
  sys.set_prescribed(gas_phase, gas);
  sys.set_surface_prescribed(liquid_phase, true);
  sys.set_surface_prescribed(gas_phase, true);
  sys.set_surface_penalty(liquid_phase, kGamma);
  if (penalise_gas) sys.set_surface_penalty(gas_phase, kGamma);
  sys.set_prescription([](double t, NodalPrescription& np) {
    for (std::size_t i = 0; i < np.prescribed[0].size(); ++i) {
      np.value[1][i] = 5e3 - 20.0 * t, np.rate[1][i] = -20.0;
      np.value[0][i] = -3e4 + 100.0 * t, np.rate[0][i] = 100.0;
    }
    np.surface_value = {-3e4 + 100.0 * t, 5e3 - 20.0 * t};
  });
}

/// Unknowns: P_g = 1e4 + noise, P_l = P_g - s with s from 3e4 to 1.2e5 Pa across x, plus noise.
template <class S>
std::vector<double> state(const S& sys, const Grid<2>& grid, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> y(sys.n_unknowns(), 0.0);
  for (std::int64_t k = 0; k < sys.n_pressure_unknowns(); ++k) {
    const auto [node, fluid] = sys.unknown_location(k);
    const double pg = 1e4 + 2e3 * u(gen), x = grid.node_position(node)[0] / 2.0;
    y[k] = fluid == gas_phase ? pg : pg - (3e4 + 9e4 * x) + 1e3 * u(gen);
  }
  return y;
}

TEST(SurfacePenalty, CouplesTheFaceWithItsMeasureAndFreesTheSurfaceNodes) {
  const Block b(0.0, 1);
  PressureSystem<2, GimpKernel> sys(b.grid, {van_genuchten_soil()}, MassBalance::full,
                                    Vec<2>(0.0, -9.81));
  configure(sys, b, false);
  sys.prepare(b.mp, b.fp, b.ranges);
  const FaceTrace& c = sys.surface_penalty_couplings()[liquid_phase];
  ASSERT_FALSE(c.value.empty());
  EXPECT_TRUE(sys.surface_penalty_couplings()[gas_phase].value.empty());
  // One soil: c sums to (γ / h) λ |Γ|, the face 2 m wide at y = 1.25 (GIMP volumes are exact
  // for points whose domains tile the body, so the face is found where it lies).
  const auto m = van_genuchten_soil();
  const double lambda = m.liquid_density(0.0) * m.intrinsic_permeability / m.liquid_viscosity;
  double total = 0.0;
  for (std::size_t k = 0; k < c.value.size(); ++k) {
    total += c.value[k];
    EXPECT_GT(b.grid.node_position(c.row[k])[1], 0.9);  // the rows at y = 1 and 1.5
  }
  EXPECT_NEAR(total, kGamma / 0.5 * lambda * 2.0, 1e-12 * total);
  // The liquid's surface nodes are unknowns but for the light ones (below an eighth of a full
  // node's volume), which stay held; the gas's are held.
  int free = 0;
  for (std::int64_t i = 0; i < b.grid.n_nodes(); ++i) {
    if (!sys.surface_nodes()[i]) continue;
    const bool light =
        node_volume_fraction<2>(b.grid, i, sys.quadrature().node_volume[i]) < inside_fraction;
    EXPECT_EQ(sys.unknown(liquid_phase, i) < 0, light) << i;
    EXPECT_EQ(sys.unknown(gas_phase, i), -1) << i;
    if (!light) ++free;
  }
  EXPECT_GT(free, 0);
  EXPECT_THROW(sys.set_surface_penalty(liquid_phase, -1.0), std::invalid_argument);
}

// Under rain the penalty acts on the held part of the face (held_part): the entries between the
// held surface nodes and the nodes off the surface that the trace couples to one of them. Node 0
// is a held surface node, 1 a surface node in flux mode; 2 lies inside and couples to 0, 3 inside
// and couples to 1 and 2 alone. Kept: the entries among 0 and 2, whatever the flags say of the
// nodes off the surface.
TEST(SurfacePenalty, UnderRainItActsOnTheHeldPartOfTheFaceAlone) {
  FaceTrace c;
  for (const auto& [i, j] : std::vector<std::pair<int, int>>{
           {0, 0}, {0, 2}, {1, 1}, {1, 3}, {2, 0}, {2, 2}, {2, 3}, {3, 1}, {3, 2}, {3, 3}})
    c.row.push_back(i), c.col.push_back(j), c.value.push_back(1.0 + i + 10.0 * j);
  const std::vector<std::uint8_t> surface{1, 1, 0, 0};
  for (const std::vector<std::uint8_t>& exempt :
       {std::vector<std::uint8_t>{0, 1, 1, 1}, std::vector<std::uint8_t>{0, 1, 0, 0}}) {
    const FaceTrace h = held_part(c, surface, exempt);
    ASSERT_EQ(h.value.size(), 4u);
    const std::vector<std::int64_t> rows{0, 0, 2, 2}, cols{0, 2, 0, 2};
    EXPECT_EQ(h.row, rows);
    EXPECT_EQ(h.col, cols);
    for (std::size_t k = 0; k < h.value.size(); ++k)
      EXPECT_EQ(h.value[k], 1.0 + static_cast<double>(h.row[k]) + 10.0 * h.col[k]);
  }
  // No flags: the whole face; every surface node in flux mode: none of it.
  EXPECT_EQ(held_part(c, surface, {}).value.size(), c.value.size());
  EXPECT_TRUE(held_part(c, surface, {1, 1, 1, 1}).value.empty());
}

TEST(SurfacePenalty, JacobianMatchesFiniteDifferences) {
  for (const bool both : {false, true})
    for (const unsigned seed : {2u, 5u}) {
      const Block b(0.03, seed);
      PressureSystem<2, GimpKernel> sys(b.grid, {van_genuchten_soil()}, MassBalance::full,
                                        Vec<2>(0.0, -9.81));
      configure(sys, b, both);
      sys.prepare(b.mp, b.fp, b.ranges);
      // The tolerance of tests/numerics/test_pressure_system.cpp (fd_tolerance), same step.
      EXPECT_LT(jacobian_error(sys, state(sys, b.grid, seed), 0.7), 1e-6)
          << (both ? "both fluids" : "the liquid") << ", seed " << seed;
    }
}

TEST(SurfacePenalty, StorageChangeEqualsInflowWithThePenaltysMass) {
  for (const bool both : {false, true}) {
    const Block b(0.03, 3);
    PressureSystem<2, GimpKernel> sys(b.grid, {van_genuchten_soil()}, MassBalance::full,
                                      Vec<2>(0.0, -9.81));
    configure(sys, b, both);
    sys.prepare(b.mp, b.fp, b.ranges);
    const auto y = state(sys, b.grid, 3);
    std::vector<double> ydot(y.size());
    ASSERT_EQ(sys.rhs(0.0, y, ydot), 0);
    const auto stored = sys.storage_rate(0.0, y), inflow = sys.boundary_inflow(0.0, y);
    for (int a = 0; a < 2; ++a) {
      EXPECT_NEAR(stored[a], inflow[a], 1e-10 * std::abs(inflow[a])) << a;
      EXPECT_NEAR(ydot[sys.inflow_unknown(a)] * sys.inflow_scale(a), inflow[a],
                  1e-12 * std::abs(inflow[a]));
    }
    // The face is wetter than the soil under it (P̄_l above every P_l): water enters.
    EXPECT_GT(inflow[liquid_phase], 0.0);
  }
}

TEST(SurfacePenalty, TheCorrectionsConductanceGainsTheCoupling) {
  // The flow correction's L (numerics/pressure/conductance.hpp) with the penalties of both
  // fluids against L without them, in the same pattern: they differ by c between the fluids'
  // free unknowns, entry by entry, and L stays symmetric with x^T L x grown by x^T c x >= 0.
  const Block b(0.03, 4);
  PressureSystem<2, GimpKernel> sys(b.grid, {van_genuchten_soil()}, MassBalance::full,
                                    Vec<2>(0.0, -9.81));
  configure(sys, b, true);
  sys.prepare(b.mp, b.fp, b.ranges);
  const auto& q = sys.quadrature();
  const auto& u = sys.unknowns();
  const FacePenalties& face = sys.surface_penalty_couplings();
  std::array<std::vector<double>, 2> conductivity{std::vector<double>(q.size(), 1e-6),
                                                  std::vector<double>(q.size(), 3e-8)};
  const SparsePattern pattern = conductance_pattern<2, GimpKernel>(q, u, face);
  pattern.validate();
  std::vector<double> plain(pattern.n_nonzeros()), with(pattern.n_nonzeros());
  assemble_conductance<2, GimpKernel>(q, u, conductivity, pattern, plain);
  assemble_conductance<2, GimpKernel>(q, u, conductivity, pattern, with, face);
  std::vector<double> expected = plain;
  int coupled = 0;
  for (int f = 0; f < 2; ++f)
    for (std::size_t k = 0; k < face[f].value.size(); ++k)
      if (const auto r = u(f, face[f].row[k]), c = u(f, face[f].col[k]); r >= 0 && c >= 0) {
        expected[pattern.position(r, c)] += face[f].value[k];
        coupled += face[f].value[k] > 0.0;
      }
  EXPECT_GT(coupled, 4);
  double scale = 0.0;
  for (const double v : with) scale = std::max(scale, std::abs(v));
  for (std::int64_t r = 0; r < pattern.n; ++r)
    for (auto k = pattern.row_ptr[r]; k < pattern.row_ptr[r + 1]; ++k) {
      EXPECT_NEAR(with[k], expected[k], 1e-14 * scale) << "row " << r;
      EXPECT_NEAR(with[k], with[pattern.position(pattern.col[k], r)], 1e-14 * scale);
    }
  std::mt19937 gen(9);
  std::uniform_real_distribution<double> rnd(-1.0, 1.0);
  std::vector<double> x(pattern.n), lx(pattern.n), px(pattern.n);
  for (auto& v : x) v = rnd(gen);
  multiply(pattern, with, x, lx);
  multiply(pattern, plain, x, px);
  double grown = 0.0, base = 0.0;
  for (std::int64_t k = 0; k < pattern.n; ++k) grown += x[k] * lx[k], base += x[k] * px[k];
  EXPECT_GT(base, 0.0);
  EXPECT_GT(grown, base);
}

}  // namespace test_surface_penalty
}  // namespace unsatmpm::numerics

// The main cycle's two-way coupling (cycles/undrained.hpp): the undrained stiffness against its
// definition by finite differences; the sub-steps' wave speed is the mixture's; a point block
// compressed with its fluids kept: the pressure rises by the undrained stiffness, the masses stay,
// and a held (prescribed) node lets the water out and counts it; the flow's share: a point takes
// what moves it with the flow's field, the rest goes to its neighbours through the nodes, and
// nothing is lost.
#include "cycles/undrained.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "tests/cycles/undrained_block.hpp"

namespace unsatmpm {
namespace test_undrained {

TEST(Undrained, StiffnessMatchesTheMassKeepingPressureChange) {
  const physics::HydraulicModel hm = soil();
  const double n = 0.3;
  // Saturated at positive pressure (liquid held alone), unsaturated (gas governs), and nearly
  // saturated with both fluids free.
  for (const auto& [pl, pg, held] :
       {std::tuple{5e3, 0.0, true}, {-3e4, 0.0, false}, {-800.0, 0.0, false}}) {
    const double k = undrained_stiffness(hm, n, pl, pg, held);
    EXPECT_NEAR(k, stiffness_by_differences(hm, n, pl, pg, held), 1e-5 * k) << pl;
  }
  // Saturated water: K_l / n.
  EXPECT_NEAR(undrained_stiffness(hm, n, 5e3, 0.0, true), 2e9 / n, 1e-3 * 2e9 / n);
}

TEST(Undrained, TheStepsWaveSpeedIsTheMixturesUndrainedPWave) {
  // Saturated points at rest: c = sqrt((M + K_l / n) V / (m_s + n V rho_l)), the fluid's mass
  // moving with the solid (p2g's mixture mass), not the solid's alone.
  const numerics::Grid<1> grid(numerics::Vec<1>(0.0), numerics::Vec<1>(0.25), {4});
  const std::vector<physics::HydraulicModel> models{soil()};
  const std::vector<double> moduli{1.35e7};
  Block b({{1e4, 0.0}, {1e4, 0.0}, {1e4, 0.0}, {1e4, 0.0}});
  const auto& mp = b.points.points;
  const double n = 0.3, v = mp.volume[0];
  const double mixture = mp.mass[0] + n * v * b.fluids.liquid_density[0];
  const double k_u = undrained_stiffness(models[0], n, 1e4, 0.0, true);
  const double expected = std::sqrt((moduli[0] + k_u) * v / mixture);
  EXPECT_NEAR(undrained_wave_speed<1>(mp, b.fluids, models, moduli, b.points.ranges), expected,
              1e-12 * expected);
  UndrainedPoints u;
  begin_undrained_interval<1>(grid, mp, b.fluids, models, b.points.ranges, 1, u);
  const double rates =
      undrained_rates<1>(mp, models, moduli, b.points.ranges, 0.0, 1, false, b.fluids, u);
  EXPECT_NEAR(rates, expected, 1e-12 * expected);
  // The solid's mass alone would give a speed sqrt(mixture / m_s) = 1.08 times faster here.
  EXPECT_GT(std::sqrt((moduli[0] + k_u) * v / mp.mass[0]), 1.05 * expected);
}

TEST(Undrained, CompressionRaisesThePressureKeepsTheMassAndADrainedNodeLetsTheWaterOut) {
  const numerics::Grid<1> grid(numerics::Vec<1>(0.0), numerics::Vec<1>(0.25), {4});
  const std::vector<physics::HydraulicModel> models{soil()};
  const std::vector<double> moduli{1.35e7};
  for (const bool drained : {false, true}) {
    Block b({{1e4, 0.0}, {1e4, 0.0}, {1e4, 0.0}, {1e4, 0.0}});
    UndrainedPoints u;
    begin_undrained_interval<1>(grid, b.points.points, b.fluids, models, b.points.ranges, 1, u);
    for (auto& f : u.held) f.assign(grid.n_nodes(), 0);
    u.held[1].assign(grid.n_nodes(), 1);  // saturated: the gas is held everywhere
    if (drained) u.held[0][4] = 1;        // the right end's liquid pressure prescribed
    const auto before = fluid_masses<1>(b.points.points, b.fluids);
    const double eps = 1e-6;  // uniform compression
    for (auto& v : b.points.points.volume) v *= 1.0 - eps;
    const UndrainedReport r = undrained_update<1, numerics::LinearKernel>(
        grid, b.points.points, models, moduli, b.points.ranges, 1.0, 1, b.fluids, u);
    ASSERT_EQ(r.first_bad, -1);
    const auto after = fluid_masses<1>(b.points.points, b.fluids);
    // Each fluid's mass is what it was plus what entered at the held nodes.
    EXPECT_NEAR(after[0], before[0] + r.supplied[0], 1e-12 * before[0]) << drained;
    if (!drained) {
      EXPECT_EQ(r.supplied[0], 0.0);
      // The pressure rose by the undrained stiffness times the strain, K_l / n eps (n = 0.3).
      const double expected = undrained_stiffness(soil(), 0.3, 1e4, 0.0, true) * eps;
      for (std::size_t p = 0; p < 4; ++p)
        EXPECT_NEAR(b.fluids.liquid_pressure[p] - 1e4, expected, 1e-3 * expected);
    } else {
      // Water left through the drained node, and the pressure near it rose less.
      EXPECT_LT(r.supplied[0], 0.0);
      EXPECT_LT(b.fluids.liquid_pressure[3], b.fluids.liquid_pressure[0]);
    }
  }
}

TEST(Undrained, APointWhoseGasDensityVanishedIsReported) {
  // A gas of the exponential law 8 MPa below its reference (K = 10 kPa) at the third point: its
  // density has underflowed to 0 and it holds no gas, so its pressure is held, at a state no
  // physical pressure gives: reported, where the same law 8 kPa below is not.
  physics::HydraulicModel hm = soil();
  hm.gas = physics::CompressibleFluid::create(1.0, 0.0, 1e4);
  const numerics::Grid<1> grid(numerics::Vec<1>(0.0), numerics::Vec<1>(0.25), {4});
  const std::vector<physics::HydraulicModel> models{hm};
  for (const double pg : {-8e6, -8e3}) {
    Block b({{-1e4, 0.0}, {-1e4, 0.0}, {-1e4, pg}, {-1e4, 0.0}}, hm);
    ASSERT_EQ(b.fluids.gas_density[2] == 0.0, pg == -8e6);
    UndrainedPoints u;
    begin_undrained_interval<1>(grid, b.points.points, b.fluids, models, b.points.ranges, 1, u);
    for (auto& f : u.held) f.assign(grid.n_nodes(), 0);
    const UndrainedReport r = undrained_update<1, numerics::LinearKernel>(
        grid, b.points.points, models, {1.35e7}, b.points.ranges, 1.0, 1, b.fluids, u);
    EXPECT_EQ(r.first_bad, pg == -8e6 ? 2 : -1) << pg;
  }
}

TEST(Undrained, EachPointTakesItsShareOfTheFlowEvenBesideAHeldNode) {
  // No deformation; the flow gave the last point, beside a held node, 0.01 kg of water, with the
  // change of its field there that this mass makes at the point's own storage, and the others
  // nothing. That point alone gains it, in full, and nothing leaves at the held node (solved at
  // the nodes with the volume change, most of it had gone to the held node and left).
  const numerics::Grid<1> grid(numerics::Vec<1>(0.0), numerics::Vec<1>(0.25), {4});
  const std::vector<physics::HydraulicModel> models{soil()};
  Block b({{-5e4, 0.0}, {-5e4, 0.0}, {-5e4, 0.0}, {-5e4, 0.0}});
  UndrainedPoints u;
  begin_undrained_interval<1>(grid, b.points.points, b.fluids, models, b.points.ranges, 1, u);
  for (auto& f : u.held) f.assign(grid.n_nodes(), 0);
  u.held[0][4] = u.held[1][4] = 1;
  const physics::StorageMatrix a = models[0].storage(0.3, -5e4, 0.0);
  const double v = b.points.points.volume[3];
  u.flow_mass[0][3] = 0.01;
  // The field change (dl, dg) with V A (dl, dg) = (0.01, 0): water in, gas kept.
  const double det = a.ll * a.gg - a.lg * a.gl;
  u.flow_change[0][3] = 0.01 / v * a.gg / det, u.flow_change[1][3] = -0.01 / v * a.gl / det;
  std::vector<std::array<double, 2>> before;
  for (std::size_t p = 0; p < 4; ++p)
    before.push_back(point_fluid_masses<1>(b.points.points, b.fluids, p));
  const UndrainedReport r = undrained_update<1, numerics::LinearKernel>(
      grid, b.points.points, models, {1.35e7}, b.points.ranges, 1.0, 1, b.fluids, u);
  ASSERT_EQ(r.first_bad, -1);
  EXPECT_NEAR(r.supplied[0], 0.0, 1e-15);
  for (std::size_t p = 0; p < 4; ++p) {
    const auto m = point_fluid_masses<1>(b.points.points, b.fluids, p);
    EXPECT_NEAR(m[0] - before[p][0], p == 3 ? 0.01 : 0.0, 1e-9) << "point " << p;
    EXPECT_NEAR(m[1], before[p][1], 1e-9 * before[p][1] + 1e-15) << "point " << p;
  }
  EXPECT_GT(b.fluids.liquid_pressure[3], -5e4);
  EXPECT_DOUBLE_EQ(b.fluids.liquid_pressure[0], -5e4);
}

TEST(Undrained, APointTakesWhatItsOwnStorageHoldsAndTheRestGoesToItsNeighbours) {
  // The flow's field rose by 1 kPa at the last point and brought it twice the mass that rise
  // makes at the point's own storage (the fitted field is softer there, as across a saturation
  // front): the point's pressure rises by the field's 1 kPa, the rest of the mass goes to the
  // nodes, to its neighbours and out at the held node, and the sum is kept.
  const numerics::Grid<1> grid(numerics::Vec<1>(0.0), numerics::Vec<1>(0.25), {4});
  const std::vector<physics::HydraulicModel> models{soil()};
  Block b({{-5e4, 0.0}, {-5e4, 0.0}, {-5e4, 0.0}, {-5e4, 0.0}});
  UndrainedPoints u;
  begin_undrained_interval<1>(grid, b.points.points, b.fluids, models, b.points.ranges, 1, u);
  for (auto& f : u.held) f.assign(grid.n_nodes(), 0);
  u.held[0][4] = u.held[1][4] = 1;
  const physics::StorageMatrix a = models[0].storage(0.3, -5e4, 0.0);
  const double v = b.points.points.volume[3];
  u.flow_change[0][3] = 1e3;
  u.flow_mass[0][3] = 2.0 * v * a.ll * 1e3;
  double total_before = 0.0;
  for (std::size_t p = 0; p < 4; ++p)
    total_before += point_fluid_masses<1>(b.points.points, b.fluids, p)[0];
  const UndrainedReport r = undrained_update<1, numerics::LinearKernel>(
      grid, b.points.points, models, {1.35e7}, b.points.ranges, 1.0, 1, b.fluids, u);
  ASSERT_EQ(r.first_bad, -1);
  double total = 0.0;
  for (std::size_t p = 0; p < 4; ++p)
    total += point_fluid_masses<1>(b.points.points, b.fluids, p)[0];
  EXPECT_LT(r.supplied[0], 0.0);  // some left at the held node
  // The masses the points keep sum exactly (round-off); their pressures hold them to the
  // pressure tolerance at each point's storage.
  double kept = 0.0, slack = 0.0;
  for (std::size_t p = 0; p < 4; ++p)
    kept += u.old_mass[0][p], slack += v * a.ll * undrained_pressure_tolerance;
  EXPECT_NEAR(kept - total_before, u.flow_mass[0][3] + r.supplied[0], 1e-12 * total_before);
  EXPECT_NEAR(total, kept, slack);
  // The point rose by its field's 1 kPa plus what the nodes gave it; its neighbour rose too, the
  // first point (no node shared with the last) did not move.
  EXPECT_GT(b.fluids.liquid_pressure[3], -5e4 + 1e3);
  EXPECT_GT(b.fluids.liquid_pressure[2], -5e4);
  EXPECT_DOUBLE_EQ(b.fluids.liquid_pressure[0], -5e4);
}

TEST(Undrained, TheIntervalsSubStepsRelaxThePointsOffsetsWithinACellAndKeepTheMasses) {
  // Two points a cell, the liquid's pressure 2 kPa apart within every cell: a pattern neither the
  // nodal solve nor the flow sees (measured in the cells three or more from the body's edges: at
  // an edge node the linear fit passes through the two points of the outer cell and keeps it). A
  // sub-step without volume change keeps it; ten that relax it, each over a tenth of an interval
  // long against both fluids' diffusion across a cell (beta = 1), remove it, and both fluids'
  // masses stay what they were. Saturated (P_g held), one pass removes it; unsaturated, each pair
  // of passes leaves c = A_lg A_gl / (A_ll A_gg) of it (about 0.75 here), so the interval's ten
  // parts leave about c^10 = 0.06.
  const numerics::Grid<1> grid(numerics::Vec<1>(0.0), numerics::Vec<1>(0.25), {12});
  const std::vector<physics::HydraulicModel> models{soil()};
  for (const double mean : {-3e4, 5e3})
    for (const double relax_dt : {0.0, 1e6}) {
      PointSet<1> points;
      numerics::FluidPoints<1> fluids;
      for (std::size_t p = 0; p < 24; ++p)
        points.points.push_back(0, numerics::Vec<1>(0.0625 + 0.125 * p), numerics::Vec<1>(0.0625),
                                0.7 * 2700.0 * 0.125, 0.125);
      points.ranges = {0, 24};
      fluids.resize(24);
      for (std::size_t p = 0; p < 24; ++p) {
        fluids.porosity[p] = 0.3;
        fluids.liquid_pressure[p] = mean + (p % 2 == 0 ? -1e3 : 1e3), fluids.gas_pressure[p] = 0.0;
      }
      update_fluid_state<1>(models, points.ranges, fluids);
      const auto spread = [&] {
        double s = 0.0;
        for (std::size_t p = 6; p < 18; p += 2)  // cells 3 to 8, three or more from an edge
          s = std::max(s, std::abs(fluids.liquid_pressure[p + 1] - fluids.liquid_pressure[p]));
        return s;
      };
      UndrainedPoints u;
      begin_undrained_interval<1>(grid, points.points, fluids, models, points.ranges, 1, u);
      for (auto& f : u.held) f.assign(grid.n_nodes(), 0);
      if (mean > 0.0) u.held[1].assign(grid.n_nodes(), 1);  // saturated: the gas held
      const auto before = fluid_masses<1>(points.points, fluids);
      // The interval's sub-steps, each closing one of its parts.
      const int parts = relax_dt > 0.0 ? offset_relaxations_per_interval : 1;
      for (int k = 0; k < parts; ++k) {
        undrained_rates<1>(points.points, models, {1.35e7}, points.ranges, 1.0 / parts, 1, k > 0,
                           fluids, u);
        const UndrainedReport r =
            undrained_apply<1, numerics::LinearKernel>(grid, points.points, models, points.ranges,
                                                       1.0 / parts, 1, relax_dt / parts, fluids, u);
        ASSERT_EQ(r.first_bad, -1);
        EXPECT_EQ(r.supplied[0], 0.0);
      }
      // The masses kept exactly (the gas's too where it is a phase).
      double kept_l = 0.0, kept_g = 0.0;
      for (std::size_t p = 0; p < 24; ++p) kept_l += u.old_mass[0][p], kept_g += u.old_mass[1][p];
      EXPECT_NEAR(kept_l, before[0], 1e-12 * before[0]) << mean << " " << relax_dt;
      if (mean < 0.0) {
        EXPECT_NEAR(kept_g, before[1], 1e-12 * before[1]) << relax_dt;
      }
      if (relax_dt == 0.0) {
        EXPECT_GT(spread(), 0.99 * 2e3) << mean;
      } else {
        EXPECT_LT(spread(), (mean < 0.0 ? 0.1 : 0.01) * 2e3) << mean;
      }
    }
}
}  // namespace test_undrained
}  // namespace unsatmpm

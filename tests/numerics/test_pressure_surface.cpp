// The pressure system's free surface: found again at every prepare, its prescribed values
// switching on where it moves, and a gas value switched on alone there ramping in
// (numerics/pressure/jumps.hpp, GasSwitchOnRamps).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "numerics/pressure/pressure_system.hpp"
#include "tests/numerics/linear_soil.hpp"
#include "tests/numerics/pressure_column.hpp"

namespace unsatmpm::numerics {
namespace test_pressure_surface {

using System = PressureSystem<2, LinearKernel>;

// The free surface (set_surface_prescribed): the outer layer of the active region, found again by
// every prepare. Column's points fill cells [0, 4) x [0, 3) of a 6 x 5 grid: the surface is the
// active nodes of the cells that also have an inactive node, i = 4 and j = 3, and not the nodes on
// the grid's own faces x = 0 and y = 0 (the body rests against them).
TEST(PressureSystem, FreeSurfaceIsTheOuterLayerOfTheActiveRegion) {
  Column c(11);
  const Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(0.5, 0.5), {6, 5});
  System sys(grid, {van_genuchten_soil(), linear_soil()}, MassBalance::full, Vec<2>(0.0, -9.81));
  sys.set_surface_prescribed(liquid_phase, true);
  const double p_surface = -2e4;
  sys.set_prescription([&](double, NodalPrescription& np) {
    for (std::size_t i = 0; i < np.value[0].size(); ++i) np.value[0][i] = p_surface;
  });
  for (std::size_t p = 0; p < c.fp.size(); ++p)
    c.fp.liquid_pressure[p] = -8e5, c.fp.gas_pressure[p] = 0.0, c.fp.saturation[p] = 0.3;
  prepare(sys, c);
  const auto surface_of = [&](const System& s) {
    std::vector<std::array<int, 2>> nodes;
    for (std::int64_t i = 0; i < grid.n_nodes(); ++i)
      if (s.surface_nodes()[i]) nodes.push_back(grid.node_ijk(i));
    return nodes;
  };
  const std::vector<std::array<int, 2>> expected = {{4, 0}, {4, 1}, {4, 2}, {0, 3},
                                                    {1, 3}, {2, 3}, {3, 3}, {4, 3}};
  auto found = surface_of(sys);
  std::sort(found.begin(), found.end(),
            [](auto a, auto b) { return a[1] != b[1] ? a[1] < b[1] : a[0] < b[0]; });
  EXPECT_EQ(found, expected);
  // 20 active nodes: 12 liquid unknowns, 20 gas unknowns (the gas is not prescribed).
  EXPECT_EQ(sys.n_pressure_unknowns(), 32);

  // The first start switches the surface on: the mass M_i (p_surface - projected) enters.
  std::vector<double> y0(sys.n_unknowns());
  std::array<std::vector<double>, 2> field;
  sys.start(0.0, c.fp, y0, field, System::Prescribed::switch_on);
  EXPECT_GT(sys.start_inflow()[0], 0.0);
  for (std::int64_t i = 0; i < grid.n_nodes(); ++i) {
    if (sys.surface_nodes()[i]) {
      EXPECT_NEAR(field[0][i], -8e5, 1.0) << i;  // the projected value, not -2e4
    }
  }

  // Same configuration, continuing: nothing switches on again.
  prepare(sys, c);
  sys.start(0.0, c.fp, y0, field, System::Prescribed::continuing);
  EXPECT_EQ(sys.start_inflow()[0], 0.0);

  // The right column of cells emptied: the surface moves to i = 3, whose nodes switch on.
  MaterialPoints<2> fewer;
  FluidPoints<2> fewer_fp;
  std::vector<std::int64_t> ranges{0};
  std::vector<double> div;
  for (std::size_t m = 0; m + 1 < c.ranges.size(); ++m) {
    for (auto p = c.ranges[m]; p < c.ranges[m + 1]; ++p)
      if (c.mp.position[p][0] < 1.5)
        fewer.push_back(int(m), c.mp.position[p], c.mp.half_size[p], 100.0, 0.0625),
            div.push_back(0.0);
    ranges.push_back(static_cast<std::int64_t>(fewer.size()));
  }
  fewer_fp.resize(fewer.size());
  for (std::size_t p = 0; p < fewer.size(); ++p)
    fewer_fp.porosity[p] = 0.35, fewer_fp.liquid_pressure[p] = -8e5, fewer_fp.saturation[p] = 0.3;
  sys.set_solid_rate(div);
  EXPECT_TRUE(sys.prepare(fewer, fewer_fp, ranges));
  found = surface_of(sys);
  EXPECT_EQ(found.size(), 7u);
  for (const auto& ij : found) EXPECT_TRUE(ij[0] == 3 || ij[1] == 3) << ij[0] << ", " << ij[1];
  sys.start(0.0, fewer_fp, y0, field, System::Prescribed::continuing);
  EXPECT_GT(sys.start_inflow()[0], 0.0);  // the new surface nodes at i = 3 switched on
}

// A gas value switched on alone at a node newly on a moving free surface (its liquid an unknown)
// ramps in over the interval instead of jumping (GasSwitchOnRamps): no mass enters at the start,
// the node's gas goes from the fitted value at t0 to the prescribed one at the interval's end,
// linearly, and the rate it is given is that line's slope, counted as inflow like any prescribed
// rate. Controls: without a ramp end the same start jumps, and the jump brings gas; so does a
// node whose skeleton storage couples the liquid to the gas more than its retention does
// (|M_lg| > M_ll, GasSwitchOnRamps::suits).
TEST(PressureSystem, GasSwitchedOnAtAMovingSurfaceRampsIn) {
  Column c(13);
  const Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(0.5, 0.5), {6, 5});
  const double p_surface = 5e3, t0 = 2.0, t1 = 3.0;
  for (std::size_t p = 0; p < c.fp.size(); ++p)
    c.fp.liquid_pressure[p] = -2e4, c.fp.gas_pressure[p] = 0.0, c.fp.saturation[p] = 0.8;
  // The right column of cells emptied, as in the test above: the nodes at i = 3 come onto the
  // surface.
  MaterialPoints<2> fewer;
  FluidPoints<2> fewer_fp;
  std::vector<std::int64_t> ranges{0};
  for (std::size_t m = 0; m + 1 < c.ranges.size(); ++m) {
    for (auto p = c.ranges[m]; p < c.ranges[m + 1]; ++p)
      if (c.mp.position[p][0] < 1.5)
        fewer.push_back(int(m), c.mp.position[p], c.mp.half_size[p], 100.0, 0.0625);
    ranges.push_back(static_cast<std::int64_t>(fewer.size()));
  }
  fewer_fp.resize(fewer.size());
  for (std::size_t p = 0; p < fewer.size(); ++p)
    fewer_fp.porosity[p] = 0.35, fewer_fp.liquid_pressure[p] = -2e4, fewer_fp.gas_pressure[p] = 0.0,
    fewer_fp.saturation[p] = 0.8;
  const std::vector<double> no_rate(c.fp.size(), 0.0), no_rate_fewer(fewer.size(), 0.0);
  enum class Variant { ramp, no_ramp_end, soft_skeleton };
  for (const auto variant : {Variant::ramp, Variant::no_ramp_end, Variant::soft_skeleton}) {
    const bool ramp = variant == Variant::ramp;
    System sys(grid, {van_genuchten_soil(), van_genuchten_soil()}, MassBalance::full,
               Vec<2>(0.0, -9.81));
    sys.set_surface_prescribed(gas_phase, true);
    sys.set_prescription([&](double, NodalPrescription& np) {
      for (std::size_t i = 0; i < np.value[gas_phase].size(); ++i)
        np.value[gas_phase][i] = p_surface, np.rate[gas_phase][i] = 0.0;
    });
    std::vector<double> y0;
    std::array<std::vector<double>, 2> field;
    sys.set_solid_rate(no_rate);
    sys.prepare(c.mp, c.fp, c.ranges);
    y0.assign(sys.n_unknowns(), 0.0);
    sys.start(0.0, c.fp, y0, field, System::Prescribed::switch_on);  // the first surface
    sys.set_solid_rate(no_rate_fewer);
    if (variant == Variant::soft_skeleton)  // S_l rho_l / K with K = 1 kPa, in the gas column
      sys.set_extra_storage(std::vector<physics::StorageMatrix>(
          fewer.size(), physics::StorageMatrix{0.0, 0.8 * 1000.0 / 1e3, 0.0, 0.2 * 1.2 / 1e3}));
    sys.prepare(fewer, fewer_fp, ranges);
    if (variant != Variant::no_ramp_end) sys.set_ramp_end(t1);
    y0.assign(sys.n_unknowns(), 0.0);
    std::array<std::vector<double>, 2> fitted;
    sys.start(t0, fewer_fp, y0, fitted, System::Prescribed::continuing);
    std::vector<std::int64_t> fresh;  // the new surface nodes, at i = 3 below j = 3
    for (std::int64_t i = 0; i < grid.n_nodes(); ++i)
      if (const auto ij = grid.node_ijk(i); ij[0] == 3 && ij[1] < 3) fresh.push_back(i);
    ASSERT_EQ(fresh.size(), 3u);
    if (!ramp) {
      EXPECT_GT(sys.start_inflow()[gas_phase], 0.0);  // the controls: a jump brings gas
      continue;
    }
    EXPECT_EQ(sys.start_inflow()[gas_phase], 0.0);
    EXPECT_EQ(sys.start_inflow()[liquid_phase], 0.0);
    const auto at = [&](double t) {
      std::array<std::vector<double>, 2> p;
      sys.nodal_pressures(t, y0, p);
      return p;
    };
    const auto start = at(t0), mid = at(0.5 * (t0 + t1)), end = at(t1), after = at(t1 + 1.0);
    for (const auto i : fresh) {
      EXPECT_EQ(sys.unknown(gas_phase, i), -1) << i;  // prescribed
      EXPECT_GE(sys.unknown(liquid_phase, i), 0) << i;
      EXPECT_NEAR(start[gas_phase][i], fitted[gas_phase][i], 1e-9) << i;
      EXPECT_GT(std::abs(p_surface - start[gas_phase][i]), 1e3) << i;  // a ramp, not a no-op
      EXPECT_NEAR(mid[gas_phase][i], 0.5 * (start[gas_phase][i] + p_surface), 1e-9) << i;
      EXPECT_NEAR(end[gas_phase][i], p_surface, 1e-9) << i;
      EXPECT_NEAR(after[gas_phase][i], p_surface, 1e-9) << i;
    }
    // The rate handed to the flow is the ramp's slope: the gas stored at the nodes changes as
    // fast as the inflow says.
    std::vector<double> ydot(y0.size());
    ASSERT_EQ(sys.rhs(0.5 * (t0 + t1), y0, ydot), 0);
    const auto stored = sys.storage_rate(0.5 * (t0 + t1), y0);
    const auto q = sys.boundary_inflow(0.5 * (t0 + t1), y0);
    EXPECT_NEAR(stored[gas_phase], q[gas_phase], 1e-10 * std::abs(q[gas_phase]));
    EXPECT_GT(std::abs(q[gas_phase]), 0.0);
  }
}

}  // namespace test_pressure_surface
}  // namespace unsatmpm::numerics

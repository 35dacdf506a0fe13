// A row of 0.25 m points in one material for the main cycle's undrained update's tests
// (test_undrained.cpp, test_undrained_occluded.cpp): the soil, the block and a closed compression.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <utility>
#include <vector>

#include "cycles/three_phase_setup.hpp"
#include "cycles/undrained.hpp"
#include "physics/fluid_contents.hpp"

namespace unsatmpm::test_undrained {

inline physics::HydraulicModel soil(double kappa = 1e-12) {
  physics::HydraulicModel hm{};
  hm.liquid = physics::CompressibleFluid::create(1000.0, 0.0, 2e9);
  hm.gas = physics::IdealGas::create(1.2);
  hm.retention = physics::VanGenuchten::create(2e4, 0.4, 0.0, 1.0);
  hm.liquid_relative_permeability = physics::ConstantRelPerm{};
  hm.gas_relative_permeability = physics::GasPowerRelPerm::create(3.0);
  hm.solid_density = 2700.0;
  hm.intrinsic_permeability = kappa;
  hm.liquid_viscosity = 1e-3;
  hm.gas_viscosity = 1.8e-5;
  return hm;
}

/// dp*/d eps_v by finite differences: the pressures that keep both fluids' masses when the pore
/// volume n V shrinks by d eps V (the solid volume kept).
inline double stiffness_by_differences(const physics::HydraulicModel& hm, double n, double pl,
                                       double pg, bool held) {
  const auto [cl, cg] = physics::fluid_contents(hm, pl, pg);
  const double d = 1e-9;
  const double pores = n - d;  // per unit volume: V = 1 -> 1 - d
  double l = pl, g = pg;
  EXPECT_GE(physics::pressures_from_contents(hm, cl * n / pores, cg * n / pores, held, l, g), 0);
  return (pl >= pg ? l - pl : g - pg) / d;
}

/// A row of points in one material, each with its own state.
struct Block {
  PointSet<1> points;
  numerics::FluidPoints<1> fluids;
  explicit Block(std::vector<std::pair<double, double>> pressures,
                 const physics::HydraulicModel& hm = soil()) {
    const std::size_t n = pressures.size();
    for (std::size_t p = 0; p < n; ++p)
      points.points.push_back(0, numerics::Vec<1>(0.125 + 0.25 * p), numerics::Vec<1>(0.125),
                              0.7 * 2700.0 * 0.25, 0.25);
    points.ranges = {0, std::int64_t(n)};
    fluids.resize(n);
    for (std::size_t p = 0; p < n; ++p) {
      fluids.porosity[p] = 0.3;
      fluids.liquid_pressure[p] = pressures[p].first, fluids.gas_pressure[p] = pressures[p].second;
    }
    update_fluid_state<1>({hm}, points.ranges, fluids);
  }
};

/// The block's points compressed uniformly by eps of their volume, no node held, in one
/// undrained update on a 4-cell grid of 0.25 m (skeleton modulus 1.35e7 Pa).
inline UndrainedReport compress_closed(Block& b, const physics::HydraulicModel& hm, double eps) {
  const numerics::Grid<1> grid(numerics::Vec<1>(0.0), numerics::Vec<1>(0.25), {4});
  const std::vector<physics::HydraulicModel> models{hm};
  UndrainedPoints u;
  begin_undrained_interval<1>(grid, b.points.points, b.fluids, models, b.points.ranges, 1, u);
  for (auto& f : u.held) f.assign(grid.n_nodes(), 0);
  for (auto& v : b.points.points.volume) v *= 1.0 - eps;
  return undrained_update<1, numerics::LinearKernel>(grid, b.points.points, models, {1.35e7},
                                                     b.points.ranges, 1.0, 1, b.fluids, u);
}

}  // namespace unsatmpm::test_undrained

// The fixed-stress split's added storage (cycles/fixed_stress.hpp): S_a rho_a / K_dr in the
// column of the larger pressure, and the points' fluid state after a pressure update.
#include "cycles/fixed_stress.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace test_fixed_stress {

using namespace unsatmpm;

struct TwoPoints {
  PointSet<2> points;
  numerics::FluidPoints<2> fluids;
  TwoPoints() {
    for (int p = 0; p < 2; ++p)
      points.points.push_back(0, numerics::Vec<2>(0.5 + p, 0.5), numerics::Vec<2>(0.25, 0.25), 1.0,
                              0.25);
    points.ranges = {0, 2};
    fluids.resize(2);
    for (int p = 0; p < 2; ++p)
      fluids.saturation[p] = 0.8, fluids.liquid_density[p] = 1000.0, fluids.gas_density[p] = 1.2;
    fluids.liquid_pressure = {-2e4, 3e3};  // unsaturated, then liquid above gas
    fluids.gas_pressure = {0.0, 0.0};
  }
};

TEST(FixedStress, StorageIsSaturationTimesDensityOverTheDrainedModulus) {
  TwoPoints c;
  const auto elastic = physics::LinearElastic::create(1e7, 0.3);
  const std::vector<SolidModel> models{elastic};
  physics::HydraulicModel hm{};
  hm.solid_density = 1.0;  // the points: solid mass 1 kg in 0.25 m^3; their bound 2.5 m^3
  hm.max_porosity = 0.6;
  const std::vector<physics::HydraulicModel> hydraulics{hm};
  const auto extra = fixed_stress_storage<2>(models, hydraulics, c.points, c.fluids);
  const double k = numerics::drained_bulk_modulus<2>(elastic);
  const double cl = 0.8 * 1000.0 / k, cg = 0.2 * 1.2 / k;
  // Point 0: p* = P_g, so both rows take the gas column.
  EXPECT_DOUBLE_EQ(extra[0].ll, 0.0);
  EXPECT_DOUBLE_EQ(extra[0].lg, cl);
  EXPECT_DOUBLE_EQ(extra[0].gl, 0.0);
  EXPECT_DOUBLE_EQ(extra[0].gg, cg);
  // Point 1: p* = P_l, the liquid column.
  EXPECT_DOUBLE_EQ(extra[1].ll, cl);
  EXPECT_DOUBLE_EQ(extra[1].lg, 0.0);
  EXPECT_DOUBLE_EQ(extra[1].gl, cg);
  EXPECT_DOUBLE_EQ(extra[1].gg, 0.0);
}

TEST(FixedStress, NoStorageAtThePorosityBound) {
  // A point at its largest volume cannot swell: the flow must not give it water for a swelling.
  TwoPoints c;
  const std::vector<SolidModel> models{physics::LinearElastic::create(1e7, 0.3)};
  physics::HydraulicModel hm{};
  hm.solid_density = 1.0;  // the points: solid mass 1 kg in 0.25 m^3; their bound 2.5 m^3
  hm.max_porosity = 0.6;
  const std::vector<physics::HydraulicModel> hydraulics{hm};
  c.points.points.volume[1] = hm.max_volume(c.points.points.mass[1]);
  const auto extra = fixed_stress_storage<2>(models, hydraulics, c.points, c.fluids);
  EXPECT_GT(extra[0].lg, 0.0);
  EXPECT_EQ(extra[1].ll, 0.0);
  EXPECT_EQ(extra[1].lg, 0.0);
  EXPECT_EQ(extra[1].gl, 0.0);
  EXPECT_EQ(extra[1].gg, 0.0);
}

TEST(FixedStress, FluidStateFollowsThePressuresAndNamesANonFinitePoint) {
  TwoPoints c;
  physics::HydraulicModel hm{};
  hm.liquid = physics::CompressibleFluid::create(1000.0, 0.0, 2e9);
  hm.gas = physics::IdealGas::create(1.2);
  hm.retention = physics::LinearRetention::create(1e-6, 0.0);
  const std::vector<physics::HydraulicModel> hydraulics{hm};
  EXPECT_EQ(update_fluid_state<2>(hydraulics, c.points.ranges, c.fluids), -1);
  EXPECT_DOUBLE_EQ(c.fluids.saturation[0], 1.0 - 1e-6 * 2e4);
  EXPECT_DOUBLE_EQ(c.fluids.saturation[1], 1.0);  // P_l > P_g: saturated
  EXPECT_GT(c.fluids.liquid_density[1], c.fluids.liquid_density[0]);
  c.fluids.gas_pressure[1] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(update_fluid_state<2>(hydraulics, c.points.ranges, c.fluids), 1);
}

}  // namespace test_fixed_stress

// The explicit step's pressure update (numerics/three_phase_pressures.hpp) at single points: the
// masses it assigns are the ones the state holds, a large increment included; its shortfall is
// handed on; a gas-free point's gas is supplied and counted; a point with no pores, with masses
// no pressures hold, or with a density no physical pressure gives, is reported.
#include <gtest/gtest.h>

#include <cmath>
#include <utility>

#include "numerics/three_phase_pressures.hpp"
#include "tests/numerics/mobile_gas_soil.hpp"

namespace unsatmpm::numerics {
namespace test_three_phase_pressures {

// One point at porosity n, pressures (p_l, p_g), volume v [m^2], its laws current and the
// scratch g2p_three_phase leaves: the masses at the step's start in the shortfall's columns.
struct OnePoint {
  Grid<2> grid{Vec<2>(0.0, 0.0), Vec<2>(0.25, 0.25), {4, 4}};
  MaterialPoints<2> mp;
  FluidPoints<2> fp;
  physics::HydraulicModel hm;
  OnePoint(double n, double p_l, double p_g, double v,
           physics::HydraulicModel model = mobile_gas_soil(0.1))
      : hm(std::move(model)) {
    mp.push_back(0, Vec<2>(0.5, 0.5), Vec<2>(0.1, 0.1), (1.0 - n) * hm.solid_density * v, v);
    fp.resize(1);
    fp.porosity[0] = n, fp.liquid_pressure[0] = p_l, fp.gas_pressure[0] = p_g;
    refresh_point_laws<2>(hm, 0, hm.state(p_l, p_g), fp);
    fp.liquid_shortfall[0] = n * v * fp.saturation[0] * fp.liquid_density[0];
    fp.gas_shortfall[0] = n * v * (1.0 - fp.saturation[0]) * fp.gas_density[0];
  }
  ThreePhaseReport apply() {
    return apply_pressure_increments<2, Skeleton::deformable>(grid, hm, 1e7, 0, 1, mp, fp, 1);
  }
  std::array<double, 2> state_masses() const {
    const double nv = fp.porosity[0] * mp.volume[0];
    return {nv * fp.saturation[0] * fp.liquid_density[0],
            nv * (1.0 - fp.saturation[0]) * fp.gas_density[0]};
  }
};

// A drying increment of 30 kPa in one step at 2 kPa of suction, where the retention slope changes
// fast: the linear update's own pressure, P_l + dP_l, holds 17 % less water than the balance
// assigned (measured). The state now holds the assigned masses to its storage times the
// inversion's tolerance, the rest is the shortfall, and P_l ends 13.8 kPa above the linear one.
TEST(ThreePhasePressures, TheStateHoldsTheMassesTheBalanceAssigns) {
  OnePoint pt(0.4, -2e3, 0.0, 0.01);
  const physics::StorageMatrix a = pt.fp.storage[0];
  const double dp_l = -3e4;
  pt.fp.liquid_increment[0] = dp_l, pt.fp.gas_increment[0] = 0.0;
  pt.fp.volumetric_strain_increment[0] = 0.0;
  const double m_l = pt.fp.liquid_shortfall[0] + 0.01 * a.ll * dp_l;
  const double m_g = pt.fp.gas_shortfall[0] + 0.01 * a.gl * dp_l;
  const ThreePhaseReport r = pt.apply();
  ASSERT_EQ(r.first_bad, -1);
  const auto held = pt.state_masses();
  EXPECT_NEAR(held[0] + pt.fp.liquid_shortfall[0], m_l, 1e-14 * m_l);
  EXPECT_NEAR(held[1] + pt.fp.gas_shortfall[0], m_g, 1e-14 * m_g);
  const double slack = 2.0 * 0.01 * explicit_pressure_tolerance;
  const physics::StorageMatrix b = pt.fp.storage[0];
  EXPECT_LE(std::abs(pt.fp.liquid_shortfall[0]), slack * (std::abs(b.ll) + std::abs(b.lg)));
  EXPECT_LE(std::abs(pt.fp.gas_shortfall[0]), slack * (std::abs(b.gl) + std::abs(b.gg)));
  // The linear update's pressure holds visibly less water: the inversion moved it.
  const auto linear = physics::fluid_contents(pt.hm, -2e3 + dp_l, 0.0);
  EXPECT_LT(0.4 * 0.01 * linear.first, m_l * (1.0 - 0.1));
  EXPECT_GT(pt.fp.liquid_pressure[0] - (-2e3 + dp_l), 1e4);
  EXPECT_EQ(r.gas_supplied, 0.0);
}

// The porosity follows the volume with the grains' volume kept, 1 - V_s / V: a point whose
// volume grew by 1 % at n = 0.4 reaches 1 - 0.6 / 1.01.
TEST(ThreePhasePressures, PorosityKeepsTheGrainsVolume) {
  OnePoint pt(0.4, -1e4, 0.0, 0.01);
  pt.mp.volume[0] *= 1.01;
  pt.fp.volumetric_strain_increment[0] = 0.01;
  ASSERT_EQ(pt.apply().first_bad, -1);
  EXPECT_NEAR(pt.fp.porosity[0], 1.0 - 0.6 / 1.01, 1e-14);
}

// A point free of gas holds P_g; the gas its state then holds beyond the assigned is supplied and
// reported, and none is carried.
TEST(ThreePhasePressures, AGasFreePointSuppliesItsGas) {
  OnePoint pt(0.4, 5e3, 0.0, 0.01);  // P_l > P_g: saturated, S_l = 1
  ASSERT_LE(1.0 - pt.fp.saturation[0], physics::gas_free_saturation);
  pt.fp.liquid_increment[0] = -8e3, pt.fp.gas_increment[0] = 0.0;  // to 3 kPa of suction
  pt.fp.volumetric_strain_increment[0] = 0.0;
  const double gas_before = pt.fp.gas_shortfall[0];
  const ThreePhaseReport r = pt.apply();
  ASSERT_EQ(r.first_bad, -1);
  EXPECT_EQ(pt.fp.gas_pressure[0], 0.0);
  EXPECT_EQ(pt.fp.gas_shortfall[0], 0.0);
  EXPECT_NEAR(r.gas_supplied, pt.state_masses()[1] - gas_before, 1e-15);
}

// No pores left (the volume below the grains'), and a negative liquid mass, which no pressure
// holds: both are reported, the latter with the inversion's last iterate.
TEST(ThreePhasePressures, PointsWithoutPressuresAreReported) {
  OnePoint squeezed(0.4, -1e4, 0.0, 0.01);
  squeezed.mp.volume[0] *= 0.5;
  EXPECT_EQ(squeezed.apply().first_bad, 0);

  OnePoint emptied(0.4, -1e4, 0.0, 0.01);
  emptied.fp.liquid_shortfall[0] = -1e-3;  // a linear step that took out more than there was
  emptied.fp.liquid_increment[0] = emptied.fp.gas_increment[0] = 0.0;
  EXPECT_EQ(emptied.apply().first_bad, 0);
  EXPECT_LT(emptied.fp.liquid_pressure[0], -1e4);

  // A gas of the exponential law 8 MPa below its reference (K = 10 kPa): its density has
  // underflowed to 0, a state no physical pressure gives.
  physics::HydraulicModel thin = mobile_gas_soil(0.1);
  thin.gas = physics::CompressibleFluid::create(1.0, 0.0, 1e4);
  OnePoint vacuum(0.4, -1e4, -8e6, 0.01, thin);
  ASSERT_EQ(vacuum.fp.gas_density[0], 0.0);
  vacuum.fp.liquid_increment[0] = vacuum.fp.gas_increment[0] = 0.0;
  EXPECT_EQ(vacuum.apply().first_bad, 0);
  OnePoint dense(0.4, -1e4, -8e3, 0.01, thin);  // the same law where it holds gas
  dense.fp.liquid_increment[0] = dense.fp.gas_increment[0] = 0.0;
  EXPECT_EQ(dense.apply().first_bad, -1);
}

}  // namespace test_three_phase_pressures
}  // namespace unsatmpm::numerics

// The explicit three-phase cycle's stable step (numerics/three_phase_g2p.hpp): the damped wave's
// step against its stability condition and its limits, and the fluids' coupled wave against the
// eigenvalues of W = diag(1 / rho) A^-1 diag(contents) computed independently.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>

#include "numerics/three_phase_g2p.hpp"
#include "tests/numerics/mobile_gas_soil.hpp"

namespace unsatmpm::numerics {
namespace test_step_speed {

TEST(StepSpeed, DampedStepMeetsItsStabilityConditionAndItsLimits) {
  const double c2 = 400.0 * 400.0, h = 0.1;
  EXPECT_NEAR(damped_step_speed(c2, 0.0, h), 400.0, 1e-9 * 400.0);  // the wave limit h / c
  double last = 400.0;
  for (const double gamma : {1e2, 1e3, 1e4, 1e5, 1e6}) {
    const double v = damped_step_speed(c2, gamma, h), dt = h / v, w = 2.0 * 400.0 / h;
    // At dt_max the amplification's bound holds with equality: w^2 dt^2 = 4 + 2 gamma dt.
    EXPECT_NEAR(w * w * dt * dt, 4.0 + 2.0 * gamma * dt, 1e-9 * (4.0 + 2.0 * gamma * dt));
    EXPECT_LT(v, last);  // more drag, a longer step
    last = v;
  }
  // Drag-dominated: the diffusion limit dt = h^2 gamma / (2 c^2), within 1 % at gamma = 1e6.
  const double gamma = 1e6;
  EXPECT_NEAR(h / damped_step_speed(c2, gamma, h), h * h * gamma / (2.0 * c2),
              0.01 * h * h * gamma / (2.0 * c2));
}

// At suctions from 5 kPa to 10 Pa (S_l from 0.96 to 0.9999): the step's squared speed is the
// largest of the own waves, n S_a / A_aa, and the damped speed of W's larger eigenvalue (from
// Eigen's solver here) with the weaker drag; near saturation the coupled one is the larger.
TEST(StepSpeed, TheFluidsCoupledWaveIsW_sLargerEigenvalue) {
  const physics::HydraulicModel hm = mobile_gas_soil();
  const double n = 0.4, h = 0.1, p_g = 0.0;
  for (const double s : {5000.0, 1000.0, 100.0, 10.0}) {
    const double p_l = -s, s_l = hm.saturation(s);
    const double rho_l = hm.liquid_density(p_l), rho_g = hm.gas_density(p_g);
    const physics::StorageMatrix a = hm.storage(n, p_l, p_g);
    Eigen::Matrix2d storage;
    storage << a.ll, a.lg, a.gl, a.gg;
    const Eigen::Matrix2d w =
        Eigen::Vector2d(1.0 / rho_l, 1.0 / rho_g).asDiagonal() * storage.inverse() *
        Eigen::Vector2d(n * s_l * rho_l, n * (1.0 - s_l) * rho_g).asDiagonal();
    const double top = w.eigenvalues().real().maxCoeff();
    const double se = hm.effective_saturation(s);
    const double gamma =
        std::min(hm.liquid_drag(n, s_l, se) / rho_l, hm.gas_drag(n, s_l, se) / rho_g);
    const double coupled = std::pow(damped_step_speed(top, gamma, h), 2);
    const double own = std::max(n * s_l / a.ll, n * (1.0 - s_l) / a.gg);
    const double c2 =
        wave_speed_squared<Skeleton::rigid>(hm, 0.0, n, p_l, p_g, s_l, rho_l, rho_g, 1.0, h);
    EXPECT_NEAR(c2, std::max(own, coupled), 1e-9 * c2) << "suction " << s;
    if (s <= 100.0) {
      EXPECT_GT(coupled, own) << "suction " << s;
    }
  }
}

// The laws a point's step reads (refresh_point_laws) are those each law gives on its own, to the
// bit, and the wave speed from them equals the one that evaluates the laws itself: the explicit
// cycle's results must not depend on where the laws were evaluated. Suctions on both sides of
// saturation, a compressed liquid above the gas, and a dry state.
TEST(StepSpeed, ThePointsLawsAreTheLawsOneByOne) {
  const physics::HydraulicModel hm = mobile_gas_soil();
  const double n = 0.37, h = 0.1;
  FluidPoints<2> fp;
  const std::vector<std::pair<double, double>> states = {
      {-8e5, 0.0}, {-2e4, 1e3}, {-50.0, 0.0}, {0.0, 0.0}, {3e3, 1e3}};
  fp.resize(states.size());
  for (std::size_t p = 0; p < states.size(); ++p) {
    fp.porosity[p] = n, fp.liquid_pressure[p] = states[p].first;
    fp.gas_pressure[p] = states[p].second;
    const double p_l = states[p].first, p_g = states[p].second;
    refresh_point_laws<2>(hm, static_cast<std::int64_t>(p), hm.state(p_l, p_g), fp);
    const double s = physics::suction(p_l, p_g), s_l = hm.saturation(s);
    const double se = hm.effective_saturation(s);
    EXPECT_EQ(fp.saturation[p], s_l);
    EXPECT_EQ(fp.liquid_density[p], hm.liquid_density(p_l));
    EXPECT_EQ(fp.gas_density[p], hm.gas_density(p_g));
    EXPECT_EQ(fp.effective_saturation[p], se);
    EXPECT_EQ(fp.liquid_drag[p], hm.liquid_drag(n, s_l, se));
    EXPECT_EQ(fp.gas_drag[p], hm.gas_drag(n, s_l, se));
    const physics::StorageMatrix a = hm.storage(n, p_l, p_g);
    EXPECT_EQ(fp.storage[p].ll, a.ll);
    EXPECT_EQ(fp.storage[p].lg, a.lg);
    EXPECT_EQ(fp.storage[p].gl, a.gl);
    EXPECT_EQ(fp.storage[p].gg, a.gg);
    const double rho_l = fp.liquid_density[p], rho_g = fp.gas_density[p];
    EXPECT_EQ(
        wave_speed_squared<Skeleton::deformable>(fp.storage[p], fp.liquid_drag[p], fp.gas_drag[p],
                                                 1e7, n, s_l, rho_l, rho_g, 1e-3, h),
        wave_speed_squared<Skeleton::deformable>(hm, 1e7, n, p_l, p_g, s_l, rho_l, rho_g, 1e-3, h));
  }
}

}  // namespace test_step_speed
}  // namespace unsatmpm::numerics

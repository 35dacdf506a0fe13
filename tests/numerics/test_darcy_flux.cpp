// The Darcy fluxes the main cycle writes (numerics/pressure/darcy_flux.hpp): on linear nodal
// pressure fields they are Darcy's law exactly at every point, kappa k_r / mu (-grad P + rho g),
// and at hydrostatic rest only the water's compressibility moves it.
#include <gtest/gtest.h>

#include "numerics/pressure/darcy_flux.hpp"
#include "numerics/pressure/pressure_system.hpp"
#include "tests/numerics/linear_soil.hpp"

namespace unsatmpm::numerics {
namespace test_darcy_flux {

struct Block {
  Grid<2> grid{Vec<2>(0.0, 0.0), Vec<2>(0.5, 0.5), {4, 3}};
  MaterialPoints<2> mp;
  FluidPoints<2> fp;
  std::vector<std::int64_t> ranges{0};
  Block() {
    for (int cx = 0; cx < 4; ++cx)
      for (int cy = 0; cy < 3; ++cy)
        for (int k = 0; k < 4; ++k)
          mp.push_back(0,
                       Vec<2>(0.5 * cx + 0.125 + 0.25 * (k % 2), 0.5 * cy + 0.125 + 0.25 * (k / 2)),
                       Vec<2>(0.125, 0.125), 100.0, 0.0625);
    fp.resize(mp.size());
    for (std::size_t p = 0; p < mp.size(); ++p) fp.porosity[p] = 0.4;
    ranges.push_back(static_cast<std::int64_t>(mp.size()));
  }
};

/// Nodal fields P(x, y) = p0 + gx x + gy y per fluid.
std::array<std::vector<double>, 2> linear_field(const Grid<2>& g, std::array<double, 3> l,
                                                std::array<double, 3> gas) {
  std::array<std::vector<double>, 2> p{std::vector<double>(g.n_nodes()),
                                       std::vector<double>(g.n_nodes())};
  for (std::int64_t i = 0; i < g.n_nodes(); ++i) {
    const Vec<2> x = g.node_position(i);
    p[0][i] = l[0] + l[1] * x[0] + l[2] * x[1];
    p[1][i] = gas[0] + gas[1] * x[0] + gas[2] * x[1];
  }
  return p;
}

TEST(DarcyFlux, IsDarcysLawOnLinearFields) {
  const Block b;
  const Vec<2> gravity(0.0, -9.81);
  PressureSystem<2, LinearKernel> sys(b.grid, {linear_soil()}, physics::MassBalance::full, gravity);
  ASSERT_TRUE(sys.prepare(b.mp, b.fp, b.ranges));
  std::array<std::vector<Vec<2>>, 2> q;
  // Saturated, water flowing along x and up: grad P_l = (-2e4, -5e3) Pa/m; gas at 1e5 Pa above.
  darcy_fluxes<2, LinearKernel>(sys.quadrature(), {linear_soil()}, gravity,
                                linear_field(b.grid, {5e4, -2e4, -5e3}, {1e4, 0.0, 0.0}), q);
  ASSERT_EQ(q[0].size(), b.mp.size());
  const double k = 5e-11 / 1e-3;  // kappa k_r / mu, k_r = 1
  for (std::size_t p = 0; p < b.mp.size(); ++p) {
    const double pl = 5e4 - 2e4 * b.mp.position[p][0] - 5e3 * b.mp.position[p][1];
    const double rho = linear_soil().liquid_density(pl);
    EXPECT_NEAR(q[0][p][0], k * 2e4, 1e-12 * k * 2e4);
    EXPECT_NEAR(q[0][p][1], k * (5e3 - rho * 9.81), 1e-9 * k * 1e4);
  }
  // Water hydrostatic at its reference density (dP/dy = -rho0 g): no flux but what its
  // compressibility leaves, k g (rho0 - rho(P)) upward, exactly.
  const double rho0 = linear_soil().liquid_density(0.0);
  darcy_fluxes<2, LinearKernel>(sys.quadrature(), {linear_soil()}, gravity,
                                linear_field(b.grid, {0.0, 0.0, -rho0 * 9.81}, {0.0, 0.0, 0.0}), q);
  for (std::size_t p = 0; p < b.mp.size(); ++p) {
    const double rho = linear_soil().liquid_density(-rho0 * 9.81 * b.mp.position[p][1]);
    EXPECT_NEAR(q[0][p][0], 0.0, 1e-15);
    EXPECT_NEAR(q[0][p][1], k * 9.81 * (rho0 - rho), 1e-9 * k * rho0 * 9.81);
  }
}

}  // namespace test_darcy_flux
}  // namespace unsatmpm::numerics

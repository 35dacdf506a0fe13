// The explicit cycle's conductivities at a node: the mean of the points' conductivities, not of
// their resistances, and at a node that prescribes a fluid's pressure the mean of that and the
// conductivity at the prescribed state (numerics/three_phase_transfers.hpp, nodal_conductivity;
// numerics/face_conductivity.hpp). Without them a face wetting a dry sand let water in only at
// the dry sand's conductivity (docs/balance_laws.md, "Wetting a dry soil through a face").
#include <gtest/gtest.h>

#include <string>

#include "cycles/three_phase_solver.hpp"
#include "input/case_parser.hpp"
#include "tests/cycles/explicit_run.hpp"

namespace unsatmpm {
namespace {

using L = numerics::ThreePhaseLayout<1>;

// A 1 m column of dry sand (50 kPa of suction: k_rl = 1.7e-4) without gravity, 16 cells, its top
// face's suction going from 50 kPa to `face_end` over 1 s, the gas held at 0 there.
Case dry_sand(const std::string& face_end) {
  return parse_case_text(R"(
name: sand
dimension: 1
grid: {origin: [0], size: [1], cells: [16]}
shape_function: gimp
gravity: [0]
phases: solid_liquid_gas
fluids:
  liquid: {density: 1000, bulk_modulus: 1.0e+8, viscosity: 1.0e-3}
  gas: {model: ideal, density: 1.2, viscosity: 1.8e-5}
mass_balance: full
skeleton: rigid
materials:
  - {name: sand, model: linear_elastic, young_modulus: 5.0e+6, poisson_ratio: 0.3,
     solid_density: 2650, porosity: 0.38, intrinsic_permeability: 1.0e-11,
     retention: {model: van_genuchten, p0: 1.0e+4, lambda: 0.5, residual_saturation: 0.0},
     liquid_relative_permeability: {model: mualem_van_genuchten, lambda: 0.5},
     gas_relative_permeability: {model: constant}}
bodies:
  - {name: column, material: sand, points_per_cell: 2, box: {min: [0], max: [1]},
     initial_state: {suction: 5.0e+4, gas_pressure: 0}}
boundaries:
  - {name: bottom, plane: {axis: x, at: 0}, mechanical: fixed}
  - {name: top, plane: {axis: x, at: 1},
     liquid: {suction: {ramp: {from: 5.0e+4, to: )" +
                             face_end + R"(, start: 0, end: 1}}}, gas: {pressure: 0}}
solver: {end_time: 1, damping: 0, cycle: explicit}
output: {times: [1]}
)",
                         "<test>");
}

using Solver = ThreePhaseSolver<1, numerics::GimpKernel>;

Solver make_solver(const Case& c) { return explicit_run::make_solver<1, numerics::GimpKernel>(c); }
using explicit_run::run;

// A record of two points' sums at a node: equal volumes, one wet (conductivity k_wet), one dry.
TEST(NodalConductivity, IsTheMeanOfThePointsConductivitiesNotOfTheirResistances) {
  std::array<double, L::record> r{};
  const double k_wet = 1e-5, k_dry = 1e-9, theta = 150.0;
  r[L::volume] = 2.0;
  r[L::liquid_conductivity] = k_wet + k_dry;
  r[L::liquid_theta] = 2.0 * theta;
  const double k = numerics::nodal_conductivity<1>(r.data(), L::liquid_conductivity,
                                                   L::liquid_face_conductivity, false);
  EXPECT_DOUBLE_EQ(k, 0.5 * (k_wet + k_dry));
  // The drag gives the flux theta w = -k grad P, with w = F / Q and F = -grad P sum N V.
  const double q = numerics::nodal_drag(r[L::liquid_theta], k);
  EXPECT_DOUBLE_EQ(theta * r[L::volume] / q, k);
  // At a prescribed node the face's conductivity takes half the weight.
  r[L::liquid_face_conductivity] = 2.0 * k_wet;
  EXPECT_DOUBLE_EQ(numerics::nodal_conductivity<1>(r.data(), L::liquid_conductivity,
                                                   L::liquid_face_conductivity, true),
                   0.5 * (k + k_wet));
  // No fluid at the points: no drag, whatever the face's conductivity.
  r[L::gas_theta] = 0.0;
  r[L::gas_face_conductivity] = 2.0 * k_wet;
  EXPECT_EQ(numerics::nodal_drag(r[L::gas_theta],
                                 numerics::nodal_conductivity<1>(r.data(), L::gas_conductivity,
                                                                 L::gas_face_conductivity, true)),
            0.0);
}

// Points that agree give the paper's drag, sum N V n S mu / (kappa k_r), and a face prescribing
// the points' own state gathers the points' own conductivity.
TEST(NodalConductivity, AFaceAtThePointsStateGathersThePointsConductivity) {
  Case c = dry_sand("5.0e+4");  // the face stays at the column's suction
  Solver s = make_solver(c);
  run(s, 1e-4);
  const auto& nodes = s.nodes();
  const auto& fp = s.fluids();
  const std::int64_t top = nodes.n_nodes() - 1;
  ASSERT_TRUE(nodes.liquid_prescribed[top] && nodes.gas_prescribed[top]);
  const double* r = nodes.record(top);
  EXPECT_NEAR(r[L::liquid_face_conductivity], r[L::liquid_conductivity],
              1e-9 * r[L::liquid_conductivity]);
  EXPECT_NEAR(r[L::gas_face_conductivity], r[L::gas_conductivity], 1e-9 * r[L::gas_conductivity]);
  const double drag = numerics::nodal_drag(r[L::liquid_theta], nodes.liquid_conductivity[top]);
  EXPECT_NEAR(drag, fp.liquid_drag.back() * r[L::volume], 1e-6 * drag);
}

// The face wets the sand: by 1 s (the face at zero suction) it takes in far more than the dry
// sand's conductivity could carry over half a cell, K_dry 50 kPa / (h / 2) 1 s, which bounds what
// the paper's lumped drag let in (0.0014 kg/m^2, half the bound); every point's water stays
// within its pores.
TEST(FaceWetting, AWettedFaceTakesWaterIntoADrySand) {
  Case c = dry_sand("0");
  Solver s = make_solver(c);
  const double m0 = s.balance().liquid_mass;
  run(s, 1.0);
  const auto b = s.balance();
  const double k_rl_dry = 1.7e-4, k_dry = 1000.0 * 1e-11 * k_rl_dry / 1e-3, h = 1.0 / 16;
  const double dry_bound = k_dry * 50e3 / (h / 2) * 1.0;  // [kg/m^2]
  EXPECT_GT(b.liquid_inflow, 20.0 * dry_bound) << "bound " << dry_bound;
  EXPECT_NEAR(b.liquid_mass - m0, b.liquid_inflow, 1e-6 * b.liquid_inflow);
  const auto& fp = s.fluids();
  for (std::size_t p = 0; p < fp.size(); ++p) EXPECT_LE(fp.saturation[p], 1.0) << "point " << p;
  // The point nearest the face wets first; the base stays dry.
  const auto& x = s.points().position;
  std::size_t top = 0, bottom = 0;
  for (std::size_t p = 0; p < x.size(); ++p) {
    if (x[p][0] > x[top][0]) top = p;
    if (x[p][0] < x[bottom][0]) bottom = p;
  }
  EXPECT_GT(fp.saturation[top], fp.saturation[bottom] + 0.01);
  EXPECT_NEAR(fp.saturation[bottom], 0.196, 0.001);  // S_e at 50 kPa, 26^(-1/2)
}

}  // namespace
}  // namespace unsatmpm

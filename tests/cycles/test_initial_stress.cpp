// K0 initial stresses (cycles/initial_stress.hpp): the vertical stress of a point is the weight
// above it, the horizontal ones K0 times the net vertical stress, in a one-phase and a
// three-phase body, from the top of the points' domains; the case reader's checks on
// initial_stress.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "cycles/initial_stress.hpp"
#include "cycles/setup.hpp"
#include "input/case_parser.hpp"
#include "tests/input/case_parser_test_support.hpp"

namespace unsatmpm {
namespace test_initial_stress {

using test_support::edit;
using test_support::parse;

const std::string dry = R"(name: layer
dimension: 2
grid: {origin: [0, 0], size: [1, 3], cells: [2, 6]}
shape_function: linear
gravity: [0, -10]
materials:
  - {name: soil, density: 1800, model: linear_elastic, young_modulus: 1.0e7, poisson_ratio: 0.3}
bodies:
  - {name: layer, material: soil, points_per_cell: 2, box: {min: [0, 0], max: [1, 2.5]},
     initial_stress: {k0: 0.6}}
boundaries:
  - {name: base, plane: {axis: y, at: 0}, mechanical: fixed}
solver: {end_time: 1, damping: 0}
output: {}
)";

TEST(InitialStress, DryLayerCarriesTheWeightAboveEachPoint) {
  test_support::expect_round_trip(dry);  // the effective configuration keeps initial_stress
  const Case c = parse(dry);
  const auto grid = make_grid<2>(c);
  const PointSet<2> set = fill_bodies<2>(c, grid);
  for (std::size_t p = 0; p < set.points.size(); ++p) {
    const double depth = 2.5 - set.points.position[p][1];
    const auto& s = set.points.stress[p];
    EXPECT_NEAR(s[1], -1800.0 * 10.0 * depth, 1e-9 * 1800.0 * 10.0 * 2.5) << p;
    EXPECT_NEAR(s[0], 0.6 * s[1], 1e-12 * std::abs(s[1])) << p;
    EXPECT_EQ(s[2], s[0]);
    EXPECT_EQ(s[3], 0.0);
  }
}

// A box whose top lies between two rows of points (2.45 m, rows of 0.25 m) holds the same points
// as one to 2.5 m, whose domains reach 2.5 m: the weight above each point is that of the soil
// they carry, from 2.5 m, not from the box's face (which left 0.05 m of soil out).
TEST(InitialStress, TheWeightIsThatOfThePointsDomainsNotOfTheBoxFace) {
  const Case c = parse(edit(dry, "max: [1, 2.5]", "max: [1, 2.45]"));
  const auto grid = make_grid<2>(c);
  const PointSet<2> set = fill_bodies<2>(c, grid);
  const PointSet<2> full = fill_bodies<2>(parse(dry), grid);
  ASSERT_EQ(set.points.size(), full.points.size());
  for (std::size_t p = 0; p < set.points.size(); ++p) {
    EXPECT_EQ(set.points.position[p], full.points.position[p]) << p;
    const double depth = 2.5 - set.points.position[p][1];
    EXPECT_NEAR(set.points.stress[p][1], -1800.0 * 10.0 * depth, 1e-9 * 1800.0 * 10.0 * 2.5) << p;
  }
}

TEST(InitialStress, GravityAlongPlusXPutsTheTopAtTheLowEnd) {
  const Case c =
      parse(edit(edit(dry, "gravity: [0, -10]", "gravity: [10, 0]"), "{k0: 0.6}", "{k0: 1.5}"));
  const auto grid = make_grid<2>(c);
  const PointSet<2> set = fill_bodies<2>(c, grid);
  for (std::size_t p = 0; p < set.points.size(); ++p) {
    const double depth = set.points.position[p][0];  // the top is x = 0
    EXPECT_NEAR(set.points.stress[p][0], -18000.0 * depth, 1e-9 * 18000.0) << p;
    EXPECT_NEAR(set.points.stress[p][1], 1.5 * set.points.stress[p][0], 1e-9 * 18000.0) << p;
  }
}

// A saturated layer (water table at its top): the total vertical stress at a depth is the
// weight of the mixture above, (1 - n) rho_s + n rho_l (the liquid's compressibility adds a part
// in 1e5 here), and the net stress adds back the pore pressure rho_l g depth.
TEST(InitialStress, SaturatedLayerCarriesTheMixtureAndSubtractsThePorePressure) {
  const std::string wet = edit(
      edit(dry, "  - {name: soil, density: 1800,",
           "  - {name: soil, solid_density: 2700, porosity: 0.4, intrinsic_permeability: 1.0e-12,"
           "\n     retention: {model: linear, a_s: 1.0e-6},"
           "\n     liquid_relative_permeability: {model: constant},"
           "\n     gas_relative_permeability: {model: constant},"),
      "     initial_stress: {k0: 0.6}}",
      "     initial_stress: {k0: 0.6},\n     initial_state: {water_table: {elevation: 2.5, "
      "max_suction: 0}, gas_pressure: 0}}");
  const Case c = parse(edit(wet, "materials:",
                            "phases: solid_liquid_gas\nfluids:\n  liquid: {density: 1000, "
                            "bulk_modulus: 2.0e9, viscosity: 1.0e-3}\n  gas: {model: ideal, "
                            "density: 1.2, viscosity: 1.8e-5}\nmass_balance: full\nmaterials:"));
  const auto grid = make_grid<2>(c);
  const PointSet<2> set = fill_bodies<2>(c, grid);
  const double rho_mix = 0.6 * 2700.0 + 0.4 * 1000.0;
  for (std::size_t p = 0; p < set.points.size(); ++p) {
    const double depth = 2.5 - set.points.position[p][1];
    const double total = -rho_mix * 10.0 * depth, pore = 1000.0 * 10.0 * depth;
    const auto& s = set.points.stress[p];
    EXPECT_NEAR(s[1], total + pore, 1e-4 * rho_mix * 10.0 * 2.5) << p;
    EXPECT_NEAR(s[0], 0.6 * s[1], 1e-12 * std::abs(s[1])) << p;
  }
}

TEST(InitialStressErrors, OnlyBoxesUnderAxisGravityWithoutGravityLoading) {
  using test_support::expect_error;
  const std::string key = "bodies[0].initial_stress";
  expect_error(edit(dry, "box: {min: [0, 0], max: [1, 2.5]}",
                    "polygon: {vertices: [[0, 0], [1, 0], [1, 2.5], [0, 2]]}"),
               "initial_stress", key, "need a horizontal top surface");
  expect_error(edit(dry, "gravity: [0, -10]", "gravity: [3, -10]"), "initial_stress", key,
               "need gravity along one grid axis");
  expect_error(edit(dry, "{k0: 0.6}", "{k0: 0}"), "initial_stress", key + ".k0",
               "out of range (0, 10]");
  expect_error(edit(dry, "{k0: 0.6}", "{}"), "initial_stress", key, "missing required key 'k0'");
  expect_error(edit(dry, "damping: 0}",
                    "damping: 0, gravity_loading: {damping: 0.5, tolerance: 1.0e-3, "
                    "max_time: 5}}"),
               "solver:", "solver", "give one");
}

}  // namespace test_initial_stress
}  // namespace unsatmpm

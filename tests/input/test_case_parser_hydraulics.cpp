// The case parser, three-phase part: fluids, hydraulic materials, initial pressures, liquid and
// gas boundary conditions as time functions; their effective-configuration round trip; and one
// test per error class checking file, line and key path of the message.
#include <gtest/gtest.h>

#include <limits>
#include <numbers>
#include <string>
#include <utility>
#include <variant>

#include "case_parser_test_support.hpp"  // same folder
#include "input/case_parser.hpp"
#include "three_phase_cases.hpp"

namespace unsatmpm {
namespace test_case_parser_hydraulics {

using namespace test_support;

TEST(CaseParserHydraulics, ParsesThreePhaseColumn) {
  const Case c = parse(column_1d);
  EXPECT_EQ(c.phases, Phases::solid_liquid_gas);
  EXPECT_EQ(c.mass_balance, physics::MassBalance::full);
  EXPECT_EQ(c.pressure_update, PressureUpdate::nodal);  // default
  EXPECT_EQ(c.skeleton, physics::Skeleton::rigid);
  const FluidsSpec& f = c.fluids.value();
  EXPECT_EQ(f.liquid.reference_density, 1000.0);
  EXPECT_EQ(f.liquid.bulk_modulus, 8.0e7);
  EXPECT_EQ(f.liquid.reference_pressure, 0.0);  // default
  EXPECT_EQ(f.liquid_viscosity, 1.0e-3);
  EXPECT_EQ(std::get<physics::IdealGas>(f.gas).reference_density, 1.2);
  EXPECT_EQ(f.gas_viscosity, 1.8e-5);
  const MaterialSpec& m = c.materials.at(0);
  const HydraulicSpec& h = m.hydraulic.value();
  EXPECT_EQ(h.solid_density, 2700.0);
  EXPECT_EQ(h.porosity, 0.3);
  EXPECT_EQ(h.intrinsic_permeability, 5.0e-11);
  EXPECT_DOUBLE_EQ(m.density, 0.7 * 2700.0);  // (1 - n) rho_s: solid mass per mixture volume
  const auto& retention = std::get<physics::LinearRetention>(h.retention);
  EXPECT_EQ(retention.a_s, 1.0e-6);
  EXPECT_EQ(retention.s_min, 0.0);  // default
  EXPECT_TRUE(std::holds_alternative<physics::ConstantRelPerm>(h.liquid_relative_permeability));
  EXPECT_TRUE(std::holds_alternative<physics::ConstantRelPerm>(h.gas_relative_permeability));
  const InitialPressures& p = c.bodies.at(0).initial_pressures.value();
  EXPECT_EQ(p.gas_pressure, 0.0);
  EXPECT_EQ(p.liquid_pressure, -5.0e5);  // gas pressure - suction
  const BoundarySpec& top = c.boundaries.at(0);
  EXPECT_FALSE(top.mechanical.has_value());
  EXPECT_EQ(top.liquid.value().kind, LiquidCondition::Kind::suction);
  EXPECT_EQ(top.liquid->value(0.0), 0.0);
  EXPECT_EQ(top.gas_pressure.value()(3.0), 0.0);
  EXPECT_FALSE(c.boundaries.at(1).liquid.has_value());  // impervious by default
  EXPECT_TRUE(c.boundaries.at(1).gas_pressure.has_value());
}

TEST(CaseParserHydraulics, ParsesOtherLawsAndTimeFunctions) {
  const Case c = parse(slope_2d);
  EXPECT_EQ(c.mass_balance, physics::MassBalance::simplified);
  EXPECT_EQ(c.pressure_update, PressureUpdate::pointwise);
  EXPECT_EQ(c.skeleton, physics::Skeleton::deformable);  // default: deformable
  EXPECT_EQ(c.fluids->liquid.reference_pressure, 100.0);
  const auto& gas = std::get<physics::CompressibleFluid>(c.fluids->gas);
  EXPECT_EQ(gas.bulk_modulus, 1.0e4);
  EXPECT_EQ(gas.reference_pressure, 0.0);  // default
  const HydraulicSpec& clay = c.materials.at(0).hydraulic.value();
  const auto& vg = std::get<physics::VanGenuchten>(clay.retention);
  EXPECT_EQ(vg.p0, 2.0e4);
  EXPECT_EQ(vg.lambda, 0.4);
  EXPECT_EQ(vg.s_min, 0.1);
  EXPECT_EQ(vg.s_max, 1.0);  // default
  EXPECT_EQ(std::get<physics::MualemVanGenuchten>(clay.liquid_relative_permeability).lambda, 0.4);
  EXPECT_EQ(std::get<physics::GasPowerRelPerm>(clay.gas_relative_permeability).exponent, 3.0);
  EXPECT_EQ(clay.maximum_porosity, 0.6);
  EXPECT_FALSE(c.materials.at(1).hydraulic->maximum_porosity);  // absent: no bound
  EXPECT_DOUBLE_EQ(c.materials.at(1).density, 0.6 * 2650.0);
  EXPECT_EQ(std::get<physics::PowerRelPerm>(c.materials[1].hydraulic->liquid_relative_permeability)
                .exponent,
            3.0);
  EXPECT_EQ(c.bodies.at(0).initial_pressures->liquid_pressure, -8.0e5);
  EXPECT_EQ(c.bodies.at(1).initial_pressures->liquid_pressure, 100.0 - 2.0e4);
  EXPECT_EQ(c.boundaries.at(0).mechanical, MechanicalCondition::fixed);
  EXPECT_FALSE(c.boundaries[0].liquid || c.boundaries[0].gas_pressure);
  const TimeFunction& ramp = c.boundaries.at(1).liquid.value().value;
  EXPECT_EQ(ramp(0.0), 8.0e5);
  EXPECT_DOUBLE_EQ(ramp(2.5), 6.0e5);
  EXPECT_EQ(ramp(10.0), 0.0);
  EXPECT_EQ(ramp(15.0), 0.0);  // held
  EXPECT_FALSE(c.boundaries[1].mechanical.has_value());
  const LiquidCondition& table = c.boundaries.at(2).liquid.value();
  EXPECT_EQ(table.kind, LiquidCondition::Kind::pressure);
  EXPECT_EQ(table.value.points.size(), 3u);
  EXPECT_DOUBLE_EQ(table.value(2.5), 5.0e3);
  EXPECT_DOUBLE_EQ(table.value(12.5), 1.75e4);
  EXPECT_EQ(table.value(30.0), 2.5e4);  // held after the last point
  EXPECT_EQ(c.boundaries[2].mechanical, MechanicalCondition::roller);
}

TEST(CaseParserHydraulics, EffectiveConfigurationRoundTripsExactly) {
  const std::string one_point_table =
      edit(slope_2d, "[[0, 0], [5, 1.0e4], [20, 2.5e4]]", "[[3, 7]]");
  for (const std::string& text : {column_1d, slope_2d, one_point_table}) expect_round_trip(text);
  const std::string yaml = effective_configuration(parse(column_1d));
  for (const char* expected :
       {"phases: solid_liquid_gas\n", "mass_balance: full\n", "pressure_update: nodal\n",
        "skeleton: rigid\n", "reference_pressure: 0", "residual_saturation: 0",
        "initial_state: {liquid_pressure: "
        "-5.0e+05, gas_pressure: 0}",
        "liquid: {suction: 0}"})
    EXPECT_NE(yaml.find(expected), std::string::npos) << expected << "\n" << yaml;
  EXPECT_EQ(yaml.find("density: 1890"), std::string::npos) << yaml;  // derived, not written
  const std::string slope = effective_configuration(parse(slope_2d));
  EXPECT_NE(slope.find("skeleton: deformable\n"), std::string::npos) << slope;
  EXPECT_NE(slope.find("{ramp: {from: 8.0e+05, to: 0, start: 0, end: 10}}"), std::string::npos)
      << slope;
  EXPECT_NE(slope.find("{table: [[0, 0], [5, 10000], [20, 25000]]}"), std::string::npos) << slope;
}

// The paper's embankment strength (eqs. 13-14) on slope_2d's clay.
const std::string suction_clay =
    edit(slope_2d, "    friction_angle: 20\n",
         "    friction_angle: 20\n"
         "    suction_strength: {cohesion_increase: 1.5e4, cohesion_rate: 0.7, "
         "friction_increase: 0.1}\n");

TEST(CaseParserHydraulics, ParsesAnOccludedGasThatGivesWay) {
  // occluded_gas_scale on van Genuchten and on a table, each leaving gas in the pores at s = 0;
  // absent, 0 (the paper's flat law), written back by the effective configuration.
  const std::string vg_case = edit(slope_2d, "residual_saturation: 0.1}",
                                   "residual_saturation: 0.1, max_saturation: 0.95, "
                                   "occluded_gas_scale: 1000}");
  const Case with_vg = parse(vg_case);
  EXPECT_EQ(
      std::get<physics::VanGenuchten>(with_vg.materials.at(0).hydraulic->retention).occluded.scale,
      1000.0);
  EXPECT_EQ(std::get<physics::VanGenuchten>(parse(slope_2d).materials.at(0).hydraulic->retention)
                .occluded.scale,
            0.0);
  const std::string table_case =
      edit(column_1d, "{model: linear, a_s: 1.0e-6}",
           "{model: table, points: [[0, 0.9], [1.0e5, 0.5]], occluded_gas_scale: 200}");
  const Case with_table = parse(table_case);
  const auto& table =
      std::get<physics::TabulatedRetention>(with_table.materials.at(0).hydraulic->retention);
  EXPECT_EQ(table.occluded.scale, 200.0);
  EXPECT_EQ(table.saturation(0.0), 0.9);
  for (const std::string& text : {vg_case, table_case}) expect_round_trip(text);
  EXPECT_NE(effective_configuration(parse(vg_case)).find("occluded_gas_scale: 1000"),
            std::string::npos);
}

TEST(CaseParserHydraulics, ParsesSuctionDependentStrength) {
  const Case c = parse(suction_clay);
  const auto& model = std::get<physics::SuctionMohrCoulomb>(c.materials.at(0).model);
  const double deg = std::numbers::pi / 180.0;
  EXPECT_EQ(model.strength.cohesion, 1000.0);
  EXPECT_EQ(model.strength.cohesion_increase, 1.5e4);
  EXPECT_EQ(model.strength.cohesion_rate, 0.7);
  EXPECT_DOUBLE_EQ(model.strength.friction_angle, 20 * deg);
  EXPECT_DOUBLE_EQ(model.strength.friction_increase, 0.1 * deg);  // per atmosphere
  EXPECT_EQ(model.strength.dilatancy_angle, 0.0);
  EXPECT_EQ(model.strength.tensile_strength, std::numeric_limits<double>::infinity());
  EXPECT_EQ(model.elastic().young_modulus, 1.0e7);
  EXPECT_EQ(model.saturated.strength.cohesion, 1000.0);
  // Without suction_strength the same material is the plain Mohr-Coulomb model.
  EXPECT_TRUE(std::holds_alternative<physics::MohrCoulomb>(parse(slope_2d).materials[0].model));
  expect_round_trip(suction_clay);
  expect_round_trip(edit(suction_clay, "friction_angle: 20\n",
                         "friction_angle: 20\n    tensile_strength: 500\n"));
  const std::string yaml = effective_configuration(c);
  EXPECT_NE(yaml.find("suction_strength: {cohesion_increase: 15000, cohesion_rate: 0.7, "
                      "friction_increase: 0.1}"),
            std::string::npos)
      << yaml;
  EXPECT_EQ(yaml.find("tensile_strength: inf"), std::string::npos) << yaml;
}

TEST(CaseParserHydraulicsErrors, SuctionStrength) {
  expect_error(edit(suction_clay, "cohesion_rate: 0.7", "cohesion_rate: -0.7"),
               "cohesion_rate: -0.7", "materials[0].suction_strength.cohesion_rate",
               "out of range");
  expect_error(edit(suction_clay, "friction_increase: 0.1", "friction_increase: -1"),
               "friction_increase: -1", "materials[0].suction_strength.friction_increase",
               "-1 deg is out of range");
  expect_error(edit(suction_clay, "friction_increase: 0.1}", "friction_increase: 0.1, b: 1}"),
               "friction_increase: 0.1, b: 1}", "materials[0].suction_strength.b", "unknown key");
  expect_error(edit(suction_clay, "cohesion_increase: 1.5e4, ", ""), "suction_strength: {",
               "materials[0].suction_strength", "cohesion_increase");
  expect_error(edit(suction_clay, "friction_angle: 20\n",
                    "friction_angle: 20\n"
                    "    dilatancy_angle: 25\n"),
               "dilatancy_angle: 25", "materials[0].dilatancy_angle", "out of range");
  // Only a three-phase Mohr-Coulomb material has a suction.
  expect_error(edit(suction_clay, "gas_relative_permeability: {model: constant}}",
                    "gas_relative_permeability: {model: constant},\n"
                    "     suction_strength: {cohesion_rate: 1}}"),
               "suction_strength: {cohesion_rate: 1}", "materials[1].suction_strength",
               "unknown key");
  expect_error(edit(solid_1d, "poisson_ratio: 0}",
                    "poisson_ratio: 0, suction_strength: {cohesion_rate: 1}}"),
               "suction_strength", "materials[0].suction_strength", "three-phase");
}

TEST(CaseParserHydraulicsErrors, HydraulicKeysInSolidCaseAreUnknown) {
  const std::string hint = "(a key of three-phase cases: set phases: solid_liquid_gas)";
  expect_error(edit(solid_1d, "materials:", "mass_balance: full\nmaterials:"), "mass_balance",
               "mass_balance",
               "unknown key 'mass_balance' at top level; known keys: " +
                   std::string("name, dimension, grid, shape_function, gravity, "
                               "phases, materials"));
  EXPECT_NE(error_of(edit(solid_1d, "gravity: [0]", "gravity: [0]\nskeleton: rigid")).find(hint),
            std::string::npos);
  expect_error(edit(solid_1d, "poisson_ratio: 0}", "poisson_ratio: 0, porosity: 0.3}"), "porosity",
               "materials[0].porosity", "unknown key 'porosity' in materials[0]");
  expect_error(edit(solid_1d, "max: [1]}}", "max: [1]}, initial_state: {suction: 0}}"),
               "initial_state", "bodies[0].initial_state", hint);
  expect_error(edit(solid_1d, "mechanical: fixed}", "mechanical: fixed, gas: {pressure: 0}}"),
               "gas:", "boundaries[0].gas",
               "unknown key 'gas' in boundaries[0]; known keys: "
               "name, plane, mechanical, traction " +
                   hint);
  // Forgetting `phases` in a three-phase case: the first three-phase key met says what to do.
  expect_error(edit(column_1d, "phases: solid_liquid_gas\n", ""), "solid_density",
               "materials[0].solid_density", hint);
}

TEST(CaseParserHydraulicsErrors, ThreePhaseCaseNeedsFluidsAndMassBalance) {
  const std::string no_fluids = edit(column_1d, R"(fluids:
  liquid: {density: 1000, bulk_modulus: 8.0e7, viscosity: 1.0e-3}
  gas: {model: ideal, density: 1.2, viscosity: 1.8e-5}
)",
                                     "");
  // The top level has no key path: reported at line 1, naming the key.
  for (const auto& [text, key] :
       {std::pair{no_fluids, "fluids"},
        std::pair{edit(column_1d, "mass_balance: full\n", ""), "mass_balance"}}) {
    const std::string message = error_of(text);
    const std::string expected =
        std::string("case.yaml:1:1: missing required key '") + key + "' at top level";
    EXPECT_EQ(message.rfind(expected, 0), 0u) << message;
  }
  expect_error(
      edit(column_1d, "mass_balance: full\n", "mass_balance: full\npressure_update: yes\n"),
      "pressure_update", "pressure_update", "expected one of pointwise, nodal, got 'yes'");
  expect_error(edit(column_1d, "viscosity: 1.8e-5}", "density: 2}"), "gas: {", "fluids.gas.density",
               "duplicate key 'density'");
  expect_error(edit(column_1d, ", viscosity: 1.8e-5}", "}"), "gas: {", "fluids.gas",
               "missing required key 'viscosity' in fluids.gas");
  expect_error(edit(column_1d, "model: ideal", "model: van_der_waals"), "van_der_waals",
               "fluids.gas.model", "expected one of bulk_modulus, ideal");
  expect_error(edit(column_1d, "bulk_modulus: 8.0e7", "bulk_modulus: -1"), "bulk_modulus: -1",
               "fluids.liquid.bulk_modulus", "bulk_modulus = -1 Pa is out of range");
}

TEST(CaseParserHydraulicsErrors, DensityInThreePhaseMaterial) {
  expect_error(edit(column_1d, "    solid_density: 2700", "    density: 1890"), "density: 1890",
               "materials[0].density",
               "unknown key 'density' in materials[0]; known keys: name, model, young_modulus, "
               "poisson_ratio, solid_density, porosity, intrinsic_permeability, retention, "
               "liquid_relative_permeability, gas_relative_permeability, maximum_porosity (a "
               "three-phase material gives solid_density and porosity instead)");
}

TEST(CaseParserHydraulicsErrors, PorosityOutOfRange) {
  expect_error(edit(slope_2d, "maximum_porosity: 0.6", "maximum_porosity: 0.3"),
               "maximum_porosity: 0.3", "materials[0].maximum_porosity", "out of range (0.35, 1)");
  expect_error(edit(solid_1d, "poisson_ratio: 0}", "poisson_ratio: 0, maximum_porosity: 0.5}"),
               "maximum_porosity", "materials[0].maximum_porosity", "three-phase");
  expect_error(edit(column_1d, "porosity: 0.3", "porosity: 1.2"), "porosity: 1.2",
               "materials[0].porosity", "1.2 is out of range (0, 1)");
  expect_error(edit(column_1d, "porosity: 0.3", "porosity: 0"), "porosity: 0",
               "materials[0].porosity", "0 is out of range (0, 1)");
  expect_error(edit(column_1d, "permeability: 5.0e-11", "permeability: 0"), "permeability: 0",
               "materials[0].intrinsic_permeability", "out of range (0, inf)");
}

TEST(CaseParserHydraulicsErrors, RetentionAndPermeabilityModels) {
  expect_error(edit(column_1d, "model: linear,", "model: brooks_corey,"), "brooks_corey",
               "materials[0].retention.model",
               "expected one of linear, van_genuchten, table, got 'brooks_corey'");
  expect_error(edit(column_1d, "{model: linear, a_s: 1.0e-6}", "{a_s: 1.0e-6}"), "retention",
               "materials[0].retention",
               "missing required key 'model' in materials[0].retention; "
               "models: linear, van_genuchten");
  expect_error(edit(column_1d, "a_s: 1.0e-6}", "a_s: 1.0e-6, p0: 1}"), "p0",
               "materials[0].retention.p0", "unknown key 'p0'");
  // Physics ranges come from the factories, reported at the parameter's key.
  expect_error(edit(slope_2d, "p0: 2.0e4, lambda: 0.4", "p0: 2.0e4, lambda: 1.5"), "lambda: 1.5",
               "materials[0].retention.lambda",
               "lambda = 1.5 is out of range; valid: (0, 1)");  // no unit: dimensionless
  expect_error(edit(slope_2d, "residual_saturation: 0.1}",
                    "residual_saturation: 0.1, "
                    "max_saturation: 1.5}"),
               "max_saturation", "materials[0].retention.max_saturation", "max_saturation = 1.5");
  // An occluded gas's scale: its range, and a law that leaves no gas to occlude (S_max = 1).
  expect_error(edit(slope_2d, "residual_saturation: 0.1}",
                    "residual_saturation: 0.1, max_saturation: 0.9, occluded_gas_scale: -5}"),
               "occluded_gas_scale: -5", "materials[0].retention.occluded_gas_scale",
               "occluded_gas_scale = -5 Pa is out of range; valid: [0, 1e+07] Pa");
  expect_error(edit(slope_2d, "residual_saturation: 0.1}",
                    "residual_saturation: 0.1, occluded_gas_scale: 1000}"),
               "occluded_gas_scale: 1000", "materials[0].retention.occluded_gas_scale",
               "max_saturation = 1 leaves none in the pores");
  expect_error(edit(column_1d, "{model: linear, a_s: 1.0e-6}",
                    "{model: table, points: [[0, 1], [1.0e5, 0.5]], occluded_gas_scale: 200}"),
               "occluded_gas_scale: 200", "materials[0].retention.occluded_gas_scale",
               "the saturation at suction 0 = 1 leaves none");
  expect_error(edit(column_1d, "a_s: 1.0e-6}", "a_s: 1.0e-6, occluded_gas_scale: 100}"),
               "occluded_gas_scale", "materials[0].retention.occluded_gas_scale", "unknown key");
  expect_error(edit(slope_2d, "model: power, exponent: 3}", "model: power, exponent: 0.5}"),
               "exponent: 0.5", "materials[0].gas_relative_permeability.exponent",
               "exponent = 0.5");
  expect_error(edit(column_1d, "gas_relative_permeability: {model: constant}",
                    "gas_relative_permeability: {model: mualem_van_genuchten}"),
               "mualem_van_genuchten", "materials[0].gas_relative_permeability.model",
               "expected one of constant, power");
}

TEST(CaseParserHydraulicsErrors, TimeFunctions) {
  expect_error(edit(slope_2d, "[5, 1.0e4], [20", "[5, 1.0e4], [5"), "[5, 1.0e4], [5",
               "boundaries[2].liquid.pressure.table[2][0]",
               "table times must be strictly ascending: 5 follows 5");
  expect_error(edit(slope_2d, "start: 0, end: 10", "start: 10, end: 10"), "end: 10",
               "boundaries[1].liquid.suction.ramp.end", "a ramp must end after it starts");
  expect_error(edit(slope_2d, "start: 0, end: 10", "start: -1, end: 10"), "start: -1",
               "boundaries[1].liquid.suction.ramp.start", "out of range [0, inf)");
  expect_error(edit(slope_2d, "{table: [[0, 0], [5, 1.0e4], [20, 2.5e4]]}", "{table: []}"),
               "table: []", "boundaries[2].liquid.pressure.table", "at least one");
  expect_error(edit(slope_2d, "[5, 1.0e4]", "[5, 1.0e4, 3]"), "[5, 1.0e4, 3]",
               "boundaries[2].liquid.pressure.table[1]", "expected a [time, value] pair");
  expect_error(edit(slope_2d, "from: 8.0e5", "from: -8.0e5"), "from: -8.0e5",
               "boundaries[1].liquid.suction.ramp.from", "out of range [0, inf)");
  expect_error(edit(column_1d, "liquid: {suction: 0}", "liquid: {suction: [0]}"), "suction: [0]",
               "boundaries[0].liquid.suction",
               "expected a number, {ramp: {...}} or {table: [...]}");
}

TEST(CaseParserHydraulicsErrors, SuctionWithoutGas) {
  expect_error(edit(column_1d, "    gas: {pressure: 0}\n  - name: bottom", "  - name: bottom"),
               "liquid: {suction", "boundaries[0].liquid",
               "a suction condition needs a gas condition on the same boundary");
  expect_error(edit(column_1d, "liquid: {suction: 0}", "liquid: {suction: 0, pressure: 0}"),
               "liquid: {suction", "boundaries[0].liquid.suction", "give exactly one of");
}

TEST(CaseParserHydraulicsErrors, HydraulicConditionOffTheOuterFaces) {
  expect_error(edit(slope_2d, "plane: {axis: y, at: 2}", "plane: {axis: y, at: 1.5}"),
               "liquid: {suction", "boundaries[1].liquid",
               "a liquid condition must lie on an outer face of the grid, but plane y = 1.5 is "
               "inside it (outer faces: y = 0 and y = 2)");
  // A mechanical condition may lie inside the grid.
  EXPECT_NO_THROW(parse(edit(slope_2d, "plane: {axis: y, at: 0}", "plane: {axis: y, at: 0.5}")));
}

TEST(CaseParserHydraulicsErrors, DuplicateFluidConditionOnAPlane) {
  const std::string text = edit(column_1d, "  - name: bottom\n    plane: {axis: x, at: 0}",
                                "  - name: bottom\n    plane: {axis: x, at: 1.0}");
  expect_error(text, "    gas: {pressure: 0}\nsolver", "boundaries[1].gas",
               "a gas condition on plane x = 1 is already given by boundary 'top'");
}

TEST(CaseParserHydraulicsErrors, InitialStateAndEmptyBoundary) {
  expect_error(edit(column_1d, "suction: 5.0e5", "suction: -1"), "suction: -1",
               "bodies[0].initial_state.suction", "-1 is out of range [0, inf)");
  expect_error(edit(column_1d, "{suction: 5.0e5,", "{liquid_pressure: 0, suction: 5.0e5,"),
               "initial_state", "bodies[0].initial_state.suction", "give exactly one of");
  expect_error(edit(column_1d, "{suction: 5.0e5, ", "{"), "initial_state",
               "bodies[0].initial_state", "expected one of liquid_pressure, suction, water_table");
  expect_error(edit(column_1d, "gas_pressure: 0}", "gas_pressure: -2.0e5}"), "gas_pressure: -2",
               "bodies[0].initial_state.gas_pressure", "out of range (-101325, inf)");
  expect_error(edit(column_1d, "    initial_state: {suction: 5.0e5, gas_pressure: 0}\n", ""),
               "  - name: column", "bodies[0]", "missing required key 'initial_state'");
  expect_error(edit(column_1d, "    gas: {pressure: 0}\nsolver", "solver"), "  - name: bottom",
               "boundaries[1]",
               "boundary 'bottom' prescribes nothing: give at least one of "
               "mechanical, traction, liquid, gas");
}

}  // namespace test_case_parser_hydraulics
}  // namespace unsatmpm

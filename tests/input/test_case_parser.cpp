// The case parser: valid 1D/2D/3D cases with their defaults, the effective-configuration round
// trip, and one test per error class checking file, line and key path of the message.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <string>

#include "case_parser_test_support.hpp"  // same folder
#include "input/case_parser.hpp"

namespace unsatmpm {
namespace test_case_parser {

using namespace test_support;

constexpr double deg = std::numbers::pi / 180.0;

const std::string case_2d = R"(name: column_selfweight
dimension: 2
grid: {origin: [0, 0], size: [1.0, 4.0], cells: [4, 16]}
shape_function: linear
gravity: [0, -9.81]
materials:
  - name: soil
    density: 1800
    model: mohr_coulomb
    young_modulus: 1.0e7
    poisson_ratio: 0.3
    cohesion: 5000
    friction_angle: 30
  - {name: stiff, density: 2000, model: linear_elastic, young_modulus: 1.0e8, poisson_ratio: 0.25}
bodies:
  - name: column
    material: soil
    points_per_cell: 2
    box: {min: [0, 0], max: [1, 2]}
  - name: wedge
    material: stiff
    points_per_cell: 3
    polygon: {vertices: [[0, 2], [1, 2], [0, 4]]}
    initial_velocity: [0, -0.5]
boundaries:
  - name: base
    plane: {axis: y, at: 0.0}
    mechanical: fixed
  - {name: left, plane: {axis: x, at: 0}, mechanical: roller}
solver:
  end_time: 1.0
  damping: 0.05
output:
  times: [0.1, 0.2]
  control_points:
    - {name: tip, position: [0.5, 4.0]}
)";

const std::string case_1d = R"(name: bar
dimension: 1
grid: {origin: [-1], size: [2], cells: [20]}
shape_function: gimp
gravity: [0]
materials: [{name: m, density: 1000, model: linear_elastic, young_modulus: 1e6, poisson_ratio: 0}]
bodies:
  - {name: bar, material: m, points_per_cell: 4, box: {min: [-1], max: [1]},
     initial_velocity: {sine: {amplitude: [0.01], axis: x, wavenumber: 1.5708}}}
solver: {end_time: 2, time_step: {fixed: 1.0e-4}, damping: 0, flip_fraction: 0.99}
output: {history_interval: 0.01, write_grid: false}
)";

const std::string case_3d = R"(name: slope
dimension: 3
grid: {origin: [0, 0, 0], size: [10, 5, 1], cells: [20, 10, 2]}
shape_function: gimp
gravity: [0, -9.81, 0]
materials:
  - {name: clay, density: 1900, model: mohr_coulomb, young_modulus: 2e7, poisson_ratio: 0.3,
     cohesion: 10e3, friction_angle: 20, dilatancy_angle: 5, tensile_strength: 1000}
bodies:
  - {name: slope, material: clay, points_per_cell: 2,
     polygon: {vertices: [[0, 0], [10, 0], [10, 2], [0, 5]], extrude_z: [0, 1]}}
boundaries:
  - {name: back, plane: {axis: z, at: 0.5}, mechanical: roller}
solver: {end_time: 3, time_step: {cfl_safety: 0.8}, damping: 0.1}
output: {}
)";

TEST(CaseParser, Parses2DCaseWithDefaults) {
  const Case c = parse(case_2d);
  EXPECT_EQ(c.grid.size, (std::vector<double>{1.0, 4.0}));
  EXPECT_EQ(c.grid.cells, (std::vector<int>{4, 16}));
  EXPECT_EQ(c.gravity, (std::vector<double>{0.0, -9.81}));
  const auto& mc = std::get<physics::MohrCoulomb>(c.materials.at(0).model);
  EXPECT_EQ(c.materials[0].density, 1800.0);
  EXPECT_DOUBLE_EQ(mc.strength.friction_angle, 30.0 * deg);
  EXPECT_EQ(mc.strength.dilatancy_angle, 0.0);                                  // default
  EXPECT_DOUBLE_EQ(mc.strength.tensile_strength, 5000.0 / std::tan(30 * deg));  // default
  EXPECT_EQ(std::get<physics::LinearElastic>(c.materials[1].model).poisson_ratio, 0.25);
  EXPECT_EQ(c.bodies.at(1).material, 1);
  EXPECT_EQ(std::get<BoxGeometry>(c.bodies[0].geometry).max, (std::vector<double>{1.0, 2.0}));
  EXPECT_EQ(std::get<std::vector<double>>(c.bodies[0].initial_velocity),
            (std::vector<double>{0.0, 0.0}));  // default
  EXPECT_EQ(std::get<std::vector<double>>(c.bodies[1].initial_velocity)[1], -0.5);
  EXPECT_EQ(c.boundaries.at(0).region.axis, 1);
  EXPECT_EQ(c.boundaries.at(1).mechanical, MechanicalCondition::roller);
  EXPECT_EQ(c.phases, Phases::solid);  // default
  EXPECT_FALSE(c.fluids.has_value());
  EXPECT_FALSE(c.materials[0].hydraulic.has_value());
  EXPECT_FALSE(c.bodies[0].initial_pressures.has_value());
  EXPECT_FALSE(c.boundaries[0].liquid || c.boundaries[0].gas_pressure);
  EXPECT_FALSE(c.solver.time_step.fixed.has_value());  // default: CFL
  EXPECT_EQ(c.solver.time_step.cfl_safety, 0.5);
  EXPECT_EQ(c.solver.flip_fraction, 1.0);
  EXPECT_EQ(c.output.times, (std::vector<double>{0.1, 0.2}));
  EXPECT_EQ(c.output.history_interval, 0.0);
  EXPECT_TRUE(c.output.write_grid);
  EXPECT_EQ(c.output.control_points.at(0).position, (std::vector<double>{0.5, 4.0}));
}

TEST(CaseParser, Parses1DCaseWithSineVelocityAndFixedStep) {
  const Case c = parse(case_1d);
  EXPECT_EQ(c.grid.origin, (std::vector<double>{-1.0}));
  EXPECT_EQ(c.shape_function, ShapeFunctionKind::gimp);
  const auto& sine = std::get<SineVelocity>(c.bodies[0].initial_velocity);
  EXPECT_EQ(sine.amplitude, (std::vector<double>{0.01}));
  EXPECT_EQ(sine.wavenumber, 1.5708);
  EXPECT_EQ(sine.origin, 0.0);  // default
  EXPECT_EQ(c.solver.time_step.fixed, 1.0e-4);
  EXPECT_EQ(c.solver.flip_fraction, 0.99);
  EXPECT_TRUE(c.boundaries.empty());
  EXPECT_TRUE(c.output.times.empty());
  EXPECT_EQ(c.output.history_interval, 0.01);
  EXPECT_FALSE(c.output.write_grid);
}

TEST(CaseParser, Parses3DCaseWithExtrudedPolygon) {
  const Case c = parse(case_3d);
  const auto& polygon = std::get<PolygonGeometry>(c.bodies[0].geometry);
  EXPECT_EQ(polygon.vertices.at(3)[1], 5.0);
  EXPECT_EQ(polygon.extrude_z.value()[1], 1.0);
  const auto& mc = std::get<physics::MohrCoulomb>(c.materials[0].model);
  EXPECT_DOUBLE_EQ(mc.strength.dilatancy_angle, 5.0 * deg);
  EXPECT_EQ(mc.strength.tensile_strength, 1000.0);
  EXPECT_EQ(c.boundaries.at(0).region.coordinate, 0.5);  // on z
  EXPECT_EQ(c.solver.time_step.cfl_safety, 0.8);
}

TEST(CaseParser, EffectiveConfigurationRoundTripsExactly) {
  // Angles that do not survive deg -> rad -> deg in floating point unless written with care.
  const std::string odd_angles =
      edit(case_2d, "friction_angle: 30", "friction_angle: 28.7\n    dilatancy_angle: 22.6");
  // (Three-phase cases: test_case_parser_hydraulics.cpp.)
  for (const std::string& text : {case_1d, case_2d, case_3d, odd_angles}) expect_round_trip(text);
  const std::string yaml = effective_configuration(parse(case_2d));
  EXPECT_NE(yaml.find("friction_angle: 30\n"), std::string::npos) << yaml;  // degrees
  EXPECT_NE(yaml.find("cfl_safety: 0.5"), std::string::npos) << yaml;       // defaults written
  EXPECT_NE(yaml.find("flip_fraction: 1\n"), std::string::npos) << yaml;
  EXPECT_NE(yaml.find("dilatancy_angle: 0\n"), std::string::npos) << yaml;
  EXPECT_NE(yaml.find("phases: solid\n"), std::string::npos) << yaml;  // echoed
  EXPECT_EQ(yaml.find("mass_balance"), std::string::npos) << yaml;     // solid: unknown key
  const std::string odd = effective_configuration(parse(odd_angles));
  EXPECT_NE(odd.find("friction_angle: 28.7\n"), std::string::npos) << odd;
  EXPECT_NE(odd.find("dilatancy_angle: 22.6\n"), std::string::npos) << odd;
}

TEST(CaseParserErrors, UnknownKeyAtTopLevelListsKnownKeys) {
  const std::string text = edit(case_2d, "shape_function: linear", "shape_functon: linear");
  expect_error(text, "shape_functon", "shape_functon",
               "unknown key 'shape_functon' at top level; known keys: name, dimension, grid");
}

TEST(CaseParserErrors, UnknownNestedKeyListsKnownKeys) {
  expect_error(edit(case_2d, "  damping: 0.05", "  dampin: 0.05"), "dampin", "solver.dampin",
               "unknown key 'dampin' in solver; known keys: end_time, time_step, damping, "
               "flip_fraction");
  // A key of the other constitutive model is unknown too.
  const std::string text =
      edit(case_2d, "poisson_ratio: 0.25}", "poisson_ratio: 0.25, cohesion: 1}");
  expect_error(text, "cohesion: 1", "materials[1].cohesion",
               "unknown key 'cohesion' in materials[1]; known keys: name, density, model, "
               "young_modulus, poisson_ratio");
}

TEST(CaseParserErrors, WrongTypeSaysWhatWasExpected) {
  const std::string text = edit(case_2d, "density: 1800", "density: abc");
  expect_error(text, "density: abc", "materials[0].density", "expected a number, got 'abc'");
  EXPECT_EQ(error_of(text).rfind("case.yaml:8:14:", 0), 0u) << error_of(text);  // the column
  expect_error(edit(case_2d, "cells: [4, 16]", "cells: [4, 16.5]"), "cells", "grid.cells[1]",
               "expected an integer, got '16.5'");
  expect_error(edit(case_2d, "damping: 0.05", "damping: '0.05'"), "damping", "solver.damping",
               "expected a number, got the quoted string '0.05'");
  expect_error(edit(case_2d, "  - name: base", "  - name: [base]"), "[base]", "boundaries[0].name",
               "expected a string, got a sequence");
}

TEST(CaseParserErrors, ExplicitYamlTagsAreRefused) {
  // A tag would make a string read as a number (!!str 0.05) or a number from a quoted string.
  expect_error(edit(case_2d, "damping: 0.05", "damping: !!str 0.05"), "damping", "solver.damping",
               "YAML tags are not accepted (found tag:yaml.org,2002:str)");
  expect_error(edit(case_2d, "damping: 0.05", "damping: !!float '0.05'"), "damping",
               "solver.damping", "YAML tags are not accepted");
  expect_error(edit(case_2d, "  - name: base", "  - name: !x base"), "!x base",
               "boundaries[0].name", "YAML tags are not accepted (found !x)");
  expect_error(edit(case_2d, "model: mohr_coulomb", "model: !!str mohr_coulomb"), "!!str mohr",
               "materials[0].model", "YAML tags are not accepted");
}

TEST(CaseParserErrors, AMissingElasticKeyOfAMohrCoulombMaterialIsNamed) {
  const std::string text = edit(case_2d, "    young_modulus: 1.0e7\n", "");
  expect_error(text, "  - name: soil", "materials[0]",
               "missing required key 'young_modulus' in materials[0]");
}

TEST(CaseParserErrors, MissingRequiredKeyNamesKeyAndEnclosingMap) {
  const std::string text = edit(case_2d, "  end_time: 1.0\n", "");
  expect_error(text, "  damping: 0.05", "solver", "missing required key 'end_time' in solver");
  expect_error(edit(case_2d, "output:\n  times", "output_:\n  times"), "output_", "output_",
               "unknown key 'output_'");  // the likely misspelling is reported first
}

TEST(CaseParserErrors, OutOfRangeGivesValueAndRange) {
  expect_error(edit(case_2d, "damping: 0.05", "damping: 1.5"), "damping", "solver.damping",
               "1.5 is out of range [0, 1)");
  expect_error(edit(case_2d, "points_per_cell: 3", "points_per_cell: 7"), "points_per_cell: 7",
               "bodies[1].points_per_cell", "7 is out of range [1, 6]");
  expect_error(edit(case_2d, "times: [0.1, 0.2]", "times: [0.1, 2.0]"), "times", "output.times[1]",
               "2.0 is out of range (0, 1]");
  expect_error(edit(case_2d, "times: [0.1, 0.2]", "times: [0.2, 0.1]"), "times", "output.times[1]",
               "strictly ascending");
}

TEST(CaseParserErrors, NonFiniteNumbersAreRejected) {
  expect_error(edit(case_2d, "end_time: 1.0", "end_time: .nan"), "end_time", "solver.end_time",
               "expected a finite number, got '.nan'");
  expect_error(edit(case_2d, "gravity: [0, -9.81]", "gravity: [0, -.inf]"), "gravity", "gravity[1]",
               "expected a finite number, got '-.inf'");
}

TEST(CaseParserErrors, DuplicateKeysAreRejected) {
  const std::string text = edit(case_2d, "  damping: 0.05", "  damping: 0.05\n  damping: 0.1");
  expect_error(text, "  damping: 0.1", "solver.damping",
               "duplicate key 'damping' (first given at line " +
                   std::to_string(line_of(text, "damping")) + ")");
  expect_error(edit(case_2d, "at: 0.0}", "at: 0.0, at: 1.0}"), "at: 1.0", "boundaries[0].plane.at",
               "duplicate key 'at'");
}

TEST(CaseParserErrors, YamlSyntaxErrorNamesFileAndLine) {
  const std::string text = edit(case_2d, "cells: [4, 16]}", "cells: [4, 16}");
  const std::string message = error_of(text);
  EXPECT_EQ(message.rfind("case.yaml:3:", 0), 0u) << message;
  EXPECT_NE(message.find("YAML syntax error"), std::string::npos) << message;
}

TEST(CaseParserErrors, MissingFileNamesTheFile) {
  const std::string path = "/nonexistent-unsatmpm-dir/case.yaml";
  const std::string message = error_of([&] { parse_case_file(path); });
  EXPECT_EQ(message.rfind(path + ": cannot open the file", 0), 0u) << message;
  // And a readable file parses, remembering its path.
  const std::string file = testing::TempDir() + "unsatmpm_case_parser.yaml";
  std::ofstream(file) << case_1d;
  EXPECT_EQ(parse_case_file(file).file, file);
  std::remove(file.c_str());
}

TEST(CaseParserErrors, BodyOutsideGrid) {
  expect_error(edit(case_2d, "max: [1, 2]", "max: [1, 5]"), "max: [1, 5]", "bodies[0].box.max",
               "[1, 5] lies outside the grid [0, 1] x [0, 4]");
  expect_error(edit(case_2d, "[0, 4]]", "[0, 4.5]]"), "[0, 4.5]", "bodies[1].polygon.vertices[2]",
               "lies outside the grid");
  expect_error(edit(case_2d, "max: [1, 2]", "max: [1, -1]"), "max: [1, -1]", "bodies[0].box.max",
               "max must exceed min along every axis; along y");
  expect_error(edit(case_3d, "extrude_z: [0, 1]", "extrude_z: [0, 2]"), "extrude_z",
               "bodies[0].polygon.extrude_z", "outside the grid's z range [0, 1]");
}

TEST(CaseParserErrors, BoundaryPlaneMustBeOnGridNodePlane) {
  expect_error(edit(case_2d, "at: 0.0}", "at: 0.3}"), "at: 0.3", "boundaries[0].plane.at",
               "plane y = 0.3 is not on a grid node plane (nearest: 0.25 and 0.5; spacing 0.25)");
  expect_error(edit(case_2d, "at: 0.0}", "at: 4.25}"), "at: 4.25", "boundaries[0].plane.at",
               "lies outside the grid [0, 4]");
  // Nearer the last node plane than a spacing beyond it: outside, not "between 4 and 4.25".
  expect_error(edit(case_2d, "at: 0.0}", "at: 4.1}"), "at: 4.1", "boundaries[0].plane.at",
               "plane y = 4.1 lies outside the grid [0, 4]");
  expect_error(edit(case_2d, "axis: y", "axis: z"), "axis: z", "boundaries[0].plane.axis",
               "axis 'z' does not exist in 2D");
}

TEST(CaseParserErrors, UnknownMaterialListsKnownNames) {
  expect_error(edit(case_2d, "material: stiff", "material: stif"), "material: stif",
               "bodies[1].material", "unknown material 'stif'; known materials: soil, stiff");
  expect_error(edit(case_2d, "name: stiff", "name: soil"), "name: soil, density: 2000",
               "materials[1].name", "duplicate material name 'soil' (first defined at line 7)");
}

TEST(CaseParserErrors, BadPolygons) {
  const std::string bow_tie = "vertices: [[0, 2], [1, 4], [1, 2], [0, 4]]";
  expect_error(edit(case_2d, "vertices: [[0, 2], [1, 2], [0, 4]]", bow_tie), "vertices",
               "bodies[1].polygon.vertices", "edge 0 (vertices 0-1) and edge 2 (vertices 2-3)");
  expect_error(edit(case_2d, "[[0, 2], [1, 2], [0, 4]]", "[[0, 2], [1, 2]]"), "vertices",
               "bodies[1].polygon.vertices", "at least 3 vertices, got 2");
  expect_error(edit(case_2d, "[[0, 2], [1, 2], [0, 4]]", "[[0, 2], [1, 2], [0.5, 2]]"), "vertices",
               "bodies[1].polygon.vertices", "folds back");
  expect_error(edit(case_2d, "[0, 4]]}", "[0, 4]], extrude_z: [0, 1]}"), "extrude_z",
               "bodies[1].polygon.extrude_z", "extrude_z is allowed only in 3D");
  expect_error(edit(case_3d, ", extrude_z: [0, 1]}", "}"), "polygon", "bodies[0].polygon",
               "missing required key 'extrude_z'");
}

TEST(CaseParserErrors, WrongVectorLength) {
  expect_error(edit(case_2d, "gravity: [0, -9.81]", "gravity: [0, -9.81, 0]"), "gravity", "gravity",
               "expected 2 numbers (one per dimension; dimension is 2), got 3");
  expect_error(edit(case_3d, "origin: [0, 0, 0]", "origin: [0, 0]"), "origin", "grid.origin",
               "expected 3 numbers");
}

TEST(CaseParserErrors, PhysicsParametersCheckedByTheModelFactories) {
  expect_error(edit(case_2d, "friction_angle: 30", "friction_angle: 95"), "friction_angle",
               "materials[0].friction_angle", "95 deg is out of range (0, 90) deg");
  expect_error(edit(case_2d, "friction_angle: 30", "friction_angle: 30\n    dilatancy_angle: 40"),
               "dilatancy_angle", "materials[0].dilatancy_angle",
               "40 deg is out of range [0, 30] deg");
  expect_error(edit(case_2d, "poisson_ratio: 0.25", "poisson_ratio: 0.6"), "poisson_ratio: 0.6",
               "materials[1].poisson_ratio", "poisson_ratio = 0.6");
  expect_error(edit(case_2d, "friction_angle: 30", "friction_angle: 30\n    tensile_strength: 1e5"),
               "tensile_strength", "materials[0].tensile_strength", "tensile_strength = 100000");
}

const std::string loaded_top = R"(  - name: surcharge
    plane: {axis: y, at: 2.0}
    traction: {normal: {ramp: {from: 0, to: 2.0e+4, start: 0, end: 1}}, shear: {axis: x, value: 500}}
)";

TEST(CaseParser, TractionOnAPlaneRoundTrips) {
  const std::string text = edit(case_2d, "solver:\n", loaded_top + "solver:\n");
  const Case c = parse(text);
  ASSERT_TRUE(c.boundaries.back().traction);
  const TractionSpec& t = *c.boundaries.back().traction;
  EXPECT_EQ(c.boundaries.back().mechanical, std::nullopt);  // a solid case's load needs none
  EXPECT_DOUBLE_EQ(t.normal(0.5), 1.0e4);
  EXPECT_EQ(t.shear_axis, 0);
  EXPECT_DOUBLE_EQ(t.shear(3.0), 500.0);
  EXPECT_EQ(t.where.rfind("case.yaml:" + std::to_string(line_of(text, "traction:")) + ":", 0), 0u)
      << t.where;
  expect_round_trip(text);
}

TEST(CaseParserErrors, TractionsCheckedWhereTheyAreRead) {
  const std::string text = edit(case_2d, "solver:\n", loaded_top + "solver:\n");
  expect_error(edit(text, "shear: {axis: x,", "shear: {axis: y,"), "shear: {axis: y",
               "boundaries[2].traction.shear.axis", "must differ from the plane's (y)");
  expect_error(edit(text, "normal: {ramp", "pressure: {ramp"), "pressure: {ramp",
               "boundaries[2].traction.pressure", "unknown key");
  expect_error(edit(text, "at: 2.0}\n    traction", "at: 0.0}\n    traction"), "traction: {",
               "boundaries[2].traction", "holds (fixed): the load would act on held nodes");
  // A roller holds the normal component: a normal load there is refused, a shear is not.
  const std::string on_roller =
      edit(text, "at: 2.0}\n    traction", "at: 2.0}\n    mechanical: roller\n    traction");
  expect_error(on_roller, "traction: {", "boundaries[2].traction", "holds (roller)");
  EXPECT_NO_THROW(parse(edit(on_roller, "to: 2.0e+4", "to: 0")));
}

const std::string plate_top = R"(  - name: plate
    plane: {axis: y, at: 2.0}
    mechanical: rigid_plate
    traction: {normal: 1.0e+4}
)";

TEST(CaseParser, RigidPlateCarriesATraction) {
  // A roller on a crossing plane (left, x = 0) holds another component: allowed.
  const std::string text = edit(case_2d, "solver:\n", plate_top + "solver:\n");
  const Case c = parse(text);
  EXPECT_EQ(c.boundaries.back().mechanical, MechanicalCondition::rigid_plate);
  ASSERT_TRUE(c.boundaries.back().traction);
  EXPECT_DOUBLE_EQ(c.boundaries.back().traction->normal(0.0), 1.0e4);
  expect_round_trip(text);
}

TEST(CaseParserErrors, RigidPlateWhoseNormalMotionAnotherBoundaryHolds) {
  const std::string text = edit(case_2d, "solver:\n", plate_top + "solver:\n");
  // A plate on x = 1 crosses the fixed base (y = 0): refused at the plate's key.
  expect_error(edit(text, "{axis: y, at: 2.0}\n    mechanical: rigid_plate",
                    "{axis: x, at: 1.0}\n    mechanical: rigid_plate"),
               "mechanical: rigid_plate", "boundaries[2].mechanical",
               "boundary 'plate' is a rigid plate on plane x = 1, whose nodes' normal motion "
               "boundary 'base' (plane y = 0) also prescribes");
  // A roller on the plate's own plane.
  expect_error(edit(text, "solver:\n",
                    "  - {name: cap, plane: {axis: y, at: 2.0}, mechanical: roller}\nsolver:\n"),
               "name: cap", "boundaries[3].mechanical", "boundary 'cap' (plane y = 2)");
  // A fixed plane listed after the plate and crossing it: refused at the later key.
  const std::string wall = edit(text, "solver:\n",
                                "  - {name: wall, plane: {axis: x, at: 1.0}, mechanical: fixed}\n"
                                "solver:\n");
  expect_error(wall, "name: wall", "boundaries[3].mechanical",
               "boundary 'plate' is a rigid plate on plane y = 2, whose nodes' normal motion "
               "boundary 'wall' (plane x = 1) also prescribes");
}

TEST(CaseParserErrors, MutuallyExclusiveTimeStepAndPolygonIn1D) {
  expect_error(edit(case_3d, "{cfl_safety: 0.8}", "{cfl_safety: 0.8, fixed: 1e-3}"), "time_step",
               "solver.time_step", "fixed and cfl_safety are mutually exclusive");
  expect_error(edit(case_1d, "box: {min: [-1], max: [1]}", "polygon: {vertices: [[0, 0]]}"),
               "polygon", "bodies[0].polygon", "not allowed in 1D");
}

}  // namespace test_case_parser
}  // namespace unsatmpm

// The case parser's errors, one test per error class, each checking the file, line and key path
// of the message (docs/input.md, "Error messages").
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "case_parser_cases.hpp"         // same folder
#include "case_parser_test_support.hpp"  // same folder
#include "input/case_parser.hpp"

namespace unsatmpm {
namespace test_case_parser {

using namespace test_support;

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

TEST(CaseParserErrors, MutuallyExclusiveTimeStepAndPolygonIn1D) {
  expect_error(edit(case_3d, "{cfl_safety: 0.8}", "{cfl_safety: 0.8, fixed: 1e-3}"), "time_step",
               "solver.time_step", "fixed and cfl_safety are mutually exclusive");
  expect_error(edit(case_1d, "box: {min: [-1], max: [1]}", "polygon: {vertices: [[0, 0]]}"),
               "polygon", "bodies[0].polygon", "not allowed in 1D");
}

}  // namespace test_case_parser
}  // namespace unsatmpm

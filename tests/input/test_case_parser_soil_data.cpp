// The case parser, soil data: initial pore pressures about a water table or tabulated against
// elevation, and retention and relative-permeability curves given as measured points; their
// effective-configuration round trip and their errors (file, line, key path, offending point).
#include <gtest/gtest.h>

#include <string>
#include <variant>

#include "case_parser_test_support.hpp"  // same folder
#include "input/case_parser.hpp"
#include "three_phase_cases.hpp"

namespace unsatmpm {
namespace test_case_parser_soil_data {

using namespace test_support;

// A water table needs gravity, both of its keys, and pressures that exist over the grid.
TEST(CaseParserHydraulics, WaterTableIsReadCheckedAndWrittenBack) {
  const std::string with_gravity = edit(column_1d, "gravity: [0]", "gravity: [-9.81]");
  const std::string table = edit(with_gravity, "{suction: 5.0e5, gas_pressure: 0}",
                                 "{water_table: {elevation: 0.6, max_suction: 2.0e4}, "
                                 "gas_pressure: 50}");
  const Case c = parse(table);
  const auto& w = c.bodies[0].initial_pressures->water_table;
  ASSERT_TRUE(w.has_value());
  EXPECT_EQ(w->elevation, 0.6);
  EXPECT_EQ(w->max_suction, 2.0e4);
  EXPECT_EQ(w->gas_pressure, 50.0);
  expect_round_trip(table);
  const std::string yaml = effective_configuration(c);
  EXPECT_NE(yaml.find("initial_state: {water_table: {elevation: 0.6, max_suction: 20000}, "
                      "gas_pressure: 50}"),
            std::string::npos)
      << yaml;

  const std::string key = "bodies[0].initial_state.water_table";
  expect_error(edit(table, "gravity: [-9.81]", "gravity: [0]"), "water_table", key,
               "a water table needs gravity");
  expect_error(edit(table, ", max_suction: 2.0e4", ""), "water_table", key,
               "missing required key 'max_suction'");
  expect_error(edit(table, "max_suction: 2.0e4", "max_suction: -1"), "water_table",
               key + ".max_suction", "out of range [0, inf)");
  expect_error(edit(table, "{water_table:", "{suction: 0, water_table:"), "initial_state", key,
               "give exactly one of liquid_pressure, suction, water_table");
  // K_l = 8e7 Pa: the liquid can be at rest at most 8155 m below its table.
  expect_error(edit(table, "elevation: 0.6", "elevation: 9000"), "water_table", key + ".elevation",
               "the liquid cannot be at rest");
  // Far below the grid, the ideal gas above the table thins to nothing.
  expect_error(edit(table, "elevation: 0.6", "elevation: -1.0e7"), "water_table",
               key + ".elevation", "absolute pressure <= 0");
}

// A liquid pressure tabulated against elevation: piecewise linear, read back exactly.
TEST(CaseParserHydraulics, LiquidPressureTableAgainstElevation) {
  const std::string table =
      edit(edit(column_1d, "gravity: [0]", "gravity: [-9.81]"), "{suction: 5.0e5,",
           "{liquid_pressure: {table: [[0, 2.0e4], [1, -500]]},");
  const Case c = parse(table);
  const auto& profile = c.bodies[0].initial_pressures->liquid_profile;
  ASSERT_TRUE(profile.has_value());
  EXPECT_EQ((*profile)(0.25), 2.0e4 - 0.25 * 20500.0);
  expect_round_trip(table);
  const std::string key = "bodies[0].initial_state.liquid_pressure";
  expect_error(edit(table, "gravity: [-9.81]", "gravity: [0]"), "liquid_pressure", key,
               "a table against elevation needs gravity");
  expect_error(edit(table, "[1, -500]", "[0, -500]"), "[[0, 2.0e4], [0,", key + ".table[1][0]",
               "table elevations must be strictly ascending");
}

// Measured curves as tables: read, written back exactly, an error at the offending point's line.
TEST(CaseParserHydraulics, TabulatedCurves) {
  const std::string text = edit(
      edit(edit(column_1d, "retention: {model: linear, a_s: 1.0e-6}",
                "retention: {model: table, points: [[0, 1], [1.0e4, 0.8],\n"
                "                                       [1.0e5, 0.3]]}"),
           "liquid_relative_permeability: {model: constant}",
           "liquid_relative_permeability: {model: table, points: [[0, 0], [0.5, 0.1], [1, 1]]}"),
      "gas_relative_permeability: {model: constant}",
      "gas_relative_permeability: {model: table, points: [[0, 1], [1, 0]]}");
  const Case c = parse(text);
  const auto& h = *c.materials[0].hydraulic;
  EXPECT_EQ(std::get<physics::TabulatedRetention>(h.retention).table.back(), 0.3);
  EXPECT_EQ(std::get<physics::TabulatedRelPerm>(h.liquid_relative_permeability).table.ys()[1], 0.1);
  EXPECT_EQ(std::get<physics::TabulatedRelPerm>(h.gas_relative_permeability).value(0.5), 0.5);
  expect_round_trip(text);
  const std::string key = "materials[0].retention.points";
  expect_error(edit(text, "[1.0e5, 0.3]", "[1.0e5, 0.9]"), "[1.0e5, 0.9]", key + "[2]",
               "point 2 [100000, 0.9]: saturation must not increase as suction grows");
  expect_error(edit(text, "[[0, 1], [1.0e4", "[[5, 1], [1.0e4"), "[[5, 1]", key + "[0]",
               "the first point must be at suction 0");
  expect_error(edit(text, "[0.5, 0.1], [1, 1]", "[0.5, 0.1], [0.9, 1]"), "[0.9, 1]",
               "materials[0].liquid_relative_permeability.points[2]",
               "the last point must be at effective saturation 1");
  expect_error(edit(text, "points: [[0, 1], [1, 0]]", "points: 3"), "points: 3",
               "materials[0].gas_relative_permeability.points", "expected a list of [x, y] pairs");
}

}  // namespace test_case_parser_soil_data
}  // namespace unsatmpm

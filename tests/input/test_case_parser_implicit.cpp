// The case parser, the main cycle's part: the implicit cycle's settings, the free surface
// (pressures, rainfall), gravity loading; their round trip and one test per error class checking
// file, line and key path of the message.
#include <gtest/gtest.h>

#include <string>

#include "case_parser_test_support.hpp"  // same folder
#include "input/case_parser.hpp"
#include "three_phase_cases.hpp"

namespace unsatmpm {
namespace test_case_parser_implicit {

using namespace test_support;

const std::string implicit_settings =
    "  damping: 0\n  cycle: implicit\n  implicit: {relative_tolerance: 1.0e-5, "
    "absolute_tolerance: 0.5, coupling_interval: 0.01, linear_solver: iterative, "
    "direct_solver: klu}\n";

TEST(CaseParserHydraulics, ImplicitCycleSettingsAndDefaults) {
  const Case c = parse(edit(column_1d, "  damping: 0\n", implicit_settings));
  EXPECT_EQ(c.solver.cycle, Cycle::implicit_pressure);
  EXPECT_EQ(c.solver.implicit.relative_tolerance, 1e-5);
  EXPECT_EQ(c.solver.implicit.absolute_tolerance, 0.5);
  ASSERT_TRUE(c.solver.implicit.coupling_interval);
  EXPECT_EQ(*c.solver.implicit.coupling_interval, 0.01);
  EXPECT_EQ(c.solver.implicit.linear_solver, FlowLinearSolver::iterative);
  EXPECT_EQ(c.solver.implicit.direct_solver, FlowDirectSolver::klu);
  expect_round_trip(edit(column_1d, "  damping: 0\n", implicit_settings));

  const Case d =
      parse(edit(column_1d, "  damping: 0\n",
                 "  damping: 0\n  cycle: implicit\n  implicit: {coupling_interval: auto}\n"));
  EXPECT_EQ(d.solver.implicit.relative_tolerance, 1e-6);  // defaults
  EXPECT_EQ(d.solver.implicit.absolute_tolerance, 1.0);
  EXPECT_FALSE(d.solver.implicit.coupling_interval);
  EXPECT_EQ(d.solver.implicit.linear_solver, FlowLinearSolver::automatic);
  EXPECT_EQ(d.solver.implicit.direct_solver, FlowDirectSolver::umfpack);
  EXPECT_EQ(d.solver.implicit.surface_penalty, 0.0);
  const std::string yaml = effective_configuration(d);
  EXPECT_NE(yaml.find("linear_solver: auto"), std::string::npos) << yaml;
  EXPECT_NE(yaml.find("direct_solver: umfpack"), std::string::npos) << yaml;
  EXPECT_NE(yaml.find("cycle: implicit"), std::string::npos) << yaml;
  EXPECT_NE(yaml.find("coupling_interval: auto"), std::string::npos) << yaml;
  EXPECT_EQ(parse(column_1d).solver.cycle, Cycle::explicit_dynamic);  // the default
}

TEST(CaseParserHydraulicsErrors, ImplicitCycleSettings) {
  expect_error(edit(column_1d, "  damping: 0\n", "  damping: 0\n  cycle: implict\n"), "cycle",
               "solver.cycle", "expected one of explicit, implicit, got 'implict'");
  expect_error(edit(solid_1d, "damping: 0}", "damping: 0, cycle: implicit}"), "cycle",
               "solver.cycle", "needs phases: solid_liquid_gas");
  expect_error(edit(column_1d, "  damping: 0\n", "  damping: 0\n  implicit: {}\n"), "implicit",
               "solver.implicit", "set cycle: implicit");
  expect_error(edit(column_1d, "  damping: 0\n",
                    "  damping: 0\n  cycle: implicit\n"
                    "  implicit: {relative_tolerance: 0}\n"),
               "  implicit: {", "solver.implicit.relative_tolerance", "out of range");
  expect_error(edit(column_1d, "  damping: 0\n",
                    "  damping: 0\n  cycle: implicit\n"
                    "  implicit: {coupling_interval: never}\n"),
               "  implicit: {", "solver.implicit.coupling_interval",
               "expected a time > 0 [s] or auto, got 'never'");
  expect_error(edit(column_1d, "  damping: 0\n",
                    "  damping: 0\n  cycle: implicit\n"
                    "  implicit: {linear_solver: gmres}\n"),
               "  implicit: {", "solver.implicit.linear_solver",
               "expected one of auto, direct, iterative, got 'gmres'");
  expect_error(edit(column_1d, "  damping: 0\n",
                    "  damping: 0\n  cycle: implicit\n"
                    "  implicit: {direct_solver: superlu}\n"),
               "  implicit: {", "solver.implicit.direct_solver",
               "expected one of umfpack, klu, got 'superlu'");
  expect_error(edit(column_1d, "  damping: 0\n",
                    "  damping: 0\n  cycle: implicit\n"
                    "  implicit: {absolute_tolerance: .nan}\n"),
               "  implicit: {", "solver.implicit.absolute_tolerance", "finite");
}

// slope_2d on the implicit cycle with rain on the free surface and gravity loading.
const std::string slope_rain =
    edit(slope_2d, "solver: {end_time: 20, damping: 0.05}",
         "free_surface:\n"
         "  liquid: {suction: {ramp: {from: 8.0e5, to: 0, start: 0, end: 12}}}\n"
         "  gas: {pressure: 0}\n"
         "solver:\n"
         "  end_time: 20\n"
         "  damping: 0.05\n"
         "  cycle: implicit\n"
         "  gravity_loading: {damping: 0.7, tolerance: 1.0e-3, max_time: 5}");

TEST(CaseParserHydraulics, FreeSurfaceAndGravityLoading) {
  const Case c = parse(slope_rain);
  ASSERT_TRUE(c.free_surface);
  ASSERT_TRUE(c.free_surface->liquid);
  EXPECT_EQ(c.free_surface->liquid->kind, LiquidCondition::Kind::suction);
  EXPECT_EQ(c.free_surface->liquid->value(0.0), 8.0e5);
  EXPECT_DOUBLE_EQ(c.free_surface->liquid->value(6.0), 4.0e5);
  ASSERT_TRUE(c.free_surface->gas_pressure);
  EXPECT_EQ((*c.free_surface->gas_pressure)(3.0), 0.0);
  ASSERT_TRUE(c.solver.gravity_loading);
  EXPECT_EQ(c.solver.gravity_loading->damping, 0.7);
  EXPECT_EQ(c.solver.gravity_loading->tolerance, 1e-3);
  EXPECT_EQ(c.solver.gravity_loading->max_time, 5.0);
  expect_round_trip(slope_rain);
  const std::string yaml = effective_configuration(c);
  EXPECT_NE(yaml.find("free_surface: {liquid: {suction: {ramp: {from: 8.0e+05, to: 0, start: 0, "
                      "end: 12}}}, gas: {pressure: 0}}"),
            std::string::npos)
      << yaml;
  EXPECT_NE(yaml.find("gravity_loading: {damping: 0.7, tolerance: 0.001, max_time: 5}"),
            std::string::npos)
      << yaml;
  // The surface's liquid condition as a penalty on the face's trace.
  EXPECT_EQ(c.solver.implicit.surface_penalty, 0.0);
  const std::string penalised = edit(slope_rain, "  cycle: implicit\n",
                                     "  cycle: implicit\n  implicit: {surface_penalty: 16}\n");
  EXPECT_EQ(parse(penalised).solver.implicit.surface_penalty, 16.0);
  expect_round_trip(penalised);
  EXPECT_NE(effective_configuration(parse(penalised)).find("surface_penalty: 16"),
            std::string::npos);
  // The flow's relative permeabilities from the nodes; the points' by default.
  EXPECT_EQ(c.solver.implicit.relative_permeability, RelativePermeabilityAt::points);
  const std::string from_nodes =
      edit(slope_rain, "  cycle: implicit\n",
           "  cycle: implicit\n  implicit: {relative_permeability: nodes}\n");
  EXPECT_EQ(parse(from_nodes).solver.implicit.relative_permeability, RelativePermeabilityAt::nodes);
  expect_round_trip(from_nodes);
  EXPECT_NE(effective_configuration(parse(from_nodes)).find("relative_permeability: nodes"),
            std::string::npos);
  const std::string bad =
      error_of(edit(slope_rain, "  cycle: implicit\n",
                    "  cycle: implicit\n  implicit: {relative_permeability: node}\n"));
  EXPECT_NE(bad.find("case.yaml:"), std::string::npos) << bad;
  EXPECT_NE(bad.find("relative_permeability"), std::string::npos) << bad;
  EXPECT_NE(bad.find("'node'"), std::string::npos) << bad;
  // Absent: no surface condition, no loading.
  EXPECT_FALSE(parse(slope_2d).free_surface);
  EXPECT_FALSE(parse(slope_2d).solver.gravity_loading);
  // A liquid pressure needs no gas condition; a gas condition alone is allowed.
  expect_round_trip(edit(slope_rain,
                         "{suction: {ramp: {from: 8.0e5, to: 0, start: 0, end: 12}}}\n"
                         "  gas: {pressure: 0}",
                         "{pressure: -1.0e4}"));
  expect_round_trip(edit(
      slope_rain, "  liquid: {suction: {ramp: {from: 8.0e5, to: 0, start: 0, end: 12}}}\n", ""));
}

// A three-phase case missing a top-level key reports that key, not its three-phase keys as
// unknown (they were known only once `phases` had been read, after the missing key).
TEST(CaseParserHydraulicsErrors, MissingKeyInAThreePhaseCase) {
  for (const auto& [line, key] :
       {std::pair<std::string, std::string>{"shape_function: linear\n", "shape_function"},
        {"grid: {origin: [0], size: [1], cells: [40]}\n", "grid"}}) {
    const std::string message = error_of(edit(column_1d, line, ""));
    EXPECT_EQ(message.rfind("case.yaml:1:", 0), 0u) << message;
    EXPECT_NE(message.find("missing required key '" + key + "' at top level"), std::string::npos)
        << message;
  }
}

TEST(CaseParserHydraulicsErrors, FreeSurface) {
  // Pressures, suctions and rain on the free surface act in both cycles.
  const Case explicit_rain =
      parse(edit(edit(slope_rain, "  cycle: implicit\n", ""),
                 "{suction: {ramp: {from: 8.0e5, to: 0, start: 0, end: 12}}}", "{rainfall: 20}"));
  EXPECT_EQ(explicit_rain.solver.cycle, Cycle::explicit_dynamic);
  EXPECT_TRUE(explicit_rain.free_surface->rainfall);
  expect_round_trip(edit(slope_rain, "  cycle: implicit\n", ""));
  expect_error(edit(slope_rain, "  gas: {pressure: 0}\nsolver", "solver"), "end: 12}}}",
               "free_surface.liquid", "needs a gas condition on the free surface");
  expect_error(
      edit(slope_rain, "  gas: {pressure: 0}\nsolver", "  gas: {pressure: 0}\n  rain: 1\nsolver"),
      "  rain: 1", "free_surface.rain", "unknown key");
  expect_error(edit(slope_rain,
                    "  liquid: {suction: {ramp: {from: 8.0e5, to: 0, start: 0, end: 12}}}\n"
                    "  gas: {pressure: 0}\n",
                    "  {}\n"),
               "  {}\nsolver", "free_surface", "expected at least one of liquid, gas");
  expect_error(edit(slope_rain, "from: 8.0e5, to: 0, start: 0, end: 12",
                    "from: -8.0e5, to: 0, start: 0, end: 12"),
               "from: -8.0e5", "free_surface.liquid.suction.ramp.from", "out of range");
  EXPECT_TRUE(parse(edit(column_1d, "solver:", "free_surface: {gas: {pressure: 0}}\nsolver:"))
                  .free_surface);
  expect_error(edit(solid_1d, "solver:", "free_surface: {gas: {pressure: 0}}\nsolver:"),
               "free_surface", "free_surface", "three-phase");
}

// Rainfall on the free surface: an intensity in mm/h, with the surface's gas condition.
const std::string slope_rainfall =
    edit(slope_rain, "{suction: {ramp: {from: 8.0e5, to: 0, start: 0, end: 12}}}",
         "{rainfall: {table: [[0, 20], [3600, 20], [3601, 0]]}}");

TEST(CaseParserHydraulics, Rainfall) {
  const Case c = parse(slope_rainfall);
  ASSERT_TRUE(c.free_surface);
  EXPECT_FALSE(c.free_surface->liquid);
  ASSERT_TRUE(c.free_surface->rainfall);
  EXPECT_EQ((*c.free_surface->rainfall)(100.0), 20.0);
  EXPECT_EQ((*c.free_surface->rainfall)(4000.0), 0.0);
  expect_round_trip(slope_rainfall);
  const std::string yaml = effective_configuration(c);
  EXPECT_NE(yaml.find("free_surface: {liquid: {rainfall: {table: [[0, 20], [3600, 20], [3601, "
                      "0]]}}, gas: {pressure: 0}}"),
            std::string::npos)
      << yaml;
  expect_round_trip(edit(slope_rainfall, "{table: [[0, 20], [3600, 20], [3601, 0]]}", "7.5"));
  // Under rain the penalty acts on the ponded part of the face (cycles/flow_prescription.hpp).
  const std::string penalised = edit(slope_rainfall, "  cycle: implicit\n",
                                     "  cycle: implicit\n  implicit: {surface_penalty: 16}\n");
  EXPECT_EQ(parse(penalised).solver.implicit.surface_penalty, 16.0);
  expect_round_trip(penalised);
}

TEST(CaseParserHydraulicsErrors, Rainfall) {
  expect_error(edit(slope_rainfall, "  gas: {pressure: 0}\nsolver", "solver"), "rainfall",
               "free_surface.liquid", "rainfall needs a gas condition on the free surface");
  expect_error(edit(slope_rainfall, "[0, 20], [3600", "[0, -20], [3600"), "rainfall",
               "free_surface.liquid.rainfall.table[0][1]", "out of range");
  expect_error(edit(slope_rainfall, "{rainfall: {", "{suction: 0, rainfall: {"), "rainfall",
               "free_surface.liquid.rainfall", "give exactly one of pressure, suction, rainfall");
  expect_error(edit(slope_rainfall, "gravity: [0, -9.81]", "gravity: [1, -9.81]"), "rainfall",
               "free_surface.liquid", "gravity, which must then point along one grid axis");
  // The surface penalty acts on a prescribed surface pressure, suction or rainfall only.
  expect_error(edit(column_1d, "  damping: 0\n",
                    "  damping: 0\n  cycle: implicit\n  implicit: {surface_penalty: 4}\n"),
               "  end_time", "solver", "which this case does not have");
  expect_error(edit(slope_rain, "  cycle: implicit\n",
                    "  cycle: implicit\n  implicit: {surface_penalty: -1}\n"),
               "  implicit: {", "solver.implicit.surface_penalty", "out of range");
  // On a plane: the rain has no column to fall on.
  expect_error(edit(column_1d, "liquid: {suction: 0}", "liquid: {rainfall: 10}"), "rainfall: 10",
               "boundaries[0].liquid.rainfall", "condition on the free surface");
}

TEST(CaseParserHydraulicsErrors, GravityLoading) {
  expect_error(edit(slope_rain, "tolerance: 1.0e-3", "tolerance: 0"), "gravity_loading",
               "solver.gravity_loading.tolerance", "out of range");
  expect_error(edit(slope_rain, "damping: 0.7", "damping: 1"), "gravity_loading",
               "solver.gravity_loading.damping", "out of range");
  expect_error(edit(slope_rain, ", max_time: 5}", "}"), "gravity_loading", "solver.gravity_loading",
               "max_time");
  expect_error(edit(slope_rain, "max_time: 5}", "max_time: 5, steps: 3}"), "gravity_loading",
               "solver.gravity_loading.steps", "unknown key");
  expect_error(
      edit(slope_rain, "mass_balance: simplified\n", "mass_balance: simplified\nskeleton: rigid\n"),
      "  end_time: 20\n", "solver", "needs a deformable skeleton");
}

}  // namespace test_case_parser_implicit
}  // namespace unsatmpm

// The case parser: valid 1D/2D/3D cases with their defaults, the effective-configuration round
// trip, and surface loads and rigid plates on boundary planes (the error classes of the rest:
// test_case_parser_errors.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "case_parser_cases.hpp"         // same folder
#include "case_parser_test_support.hpp"  // same folder
#include "input/case_parser.hpp"

namespace unsatmpm {
namespace test_case_parser {

using namespace test_support;

constexpr double deg = std::numbers::pi / 180.0;

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

}  // namespace test_case_parser
}  // namespace unsatmpm

// The case parser's run controls: solver.stop_at_rest read, written back and refused when wrong.
#include <gtest/gtest.h>

#include <string>

#include "case_parser_test_support.hpp"  // same folder
#include "input/case_parser.hpp"

namespace unsatmpm {
namespace test_case_parser_solver {

using namespace test_support;

const std::string settling = R"(name: settling
dimension: 2
grid: {origin: [0, 0], size: [1, 1.5], cells: [10, 15]}
shape_function: linear
gravity: [0, -9.81]
materials:
  - {name: soil, density: 1800, model: linear_elastic, young_modulus: 1.0e+6, poisson_ratio: 0.3}
bodies:
  - {name: block, material: soil, points_per_cell: 2, box: {min: [0, 0], max: [1, 1]}}
boundaries:
  - {name: base, plane: {axis: y, at: 0}, mechanical: fixed}
solver:
  end_time: 5
  damping: 0.3
  stop_at_rest: {fraction: 1.0e-3, hold: 0.5, min_peak: 2}
output: {}
)";

TEST(CaseParser, StopAtRestIsReadAndRoundTrips) {
  const Case c = parse(settling);
  ASSERT_TRUE(c.solver.stop_at_rest);
  EXPECT_EQ(c.solver.stop_at_rest->fraction, 1e-3);
  EXPECT_EQ(c.solver.stop_at_rest->hold, 0.5);
  EXPECT_EQ(c.solver.stop_at_rest->min_peak, 2.0);
  expect_round_trip(settling);
  EXPECT_NE(effective_configuration(c).find("stop_at_rest: {fraction: 0.001, hold: 0.5, "
                                            "min_peak: 2}"),
            std::string::npos)
      << effective_configuration(c);
  EXPECT_FALSE(
      parse(edit(settling, "  stop_at_rest: {fraction: 1.0e-3, hold: 0.5, min_peak: 2}\n", ""))
          .solver.stop_at_rest);
}

TEST(CaseParserErrors, StopAtRestNamesTheKey) {
  const std::string rule = "stop_at_rest: {fraction: 1.0e-3, hold: 0.5, min_peak: 2}";
  const auto with = [&](const std::string& r) { return edit(settling, rule, r); };
  expect_error(with("stop_at_rest: {fraction: 1, hold: 0.5, min_peak: 2}"), "stop_at_rest",
               "solver.stop_at_rest.fraction", "1 is out of range (0, 1)");
  expect_error(with("stop_at_rest: {fraction: 0.1, hold: 6, min_peak: 2}"), "stop_at_rest",
               "solver.stop_at_rest.hold", "6 is out of range (0, 5]");
  expect_error(with("stop_at_rest: {fraction: 0.1, hold: 1, min_peak: 0}"), "stop_at_rest",
               "solver.stop_at_rest.min_peak", "0 is out of range");
  expect_error(with("stop_at_rest: {fraction: 0.1, hold: 1}"), "stop_at_rest",
               "solver.stop_at_rest", "missing required key 'min_peak'");
  expect_error(with("stop_at_rest: {fraction: 0.1, hold: 1, min_peak: 1, after: 3}"),
               "stop_at_rest", "solver.stop_at_rest.after", "unknown key 'after'");
}

}  // namespace test_case_parser_solver
}  // namespace unsatmpm

// Helpers shared by the physics unit tests.
#pragma once

#include <gtest/gtest.h>

#include <limits>
#include <string>

#include "physics/parameter_error.hpp"

namespace unsatmpm::physics::test {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

template <class F>
double central_difference(F f, double x, double h) {
  return (f(x + h) - f(x - h)) / (2.0 * h);
}

/// Runs `make`, expecting a ParameterError that names `name` in parameter() and in what(), and
/// states the valid range.
template <class F>
void expect_parameter_error(F make, const std::string& name) {
  try {
    make();
    ADD_FAILURE() << "no ParameterError for " << name;
  } catch (const ParameterError& e) {
    EXPECT_EQ(e.parameter(), name);
    const std::string what = e.what();
    EXPECT_NE(what.find(name), std::string::npos) << what;
    EXPECT_NE(what.find("valid"), std::string::npos) << what;
  }
}

}  // namespace unsatmpm::physics::test

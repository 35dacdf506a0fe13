#include "physics/retention.hpp"

#include "physics/parameter_error.hpp"

#include <string>

namespace unsatmpm::physics {

OccludedGas OccludedGas::create(double scale, double s0, const char* s0_name) {
  require_in_range("occluded_gas_scale", scale, 0.0, 1e7, "Pa");
  if (scale > 0.0 && scale < 1.0)
    throw ParameterError("occluded_gas_scale",
                         "occluded_gas_scale = " + number_text(scale) +
                             " Pa is out of range; valid: 0 (no give) or [1, 1e+07] Pa");
  if (scale > 0.0 && 1.0 - s0 <= gas_free_saturation)
    throw ParameterError("occluded_gas_scale",
                         "occluded_gas_scale = " + number_text(scale) +
                             " Pa has no gas to act on: " + s0_name + " = " + number_text(s0) +
                             " leaves none in the pores at suction 0 (valid: 0, or " + s0_name +
                             " below " + number_text(1.0 - gas_free_saturation) + ")");
  return {scale};
}

LinearRetention LinearRetention::create(double a_s, double s_min) {
  // Parameter names are the input keys: the case parser reports the error at the key it names.
  require_in_open_range("a_s", a_s, 0.0, 1.0, "1/Pa");
  require_in_range("residual_saturation", s_min, 0.0, 0.99, "-");
  return {a_s, s_min};
}

VanGenuchten VanGenuchten::create(double p0, double lambda, double s_min, double s_max,
                                  double occluded_gas_scale) {
  require_in_open_range("p0", p0, 0.0, 1e10, "Pa");
  require_in_open_range("lambda", lambda, 0.0, 1.0, "-");
  require_in_range("max_saturation", s_max, 0.01, 1.0, "-");
  // Keeps s_max - s_min >= 0.01 so that S_e = (S - s_min) / (s_max - s_min) stays meaningful.
  require_in_range("residual_saturation", s_min, 0.0, s_max - 0.01, "-");
  return {p0, lambda, s_min, s_max,
          OccludedGas::create(occluded_gas_scale, s_max, "max_saturation")};
}

TabulatedRetention TabulatedRetention::create(const std::vector<std::array<double, 2>>& points) {
  if (!points.empty() && points.front()[0] != 0.0)
    throw ParameterError("points[0]",
                         "the first point must be at suction 0 (the saturated "
                         "state), got " +
                             number_text(points.front()[0]) + " Pa");
  TabulatedRetention r{MonotoneTable::create(points, MonotoneTable::Direction::decreasing, 0.0, 1.0,
                                             "suction", "saturation")};
  if (r.table.front() - r.table.back() < 0.01)
    throw ParameterError("points",
                         "the saturation must fall by at least 0.01 over the table "
                         "(from S_max = S(0) to S_min at the last point)");
  return r;
}

}  // namespace unsatmpm::physics

#include "physics/retention.hpp"

#include "physics/parameter_error.hpp"

namespace unsatmpm::physics {

LinearRetention LinearRetention::create(double a_s, double s_min) {
  // Parameter names are the input keys: the case parser reports the error at the key it names.
  require_in_open_range("a_s", a_s, 0.0, 1.0, "1/Pa");
  require_in_range("residual_saturation", s_min, 0.0, 0.99, "-");
  return {a_s, s_min};
}

VanGenuchten VanGenuchten::create(double p0, double lambda, double s_min, double s_max) {
  require_in_open_range("p0", p0, 0.0, 1e10, "Pa");
  require_in_open_range("lambda", lambda, 0.0, 1.0, "-");
  require_in_range("max_saturation", s_max, 0.01, 1.0, "-");
  // Keeps s_max - s_min >= 0.01 so that S_e = (S - s_min) / (s_max - s_min) stays meaningful.
  require_in_range("residual_saturation", s_min, 0.0, s_max - 0.01, "-");
  return {p0, lambda, s_min, s_max};
}

}  // namespace unsatmpm::physics

#include "physics/suction_strength.hpp"

#include <limits>
#include <numbers>

#include "physics/parameter_error.hpp"

namespace unsatmpm::physics {

SuctionStrength SuctionStrength::create(double cohesion, double cohesion_increase,
                                        double cohesion_rate, double friction_angle,
                                        double friction_increase, double dilatancy_angle,
                                        double tensile_strength) {
  // Parameter names are the input keys: the case parser reports the error at the key it names.
  constexpr double kInf = std::numeric_limits<double>::infinity();
  require_in_range("cohesion", cohesion, 0.0, kInf, "Pa");
  require_in_range("cohesion_increase", cohesion_increase, 0.0, kInf, "Pa");
  require_in_range("cohesion_rate", cohesion_rate, 0.0, kInf, "-");
  require_in_open_range("friction_angle", friction_angle, 0.0, std::numbers::pi / 2.0, "rad");
  require_in_range("friction_increase", friction_increase, 0.0, kInf, "rad/P_atm");
  require_in_range("dilatancy_angle", dilatancy_angle, 0.0, friction_angle, "rad");
  // No upper bound: t(s) = min(t', c(s) cot phi(s)) clips t' to the cone's apex at every suction;
  // t' = +infinity says so explicitly (the cut-off is the apex at every suction).
  if (tensile_strength != kInf)
    require_in_range("tensile_strength", tensile_strength, 0.0, kInf, "Pa");
  return {cohesion,          cohesion_increase, cohesion_rate,   friction_angle,
          friction_increase, dilatancy_angle,   tensile_strength};
}

}  // namespace unsatmpm::physics

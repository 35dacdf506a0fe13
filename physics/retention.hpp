// Water retention: degree of saturation S_l as a function of suction s [Pa] (SPEC §4).
//
// LinearRetention (paper eq. 7): S = clamp(1 - a_s s, s_min, 1), a_s [1/Pa].
// VanGenuchten (1980): S_e = [1 + (s / P0)^(1 / (1 - lambda))]^(-lambda),
//   S = s_min + (s_max - s_min) S_e, P0 [Pa] > 0, lambda in (0, 1).
// Each law gives S(s), dS/ds and the effective saturation S_e in [0, 1]. For s <= 0 (saturated)
// S is the law's maximum and dS/ds = 0: liquid storage in a saturated soil comes from the fluid's
// compressibility alone, and the storage is continuous from the unsaturated side only where the
// law's slope at s = 0+ is zero (van Genuchten); the linear law's slope jumps there by design.
#pragma once

#include <algorithm>
#include <cmath>
#include <variant>

namespace unsatmpm::physics {

struct LinearRetention {
  double a_s;    // [1/Pa]
  double s_min;  // residual degree of saturation [-]

  static LinearRetention create(double a_s, double s_min);
  double saturation(double s) const { return s <= 0.0 ? 1.0 : std::max(s_min, 1.0 - a_s * s); }
  double d_saturation(double s) const { return (s <= 0.0 || 1.0 - a_s * s <= s_min) ? 0.0 : -a_s; }
  double effective_saturation(double s) const { return (saturation(s) - s_min) / (1.0 - s_min); }
};

struct VanGenuchten {
  double p0;      // [Pa]
  double lambda;  // [-]
  double s_min, s_max;

  static VanGenuchten create(double p0, double lambda, double s_min, double s_max);
  double effective_saturation(double s) const {
    if (s <= 0.0) return 1.0;
    return std::pow(1.0 + std::pow(s / p0, 1.0 / (1.0 - lambda)), -lambda);
  }
  double saturation(double s) const { return s_min + (s_max - s_min) * effective_saturation(s); }
  double d_saturation(double s) const {
    if (s <= 0.0) return 0.0;
    const double m = 1.0 / (1.0 - lambda);
    const double x = std::pow(s / p0, m);
    // dS_e/ds = -lambda (1 + x)^(-lambda - 1) m x / s
    return (s_max - s_min) * (-lambda) * std::pow(1.0 + x, -lambda - 1.0) * m * x / s;
  }
};

using RetentionCurve = std::variant<LinearRetention, VanGenuchten>;

}  // namespace unsatmpm::physics

// Relative permeabilities as functions of the effective saturation S_e in [0, 1] (SPEC §4).
//
// Liquid: constant 1; power S_e^r (r >= 1); Mualem-van Genuchten (Mualem 1976, van Genuchten
//   1980) sqrt(S_e) [1 - (1 - S_e^(1/lambda))^lambda]^2. Gas: constant 1; power (1 - S_e)^r_g.
// Values are clamped to [0, 1]; S_e outside [0, 1] is clamped first.
#pragma once

#include <algorithm>
#include <cmath>
#include <variant>

namespace unsatmpm::physics {

inline double clamp_unit(double x) { return std::min(1.0, std::max(0.0, x)); }

struct ConstantRelPerm {
  double value(double /*se*/) const { return 1.0; }
};

struct PowerRelPerm {
  double exponent;  // r >= 1
  static PowerRelPerm create(double exponent);
  double value(double se) const { return std::pow(clamp_unit(se), exponent); }
};

struct MualemVanGenuchten {
  double lambda;  // in (0, 1)
  static MualemVanGenuchten create(double lambda);
  double value(double se) const {
    const double e = clamp_unit(se);
    const double inner = 1.0 - std::pow(1.0 - std::pow(e, 1.0 / lambda), lambda);
    return clamp_unit(std::sqrt(e) * inner * inner);
  }
};

struct GasPowerRelPerm {
  double exponent;  // r_g >= 1
  static GasPowerRelPerm create(double exponent);
  double value(double se) const { return std::pow(1.0 - clamp_unit(se), exponent); }
};

using LiquidRelPerm = std::variant<ConstantRelPerm, PowerRelPerm, MualemVanGenuchten>;
using GasRelPerm = std::variant<ConstantRelPerm, GasPowerRelPerm>;

}  // namespace unsatmpm::physics

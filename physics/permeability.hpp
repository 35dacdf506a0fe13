// Relative permeabilities k_r [-] as functions of the effective saturation S_e in [0, 1]
// (docs/models.md).
//
// Liquid: ConstantRelPerm 1; PowerRelPerm S_e^r (r in [1, 20]); MualemVanGenuchten (Mualem 1976,
//   van Genuchten 1980) sqrt(S_e) [1 - (1 - S_e^(1/lambda))^lambda]^2, lambda in (0, 1).
// Gas: ConstantRelPerm 1; GasPowerRelPerm (1 - S_e)^r_g (r_g in [1, 20]).
// Each law gives value(S_e) in [0, 1] and d_value(S_e) = dk_r/dS_e. S_e outside [0, 1] is clamped
// first, so there d_value = 0; at S_e = 0 and 1 it is the one-sided derivative from inside.
// Mualem-van Genuchten: d/dS_e (1 - S_e^(1/lambda))^lambda ~ (1 - S_e)^(lambda - 1) -> inf as
// S_e -> 1, so dk_r/dS_e -> +inf there. d_value holds it at its value at S_e = 1 - 1e-6
// (mualem_derivative_cap) for S_e in (1 - 1e-6, 1]: finite, continuous, never NaN or inf.
// Intrinsic permeability kappa [m^2] and viscosities [Pa s] live with the material, not here.
#pragma once

#include <algorithm>
#include <cmath>
#include <variant>
#include <vector>

#include "physics/monotone_table.hpp"

namespace unsatmpm::physics {

inline double clamp_unit(double x) { return std::min(1.0, std::max(0.0, x)); }

struct ConstantRelPerm {
  double value(double /*se*/) const { return 1.0; }
  double d_value(double /*se*/) const { return 0.0; }
};

struct PowerRelPerm {
  double exponent;  // r >= 1 (input key "exponent")

  /// Validated construction; throws ParameterError naming "exponent" and its valid range.
  static PowerRelPerm create(double exponent);
  double value(double se) const { return std::pow(clamp_unit(se), exponent); }
  double d_value(double se) const {
    if (se < 0.0 || se > 1.0) return 0.0;
    return exponent * std::pow(se, exponent - 1.0);
  }
};

namespace detail {
/// With u = e^(1/lambda): 1 - u, g = (1 - u)^lambda and f = 1 - g, each to full relative
/// precision for e in (0, 1) (1 - u through expm1 near e = 1, g through log1p near e = 0).
struct MualemTerms {
  double u, one_minus_u, g, f;
};
inline MualemTerms mualem_terms(double e, double lambda) {
  const double log_u = std::log(e) / lambda;
  const double u = std::exp(log_u);
  const double one_minus_u = -std::expm1(log_u);
  const double log_g = lambda * (u < 0.5 ? std::log1p(-u) : std::log(one_minus_u));
  return {u, one_minus_u, std::exp(log_g), -std::expm1(log_g)};
}
}  // namespace detail

struct MualemVanGenuchten {
  static constexpr double mualem_derivative_cap = 1e-6;  // d_value held for S_e > 1 - cap
  double lambda;                                         // in (0, 1)

  /// Validated construction; throws ParameterError naming "lambda" and its valid range.
  static MualemVanGenuchten create(double lambda);
  double value(double se) const {
    if (se <= 0.0) return 0.0;
    if (se >= 1.0) return 1.0;
    const double f = detail::mualem_terms(se, lambda).f;
    return clamp_unit(std::sqrt(se) * f * f);
  }
  /// dk/dS_e = (f / sqrt(S_e)) [f / 2 + 2 g u / (1 - u)]; 0 at S_e = 0 (its limit) and outside.
  double d_value(double se) const {
    if (se <= 0.0 || se > 1.0) return 0.0;
    const double e = std::min(se, 1.0 - mualem_derivative_cap);
    const detail::MualemTerms t = detail::mualem_terms(e, lambda);
    return t.f / std::sqrt(e) * (0.5 * t.f + 2.0 * t.g * t.u / t.one_minus_u);
  }
};

struct GasPowerRelPerm {
  double exponent;  // r_g >= 1 (input key "exponent")

  /// Validated construction; throws ParameterError naming "exponent" and its valid range.
  static GasPowerRelPerm create(double exponent);
  double value(double se) const { return std::pow(1.0 - clamp_unit(se), exponent); }
  double d_value(double se) const {
    if (se < 0.0 || se > 1.0) return 0.0;
    return -exponent * std::pow(1.0 - se, exponent - 1.0);
  }
};

/// A measured relative permeability: k_r at effective saturations S_e from 0 to 1 (first and
/// last points), values in [0, 1], non-decreasing for the liquid and non-increasing for the gas,
/// through a monotone cubic (monotone_table.hpp).
struct TabulatedRelPerm {
  MonotoneTable table;

  /// Validated construction; `gas` selects the direction. Throws ParameterError naming
  /// "points[k]" (or "points").
  static TabulatedRelPerm create(const std::vector<std::array<double, 2>>& points, bool gas);
  double value(double se) const { return table.value(clamp_unit(se)); }
  double d_value(double se) const { return (se < 0.0 || se > 1.0) ? 0.0 : table.slope(se); }
};

using LiquidRelPerm =
    std::variant<ConstantRelPerm, PowerRelPerm, MualemVanGenuchten, TabulatedRelPerm>;
using GasRelPerm = std::variant<ConstantRelPerm, GasPowerRelPerm, TabulatedRelPerm>;

}  // namespace unsatmpm::physics

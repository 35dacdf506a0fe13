// Water retention: degree of saturation S_l as a function of suction s [Pa] (docs/models.md).
//
// LinearRetention (Yerro et al. 2015, eq. 7): S = clamp(1 - a_s s, s_min, 1), a_s [1/Pa] > 0,
//   residual saturation s_min in [0, 0.99]; S_e = (S - s_min) / (1 - s_min).
//   Table 1: a_s = 1e-3 1/kPa = 1e-6 1/Pa gives S = 0.5 at s = 0.5 MPa.
// VanGenuchten (van Genuchten 1980): S_e = [1 + (s / P0)^m]^(-lambda), m = 1 / (1 - lambda),
//   S = s_min + (s_max - s_min) S_e; P0 [Pa] > 0, lambda in (0, 1), 0 <= s_min < s_max <= 1.
//   Since m > 1, dS/ds -> 0 as s -> 0+: the curve leaves saturation with zero slope.
//
// TabulatedRetention: measured points (s, S_l) through a monotone cubic (monotone_table.hpp).
//
// Each law gives saturation(s), d_saturation(s) = dS/ds [1/Pa] (<= 0), both at once with S_e
// (saturation_and_slope: the same values to the bit, van Genuchten's powers taken once),
// effective_saturation(s) in [0, 1] and d_effective_saturation(s) = dS_e/ds [1/Pa], and the
// second derivatives d2_saturation(s) = d^2S/ds^2 and d2_effective_saturation(s) [1/Pa^2] that
// the implicit solver's analytic Jacobian needs (derivatives of the storage matrix).
// Saturated states, s <= 0: the laws are called with the signed difference P_g - P_l
// (retention_suction), and S_e = 1 there. Where the law saturates the pores (S(0) = 1) S = 1 and
// both slopes and both second derivatives are 0 (not the one-sided values at 0+): liquid storage
// in a saturated soil comes from the liquid's compressibility alone. Where it leaves gas in the
// pores at s = 0 (S(0) = S_max < 1, van Genuchten or a table) that gas is occluded, and the law's
// branch at s < 0 is OccludedGas's: flat at S_max by default (the paper's law), or giving way to
// the liquid pressed above the gas (docs/models.md, "An occluded gas"). At s = 0 itself every
// value is the s <= 0 side's. For van Genuchten the slope is continuous at s = 0 when flat; the
// linear law's slope jumps from 0 to -a_s there (and back to 0 where it reaches s_min), by
// construction of eq. 7.
//
// Second derivative of van Genuchten, with x = (s/P0)^m (derivation: d ln S_e/ds = -lambda m r/s,
// d ln r/ds = m (1 - r)/s with r = x/(1 + x), and m - 1 = lambda m):
//   d^2S_e/ds^2 = lambda m^2 S_e [x/(1 + x)] [(x - lambda)/(1 + x)] / s^2,
// negative (concave) for x < lambda, positive (convex tail) beyond the inflection x = lambda.
// As s -> 0+ it tends to -lambda^2 m^2 (s/P0)^(m - 2) / P0^2: unbounded for m < 2 (lambda < 1/2),
// -1/P0^2 for m = 2, 0 for m > 2; it then jumps to the saturated 0 at s = 0. For lambda < 1/2,
// lambda m < 1, so for s >= 1e-12 P0 its magnitude stays below 1e12 / P0^2 (finite for any
// physical P0). Below that it grows like (s/P0)^(m - 2) and is held at -DBL_MAX where the true
// value leaves the doubles (m near 1: s P0 below ~1e-308 Pa^2): finite, never NaN, for any s.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <variant>
#include <vector>

#include "physics/monotone_table.hpp"

namespace unsatmpm::physics {

/// Gas saturation S_g = 1 - S_l at or below which a node (or, in the pointwise update, a point)
/// counts as free of gas: no connected gas phase whose mass balance could be solved. Both cycles
/// then hold its gas pressure at its surroundings' value and supply the gas that a desaturation
/// needs there, counted as gas inflow (docs/balance_laws.md, "Saturated soil"). 1e-4 is reached
/// at a suction of 100 Pa with the paper's linear law (a_s = 1e-6 1/Pa) and of about 150 Pa with
/// van Genuchten P0 = 20 kPa, lambda = 0.4: far below any suction the soil's state depends on.
inline constexpr double gas_free_saturation = 1e-4;

/// Whether a node whose points hold gas_volume of gas in pore_volume of pores [both m^3, or both
/// weighted alike] is free of gas: at most gas_free_saturation of its pores (both cycles' test).
inline bool free_of_gas(double gas_volume, double pore_volume) {
  return gas_volume <= gas_free_saturation * pore_volume;
}

/// The argument of the retention laws: P_g - P_l [Pa], signed. Its positive part is the suction
/// (unsaturated_state.hpp); below 0 the liquid is pressed above the gas, which only a law leaving
/// an occluded gas distinguishes from 0 (OccludedGas).
inline double retention_suction(double p_l, double p_g) { return p_g - p_l; }

/// The branch s < 0 of a law that leaves an occluded gas, S(0) = s0 < 1 (docs/models.md, "An
/// occluded gas"): S = 1 - (1 - s0) exp(s / scale). Compressed, a soil's occluded bubbles give
/// way to the water at about the water's pressure, so that the gas takes the compression at its
/// own stiffness (Boyle's law) rather than the water at its own; `scale` [Pa] is the excess of
/// the liquid's pressure over the gas's that drives 1 - 1/e of the occluded gas's pore space to
/// the liquid, and the results depend little on it where it is small beside the gas's absolute
/// pressure. scale = 0: no give, S = s0 and zero slopes (the paper's law, flat at S_max).
struct OccludedGas {
  double scale = 0.0;  // [Pa]

  /// Validated for a law with S(0) = s0 (named s0_name in the message): 0, or [1, 1e7] Pa where
  /// 1 - s0 exceeds gas_free_saturation; throws ParameterError naming "occluded_gas_scale".
  static OccludedGas create(double scale, double s0, const char* s0_name);

  double saturation(double s, double s0) const {
    return scale > 0.0 ? 1.0 - (1.0 - s0) * std::exp(s / scale) : s0;
  }
  double slope(double s, double s0) const {
    return scale > 0.0 ? -(1.0 - s0) * std::exp(s / scale) / scale : 0.0;
  }
  double curvature(double s, double s0) const {
    return scale > 0.0 ? -(1.0 - s0) * std::exp(s / scale) / (scale * scale) : 0.0;
  }
};

/// S_l, dS/ds [1/Pa] and S_e at one suction (each law's saturation_and_slope).
struct SaturationValues {
  double s_l, ds, se;
};

struct LinearRetention {
  double a_s;    // [1/Pa]
  double s_min;  // residual degree of saturation [-]

  /// Validated construction; throws ParameterError naming "a_s" or "residual_saturation".
  static LinearRetention create(double a_s, double s_min);

  double saturation(double s) const { return s <= 0.0 ? 1.0 : std::max(s_min, 1.0 - a_s * s); }
  /// -a_s where 0 < s and 1 - a_s s > s_min; 0 in the saturated and residual (clamped) parts.
  double d_saturation(double s) const { return (s <= 0.0 || 1.0 - a_s * s <= s_min) ? 0.0 : -a_s; }
  SaturationValues saturation_and_slope(double s) const {
    const double s_l = saturation(s);
    return {s_l, d_saturation(s), (s_l - s_min) / (1.0 - s_min)};
  }
  double effective_saturation(double s) const { return (saturation(s) - s_min) / (1.0 - s_min); }
  double d_effective_saturation(double s) const { return d_saturation(s) / (1.0 - s_min); }
  /// 0: the law is piecewise linear. At its kinks (s = 0, and s = (1 - s_min)/a_s where S reaches
  /// s_min) the true second derivative is a Dirac delta from the slope's jump, which a Jacobian
  /// cannot use; there this returns the one-sided value, 0, as on either side.
  double d2_saturation(double /*s*/) const { return 0.0; }
  double d2_effective_saturation(double /*s*/) const { return 0.0; }
};

struct VanGenuchten {
  double p0;               // air-entry-like scale P0 [Pa]
  double lambda;           // shape parameter [-]
  double s_min;            // residual degree of saturation [-]
  double s_max;            // maximum degree of saturation [-]
  OccludedGas occluded{};  // the branch s < 0 where s_max < 1

  /// Validated construction; throws ParameterError naming "p0", "lambda", "max_saturation",
  /// "residual_saturation" or "occluded_gas_scale".
  static VanGenuchten create(double p0, double lambda, double s_min, double s_max,
                             double occluded_gas_scale = 0.0);

  double effective_saturation(double s) const {
    if (s <= 0.0) return 1.0;
    return se_of(x_of(s));
  }
  /// dS_e/ds = -lambda m S_e [x / (1 + x)] / s with x = (s/P0)^m. Written with x / (1 + x) in
  /// [0, 1] so that neither an underflowing nor an overflowing x gives NaN; -> 0 as s -> 0+.
  double d_effective_saturation(double s) const {
    if (s <= 0.0) return 0.0;
    const double m = 1.0 / (1.0 - lambda);
    const double x = x_of(s);
    const double x_ratio = x < 1.0 ? x / (1.0 + x) : 1.0 / (1.0 + 1.0 / x);
    return -lambda * m * se_of(x) * x_ratio / s;
  }
  /// d^2S_e/ds^2 (header comment). For x >= 1 the factors x/(1 + x) and (x - lambda)/(1 + x) are
  /// written in 1/x, as in d_effective_saturation, so an overflowing x gives no NaN. For x < 1 the
  /// magnitude is formed from logarithms: neither s/P0 nor s^2 underflows at tiny s, so it keeps
  /// growing (m < 2) instead of collapsing to 0 or 0/0, and it is capped at DBL_MAX only where
  /// the true value leaves the doubles.
  double d2_effective_saturation(double s) const {
    if (s <= 0.0) return 0.0;
    const double m = 1.0 / (1.0 - lambda);
    const double x = x_of(s);
    const double front = lambda * m * m * se_of(x);  // lambda m^2 S_e
    if (x >= 1.0) {
      const double x_ratio = 1.0 / (1.0 + 1.0 / x);
      return front * (1.0 - lambda / x) * x_ratio * x_ratio / s / s;
    }
    // front (x - lambda)/(1 + x)^2 times x/s^2 = exp(m log(s/P0) - 2 log s); log 0 = -inf at the
    // inflection gives exp(-inf) = 0.
    const double coefficient = front * (x - lambda) / ((1.0 + x) * (1.0 + x));
    const double log_s = std::log(s);
    const double magnitude =
        std::exp(std::log(std::abs(coefficient)) + m * (log_s - std::log(p0)) - 2.0 * log_s);
    return std::copysign(std::min(magnitude, std::numeric_limits<double>::max()), coefficient);
  }
  double saturation(double s) const {
    return s <= 0.0 ? occluded.saturation(s, s_max)
                    : s_min + (s_max - s_min) * effective_saturation(s);
  }
  double d_saturation(double s) const {
    return s <= 0.0 ? occluded.slope(s, s_max) : (s_max - s_min) * d_effective_saturation(s);
  }
  /// {saturation(s), d_saturation(s)}, bit for bit, with x and (1 + x)^(-lambda) taken once.
  SaturationValues saturation_and_slope(double s) const {
    if (s <= 0.0) return {saturation(s), d_saturation(s), 1.0};
    const double m = 1.0 / (1.0 - lambda);
    const double x = x_of(s);
    const double se = se_of(x);
    const double x_ratio = x < 1.0 ? x / (1.0 + x) : 1.0 / (1.0 + 1.0 / x);
    return {s_min + (s_max - s_min) * se, (s_max - s_min) * (-lambda * m * se * x_ratio / s), se};
  }
  double d2_saturation(double s) const {
    return s <= 0.0 ? occluded.curvature(s, s_max) : (s_max - s_min) * d2_effective_saturation(s);
  }

  /// x = (s/P0)^m and S_e = (1 + x)^(-lambda). For lambda = 1/2 (van Genuchten's n = 2; m = 2)
  /// by a product and a square root: within an ulp or two of pow's, and about eight times
  /// quicker than the two pows, which were a tenth of the embankment's run time
  /// (docs/performance.md). Any other lambda through pow.
  double x_of(double s) const {
    const double r = s / p0;
    return lambda == 0.5 ? r * r : std::pow(r, 1.0 / (1.0 - lambda));
  }
  double se_of(double x) const {
    return lambda == 0.5 ? 1.0 / std::sqrt(1.0 + x) : std::pow(1.0 + x, -lambda);
  }
};

/// A measured retention curve: S_l at suctions s_0 = 0 < s_1 < ... [Pa], non-increasing, in
/// [0, 1], through a monotone cubic (monotone_table.hpp); S_max = S(0), S_min = S(s_last) (held
/// beyond it), S_max - S_min >= 0.01 so that S_e = (S - S_min)/(S_max - S_min) is meaningful.
/// At s <= 0: S_e = 1, and S_max's occluded-gas branch (OccludedGas) as for van Genuchten.
struct TabulatedRetention {
  MonotoneTable table;
  OccludedGas occluded{};  // the branch s < 0 where S(0) < 1

  /// Validated construction, without give (`occluded` is set apart: OccludedGas::create); throws
  /// ParameterError naming "points[k]" (or "points").
  static TabulatedRetention create(const std::vector<std::array<double, 2>>& points);

  double saturation(double s) const {
    return s <= 0.0 ? occluded.saturation(s, table.front()) : table.value(s);
  }
  double d_saturation(double s) const {
    return s <= 0.0 ? occluded.slope(s, table.front()) : table.slope(s);
  }
  double d2_saturation(double s) const {
    return s <= 0.0 ? occluded.curvature(s, table.front()) : table.curvature(s);
  }
  SaturationValues saturation_and_slope(double s) const {
    return {saturation(s), d_saturation(s), effective_saturation(s)};
  }
  double effective_saturation(double s) const {
    return s <= 0.0 ? 1.0 : (table.value(s) - table.back()) / (table.front() - table.back());
  }
  double d_effective_saturation(double s) const {
    return s <= 0.0 ? 0.0 : table.slope(s) / (table.front() - table.back());
  }
  double d2_effective_saturation(double s) const {
    return s <= 0.0 ? 0.0 : table.curvature(s) / (table.front() - table.back());
  }
};

using RetentionCurve = std::variant<LinearRetention, VanGenuchten, TabulatedRetention>;

}  // namespace unsatmpm::physics

// Suction-dependent Mohr-Coulomb strength (Yerro, Alonso & Pinyol, eqs. 13-14; docs/models.md):
//   c(s)   = c' + dc_max (1 - exp(-B s / P_atm))                     (13)
//   phi(s) = min(phi' + A s / P_atm, phi_cap),  phi_cap = max(89 deg, phi')  (14, capped)
//   psi(s) = psi' (the dilatancy does not change; psi' <= phi' <= phi(s))
//   t(s)   = min(t', c(s) / tan phi(s))  (tension cut-off)
// s is the suction [Pa]; s <= 0 (saturated) is treated as s = 0. P_atm = 101325 Pa.
//
// Units and ranges (checked by create): c' [Pa] >= 0, dc_max [Pa] >= 0, B [-] >= 0,
// phi' [rad] in (0, pi/2), A [rad per atmosphere of suction] >= 0, psi' [rad] in [0, phi'],
// t' [Pa] >= 0 or +infinity (the cut-off at the cone's apex at every suction), all others finite.
// The paper's A = 0.1 is read as 0.1 degree per atmosphere (the paper calls its effect small). The
// case input is to give A in degrees per atmosphere, like the paper, and the input layer converts
// it to radians as it does every angle: this struct holds radians only.
//
// Choices the paper leaves open, made here:
// - The cap: eq. 14 grows without bound, so phi(s) is held at 89 deg (or at phi' if phi' is
//   already above that) so that the strength stays a valid Mohr-Coulomb strength for any suction.
//   With the paper's embankment values (phi' = 20 deg, A = 0.1 deg) the cap is reached at
//   s = 690 P_atm = 69.9 MPa, far beyond the 0.8 MPa of the case.
// - The tension cut-off: t' is the input tensile strength, limited at each suction by the apex of
//   the Mohr-Coulomb cone, c(s) cot phi(s), which MohrCoulomb requires (t <= c cot phi). t(s) is
//   constant at t' while the apex stays above it. The apex itself is not monotone: c saturates at
//   c' + dc_max while phi keeps growing, so c(s) cot phi(s) rises and then falls (paper values:
//   2.75 kPa at s = 0, a peak of 42.05 kPa at s = 0.69 MPa, 41.99 kPa at 0.8 MPa, back to 2.75 kPa
//   near 61 MPa and 0.28 kPa at the cap). A t' above the apex therefore follows that fall.
// - Derivatives at s <= 0 are 0 (the saturated branch, as in retention.hpp), not the one-sided
//   values at 0+; d_friction_angle is 0 at and beyond the cap.
// MohrCoulomb takes the strength per call, so at(s) evaluated with each point's current suction
// makes wetting shrink the yield surface step by step.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>

#include "physics/mohr_coulomb.hpp"

namespace unsatmpm::physics {

struct SuctionStrength {
  static constexpr double atmospheric_pressure = 101325.0;                       // P_atm [Pa]
  static constexpr double friction_angle_cap = 89.0 * std::numbers::pi / 180.0;  // [rad]

  double cohesion;           // c' [Pa] >= 0, saturated cohesion
  double cohesion_increase;  // dc_max [Pa] >= 0, cohesion gained from saturated to dry
  double cohesion_rate;      // B [-] >= 0
  double friction_angle;     // phi' [rad] in (0, pi/2), saturated friction angle
  double friction_increase;  // A [rad per atmosphere of suction] >= 0
  double dilatancy_angle;    // psi' [rad] in [0, phi']
  double tensile_strength;   // t' [Pa] >= 0

  /// Validated construction; throws ParameterError naming the parameter ("cohesion",
  /// "cohesion_increase", "cohesion_rate", "friction_angle", "friction_increase",
  /// "dilatancy_angle", "tensile_strength") and its valid range.
  static SuctionStrength create(double cohesion, double cohesion_increase, double cohesion_rate,
                                double friction_angle, double friction_increase,
                                double dilatancy_angle, double tensile_strength);

  /// c(s) [Pa], eq. 13; expm1 keeps the small-suction increase accurate.
  double cohesion_at(double s) const {
    return cohesion -
           cohesion_increase * std::expm1(-cohesion_rate * std::max(s, 0.0) / atmospheric_pressure);
  }
  /// dc/ds [Pa/Pa]; 0 for s <= 0.
  double d_cohesion(double s) const {
    if (s <= 0.0) return 0.0;
    const double rate = cohesion_rate / atmospheric_pressure;
    return cohesion_increase * rate * std::exp(-rate * s);
  }
  /// phi(s) [rad], eq. 14 held at the cap.
  double friction_angle_at(double s) const {
    const double cap = std::max(friction_angle_cap, friction_angle);
    return std::min(friction_angle + friction_increase * std::max(s, 0.0) / atmospheric_pressure,
                    cap);
  }
  /// dphi/ds [rad/Pa]; 0 for s <= 0 and at or beyond the cap.
  double d_friction_angle(double s) const {
    if (s <= 0.0) return 0.0;
    const double cap = std::max(friction_angle_cap, friction_angle);
    const double uncapped = friction_angle + friction_increase * s / atmospheric_pressure;
    return uncapped < cap ? friction_increase / atmospheric_pressure : 0.0;
  }
  /// t(s) = min(t', c(s) cot phi(s)) [Pa].
  double tensile_strength_at(double s) const {
    return std::min(tensile_strength, cohesion_at(s) / std::tan(friction_angle_at(s)));
  }

  /// The Mohr-Coulomb strength at suction s: passes MohrCoulomb::validate for any s.
  MohrCoulombStrength at(double s) const {
    const double c = cohesion_at(s);
    const double phi = friction_angle_at(s);
    return {c, phi, dilatancy_angle, std::min(tensile_strength, c / std::tan(phi))};
  }
};

/// Mohr-Coulomb in net stress with the strength of the current suction (docs/models.md): the model
/// a three-phase material selects with `suction_strength`. `saturated` holds the elasticity and the
/// strength at s = 0; every update evaluates strength.at(s) for the point's suction s [Pa], so the
/// return mapping brings a stress outside the wetted (smaller) surface back onto it.
struct SuctionMohrCoulomb {
  MohrCoulomb saturated;
  SuctionStrength strength;

  /// Validated construction (the elasticity, then the strength; ParameterError names the key).
  static SuctionMohrCoulomb create(const LinearElastic& elastic, const SuctionStrength& strength) {
    return {MohrCoulomb::create(elastic, strength.at(0.0)), strength};
  }
  const LinearElastic& elastic() const { return saturated.elastic; }

  MohrCoulombReturn update(const Vec6& d_eps, double suction, Vec6& sigma,
                           MohrCoulombState& state) const {
    return saturated.update(d_eps, strength.at(suction), sigma, state);
  }
  /// The strength at suction s [Pa], prepared for update (MohrCoulomb::prepare).
  PreparedStrength prepared(double s) const { return MohrCoulomb::prepare(strength.at(s)); }
  /// The update with a strength prepared at the point's suction.
  MohrCoulombReturn update(const Vec6& d_eps, const PreparedStrength& at_suction, Vec6& sigma,
                           MohrCoulombState& state) const {
    return saturated.update(d_eps, at_suction, sigma, state);
  }
};

}  // namespace unsatmpm::physics

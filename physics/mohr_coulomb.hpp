// Mohr-Coulomb elasto-plasticity with a tension cut-off, non-associated flow, and a return
// mapping in principal stresses (face, edge and apex returns).
//
// Yield surface (tension positive, principal stresses s1 >= s2 >= s3):
//   f = (s1 - s3) + (s1 + s3) sin(phi) - 2 c cos(phi) <= 0
// Plastic potential: the same with the dilatancy angle psi in place of phi.
// Tension cut-off: s1 <= t (t = tensile strength [Pa], 0 <= t <= c / tan(phi)).
// Strength (c, phi, psi, t) is passed with every call so that a suction-dependent strength
// (eqs. 13-14 of the paper; physics/suction_strength.hpp) changes the surface step by step without
// changing this model. Reference: de Souza Neto, Peric & Owen, Computational Methods for Plasticity
// (2008), §8.2.
#pragma once

#include "physics/linear_elastic.hpp"
#include "physics/voigt.hpp"

namespace unsatmpm::physics {

/// Current strength of a Mohr-Coulomb material. Angles in radians, stresses in Pa.
struct MohrCoulombStrength {
  double cohesion;          // c [Pa] >= 0
  double friction_angle;    // phi [rad], in (0, pi/2)
  double dilatancy_angle;   // psi [rad], in [0, phi]
  double tensile_strength;  // t [Pa], in [0, c / tan(phi)]
};

/// A strength with what every update needs of it evaluated once (MohrCoulomb::prepare): its
/// trigonometry. A point whose strength holds over many steps (the main cycle holds the suction
/// over a coupling interval) then pays for it once.
struct PreparedStrength {
  MohrCoulombStrength strength;
  double sin_phi, sin_psi;  // of the friction and dilatancy angles
  double k;                 // 2 c cos(phi) [Pa]
  double apex;              // c cot(phi) [Pa]: hydrostatic stress of the Mohr-Coulomb apex
  bool cut_off;             // the cut-off bites, t < c cot(phi)
  double j2_factor;         // (2 + sin(phi) / sqrt(3))^2, of the elastic pre-check
};

/// Which return the last stress update took.
enum class MohrCoulombReturn { elastic, face, edge_left, edge_right, apex, tension };

/// Per-point history of the model.
struct MohrCoulombState {
  double deviatoric_plastic_strain = 0.0;  // accumulated sqrt(2/3 de_p:de_p) [-]
};

struct MohrCoulomb {
  LinearElastic elastic;
  MohrCoulombStrength strength;

  /// Validated construction; throws ParameterError naming the offending parameter and range.
  static MohrCoulomb create(const LinearElastic& elastic, const MohrCoulombStrength& strength);
  /// Validates a strength on its own (used when strength changes with suction).
  static void validate(const MohrCoulombStrength& strength);

  /// Yield function value [Pa] of a stress for a given strength (max over the MC faces and the
  /// tension cut-off, each scaled to stress units). <= 0 inside the elastic domain.
  static double yield_function(const Vec6& sigma, const MohrCoulombStrength& strength);

  /// The strength with its trigonometry evaluated.
  static PreparedStrength prepare(const MohrCoulombStrength& strength);

  /// Stress update for a strain increment: elastic predictor, return mapping in principal
  /// stresses. Updates sigma and state in place; returns the region of the return.
  MohrCoulombReturn update(const Vec6& d_eps, const PreparedStrength& current, Vec6& sigma,
                           MohrCoulombState& state) const;
  MohrCoulombReturn update(const Vec6& d_eps, const MohrCoulombStrength& current, Vec6& sigma,
                           MohrCoulombState& state) const {
    return update(d_eps, prepare(current), sigma, state);
  }
  MohrCoulombReturn update(const Vec6& d_eps, Vec6& sigma, MohrCoulombState& state) const {
    return update(d_eps, strength, sigma, state);
  }

  /// Consistent (algorithmic) tangent d sigma_{n+1} / d d_eps of `update`, at the given
  /// start stress and increment, for the current strength. Equals the elastic stiffness when the
  /// step is elastic.
  Mat6 consistent_tangent(const Vec6& sigma_n, const Vec6& d_eps,
                          const MohrCoulombStrength& current) const;
};

}  // namespace unsatmpm::physics

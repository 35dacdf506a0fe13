// Isotropic linear elasticity in incremental form: d_sigma = D d_eps (docs/models.md).
//
// Parameters: Young's modulus E [Pa] > 0, Poisson's ratio nu in [0, 0.5). Stress [Pa] tension
// positive, strain increments in Voigt form with engineering shear. No history variables.
#pragma once

#include "physics/voigt.hpp"

namespace unsatmpm::physics {

struct LinearElastic {
  double young_modulus;  // E [Pa]
  double poisson_ratio;  // nu [-]

  /// Validated construction; throws ParameterError naming the parameter and its range.
  static LinearElastic create(double young_modulus, double poisson_ratio);

  double shear_modulus() const { return young_modulus / (2.0 * (1.0 + poisson_ratio)); }
  double bulk_modulus() const { return young_modulus / (3.0 * (1.0 - 2.0 * poisson_ratio)); }
  double lame_lambda() const {
    return young_modulus * poisson_ratio / ((1.0 + poisson_ratio) * (1.0 - 2.0 * poisson_ratio));
  }
  /// Oedometric (constrained) modulus K + 4G/3 [Pa]: sets the P-wave speed for the CFL limit.
  double constrained_modulus() const { return lame_lambda() + 2.0 * shear_modulus(); }

  /// The 6x6 elastic stiffness D [Pa] (engineering shear strain).
  Mat6 stiffness() const;

  /// sigma += D d_eps, written out for isotropy (no 6x6 product in the hot loop).
  void add_elastic_increment(const Vec6& d_eps, Vec6& sigma) const {
    const double lambda = lame_lambda(), g = shear_modulus();
    const double tr = d_eps[0] + d_eps[1] + d_eps[2];
    sigma[0] += lambda * tr + 2.0 * g * d_eps[0];
    sigma[1] += lambda * tr + 2.0 * g * d_eps[1];
    sigma[2] += lambda * tr + 2.0 * g * d_eps[2];
    sigma[3] += g * d_eps[3];
    sigma[4] += g * d_eps[4];
    sigma[5] += g * d_eps[5];
  }
};

}  // namespace unsatmpm::physics

// Principal stresses and directions of a Voigt stress (physics/voigt.hpp), sorted descending.
//
// A stress without out-of-plane shear (sigma_yz = sigma_zx = 0: every 2D plane-strain and 1D
// stress) has sigma_zz as a principal stress along z and the in-plane pair in closed form:
// with c = (sigma_xx + sigma_yy)/2, h = (sigma_xx - sigma_yy)/2 and r = sqrt(h^2 + sigma_xy^2), the
// values c +- r, and the major direction (h + r, sigma_xy) for h >= 0, (sigma_xy, r - h) for h < 0
// (each a row of A - (c + r) I turned by 90 degrees, of norm at least r, so never a difference of
// near-equal numbers); the minor direction is the major one turned by 90 degrees. Any other stress
// goes to Eigen's iterative solver, which keeps orthonormal vectors for repeated values. The closed
// form costs two square roots where the iterative solver cost 12 % of the embankment's
// sliding phase (docs/performance.md).
#pragma once

#include "physics/voigt.hpp"

namespace unsatmpm::physics {

/// Principal stresses s1 >= s2 >= s3 [Pa] and their unit directions as matching columns of an
/// orthonormal matrix.
struct Principal {
  Vec3 values;
  Mat3 vectors;
};

Principal principal_stresses(const Vec6& sigma);

}  // namespace unsatmpm::physics

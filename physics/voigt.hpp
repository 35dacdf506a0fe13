// Voigt notation shared by every constitutive model.
//
// Order xx, yy, zz, xy, yz, zx (docs/conventions.md). Stress components are plain tensor components
// [Pa]; strain vectors carry engineering shear (gamma_xy = 2 eps_xy) so that sigma . eps is the
// work. Tension is positive. Every dimension (1D column, 2D plane strain, 3D) uses the full six
// components: plane strain and uniaxial strain still have a non-zero sigma_zz.
#pragma once

#include <Eigen/Core>
#include <cmath>

namespace unsatmpm::physics {

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;
using Mat3 = Eigen::Matrix3d;
using Vec3 = Eigen::Vector3d;

/// Symmetric stress tensor from a Voigt stress vector.
inline Mat3 stress_tensor(const Vec6& s) {
  Mat3 t;
  t << s[0], s[3], s[5],  //
      s[3], s[1], s[4],   //
      s[5], s[4], s[2];
  return t;
}

/// Voigt stress vector from a symmetric stress tensor (upper triangle read).
inline Vec6 stress_voigt(const Mat3& t) {
  Vec6 s;
  s << t(0, 0), t(1, 1), t(2, 2), t(0, 1), t(1, 2), t(0, 2);
  return s;
}

/// Voigt strain vector (engineering shear) from a symmetric strain tensor.
inline Vec6 strain_voigt(const Mat3& e) {
  Vec6 v;
  v << e(0, 0), e(1, 1), e(2, 2), 2.0 * e(0, 1), 2.0 * e(1, 2), 2.0 * e(0, 2);
  return v;
}

/// Symmetric strain tensor from a Voigt strain vector (engineering shear).
inline Mat3 strain_tensor(const Vec6& v) {
  Mat3 e;
  e << v[0], 0.5 * v[3], 0.5 * v[5],  //
      0.5 * v[3], v[1], 0.5 * v[4],   //
      0.5 * v[5], 0.5 * v[4], v[2];
  return e;
}

/// Mean stress p = tr(sigma)/3 [Pa], tension positive.
inline double mean_stress(const Vec6& s) { return (s[0] + s[1] + s[2]) / 3.0; }

/// The deviatoric stress's second invariant J2 = s:s / 2 [Pa^2].
inline double second_invariant(const Vec6& s) {
  const double p = mean_stress(s);
  const double dx = s[0] - p, dy = s[1] - p, dz = s[2] - p;
  return 0.5 * (dx * dx + dy * dy + dz * dz) + s[3] * s[3] + s[4] * s[4] + s[5] * s[5];
}

/// Von Mises equivalent q = sqrt(3 J2) [Pa].
inline double von_mises(const Vec6& s) { return std::sqrt(3.0 * second_invariant(s)); }

/// Equivalent deviatoric strain sqrt(2/3 e:e) of a Voigt strain increment (engineering shear).
inline double deviatoric_strain_norm(const Vec6& e) {
  const double v = (e[0] + e[1] + e[2]) / 3.0;
  const double dx = e[0] - v, dy = e[1] - v, dz = e[2] - v;
  const double ee = dx * dx + dy * dy + dz * dz + 0.5 * (e[3] * e[3] + e[4] * e[4] + e[5] * e[5]);
  return std::sqrt(2.0 / 3.0 * ee);
}

}  // namespace unsatmpm::physics

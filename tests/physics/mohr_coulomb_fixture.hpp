// Shared by the Mohr-Coulomb tests (test_mohr_coulomb.cpp, test_mohr_coulomb_returns.cpp): the
// elasticity and strengths, the return regions' cases, rotations, and the checks' helpers.
#pragma once

#include "physics/mohr_coulomb.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/QR>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <ostream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "physics/parameter_error.hpp"

namespace unsatmpm::physics {

inline void PrintTo(MohrCoulombReturn r, std::ostream* os) {
  constexpr std::array<const char*, 6> kNames{"elastic",    "face", "edge_left",
                                              "edge_right", "apex", "tension"};
  *os << kNames[static_cast<int>(r)];
}

namespace test_mohr_coulomb {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kKpa = 1e3;

const LinearElastic kElastic{20e6, 0.3};
// c = 10 kPa, phi = 30 deg, psi = 10 deg: the apex is at c cot(phi) = 17.3 kPa, above t = 5 kPa.
const MohrCoulombStrength kStrength{10e3, 30 * kDeg, 10 * kDeg, 5e3};
// The same with the cut-off at the apex, where it never bites: the pure Mohr-Coulomb cone.
const MohrCoulombStrength kNoCutOff{10e3, 30 * kDeg, 10 * kDeg, 10e3 / std::tan(30 * kDeg)};

// Flow directions (potential gradients) in sorted principal space, s1 >= s2 >= s3.
enum Flow { kMain, kRight, kLeft, kTension1, kTension2, kTension3 };

inline Vec3 flow_direction(Flow flow, double psi) {
  const double s = std::sin(psi);
  switch (flow) {
    case kMain:
      return Vec3(1 + s, 0, -(1 - s));
    case kRight:
      return Vec3(1 + s, -(1 - s), 0);
    case kLeft:
      return Vec3(0, 1 + s, -(1 - s));
    case kTension1:
      return Vec3::Unit(0);
    case kTension2:
      return Vec3::Unit(1);
    case kTension3:
      return Vec3::Unit(2);
  }
  return Vec3::Zero();
}

struct RegionCase {
  const char* name;
  Vec3 trial;  // principal trial stresses [kPa], sorted
  MohrCoulombReturn region;
  const MohrCoulombStrength* strength;
  std::vector<Flow> flows;  // potentials of the active planes (none for elastic and apex)
};

inline void PrintTo(const RegionCase& c, std::ostream* os) { *os << c.name; }

inline const std::vector<RegionCase>& region_cases() {
  static const std::vector<RegionCase> cases{
      {"elastic", {-20, -40, -60}, MohrCoulombReturn::elastic, &kStrength, {}},
      {"face", {-10, -50, -100}, MohrCoulombReturn::face, &kStrength, {kMain}},
      {"face_deep", {4, -30, -80}, MohrCoulombReturn::face, &kStrength, {kMain}},
      {"edge_right", {-10, -95, -100}, MohrCoulombReturn::edge_right, &kStrength, {kMain, kRight}},
      {"edge_left", {-10, -15, -100}, MohrCoulombReturn::edge_left, &kStrength, {kMain, kLeft}},
      {"apex", {50, 45, 40}, MohrCoulombReturn::apex, &kNoCutOff, {}},
      {"apex_deviatoric", {40, 20, 10}, MohrCoulombReturn::apex, &kNoCutOff, {}},
      {"tension_plane", {12, 0, -10}, MohrCoulombReturn::tension, &kStrength, {kTension1}},
      {"tension_line",
       {10, 8, -10},
       MohrCoulombReturn::tension,
       &kStrength,
       {kTension1, kTension2}},
      {"tension_apex",
       {14, 12, 10},
       MohrCoulombReturn::tension,
       &kStrength,
       {kTension1, kTension2, kTension3}},
      {"tension_face_line",
       {22, -8, -14},
       MohrCoulombReturn::tension,
       &kStrength,
       {kTension1, kMain}},
      {"tension_right_corner",
       {28, -13, -15},
       MohrCoulombReturn::tension,
       &kStrength,
       {kTension1, kMain, kRight}},
      {"tension_left_corner",
       {28, 18, -30},
       MohrCoulombReturn::tension,
       &kStrength,
       {kTension1, kTension2, kMain, kLeft}},
  };
  return cases;
}

inline Mat3 rotation(double angle, const Vec3& axis) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

inline Vec6 rotate_stress(const Mat3& r, const Vec6& s) {
  return stress_voigt(r * stress_tensor(s) * r.transpose());
}

inline Vec6 rotate_strain(const Mat3& r, const Vec6& e) {
  return strain_voigt(r * strain_tensor(e) * r.transpose());
}

// Principal axes of the trial stress: a generic rotation, so that every Voigt component is used.
const Mat3 kAxes = rotation(0.7, Vec3(1, 2, 3)) * rotation(0.4, Vec3(-2, 1, 0.5));
const Vec6 kStrainIncrement = (Vec6() << 1.0, -2.0, 0.5, 1.5, -0.7, 0.9).finished() * 1e-4;

/// A step whose trial stress is kAxes diag(trial) kAxes^T: sigma_n = trial - D d_eps.
struct Step {
  Vec6 sigma_n;
  Vec6 d_eps;
  Vec6 trial;
};

inline Step make_step(const RegionCase& c) {
  Step step;
  step.d_eps = kStrainIncrement;
  Vec6 principal = Vec6::Zero();
  principal.head<3>() = c.trial * kKpa;
  step.trial = rotate_stress(kAxes, principal);
  step.sigma_n = step.trial - kElastic.stiffness() * step.d_eps;
  return step;
}

struct Result {
  MohrCoulombReturn region;
  Vec6 sigma;
  MohrCoulombState state;
};

inline Result run(const MohrCoulomb& model, const MohrCoulombStrength& strength,
                  const Vec6& sigma_n, const Vec6& d_eps, double history = 0.0) {
  Result r{MohrCoulombReturn::elastic, sigma_n, MohrCoulombState{history}};
  r.region = model.update(d_eps, strength, r.sigma, r.state);
  return r;
}

inline double stress_scale(const Vec6& s) { return s.cwiseAbs().maxCoeff(); }

/// Plastic strain increment d_eps - D^-1 d_sigma (Voigt, engineering shear).
inline Vec6 plastic_strain(const Step& step, const Vec6& sigma) {
  return step.d_eps - kElastic.stiffness().inverse() * (sigma - step.sigma_n);
}

/// Nonnegative combination of the given directions equal to v, if one exists (up to tol).
inline bool in_cone(const Vec3& v, const std::vector<Vec3>& generators, double tol) {
  const int n = static_cast<int>(generators.size());
  const int m = std::min(n, 3);
  // Every subset of m generators (n <= 4 here).
  for (int skip = 0; skip < (n > 3 ? n : 1); ++skip) {
    Eigen::Matrix<double, 3, Eigen::Dynamic> g(3, m);
    for (int i = 0, j = 0; i < n; ++i) {
      if (n > 3 && i == skip) continue;
      g.col(j++) = generators[i];
    }
    const Eigen::VectorXd coef = g.colPivHouseholderQr().solve(v);
    if ((g * coef - v).norm() <= tol * v.norm() && coef.minCoeff() >= -tol * coef.norm()) {
      return true;
    }
  }
  return false;
}

// Error of the tangent relative to the elastic stiffness (the apex tangent is zero).
inline double tangent_error(const Mat6& tangent, const Mat6& reference) {
  return (tangent - reference).cwiseAbs().maxCoeff() / kElastic.stiffness().cwiseAbs().maxCoeff();
}

}  // namespace test_mohr_coulomb
}  // namespace unsatmpm::physics

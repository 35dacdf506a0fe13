// Principal stresses: the closed form for stresses without out-of-plane shear against Eigen's
// iterative solver, and both forms' properties (sorted values, orthonormal directions, the stress
// rebuilt), including repeated and zero values and a shear far below the normal stresses.

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <random>
#include <vector>

#include "physics/principal_stress.hpp"

namespace unsatmpm::physics {
namespace {

double scale_of(const Vec6& s) { return std::max(s.cwiseAbs().maxCoeff(), 1e-300); }

// Sorted descending, orthonormal, and Q diag(values) Q^T = sigma, each to rounding of the scale.
void expect_decomposition(const Vec6& sigma) {
  const Principal p = principal_stresses(sigma);
  const double scale = scale_of(sigma);
  EXPECT_GE(p.values[0], p.values[1]);
  EXPECT_GE(p.values[1], p.values[2]);
  EXPECT_LE((p.vectors.transpose() * p.vectors - Mat3::Identity()).cwiseAbs().maxCoeff(), 1e-14)
      << sigma.transpose();
  const Mat3 rebuilt = p.vectors * p.values.asDiagonal() * p.vectors.transpose();
  EXPECT_LE((rebuilt - stress_tensor(sigma)).cwiseAbs().maxCoeff(), 1e-14 * scale)
      << sigma.transpose();
  const Vec3 reference =
      Eigen::SelfAdjointEigenSolver<Mat3>(stress_tensor(sigma), Eigen::EigenvaluesOnly)
          .eigenvalues()
          .reverse();
  EXPECT_LE((p.values - reference).cwiseAbs().maxCoeff(), 1e-14 * scale) << sigma.transpose();
}

TEST(PrincipalStress, PlaneStressesAgreeWithTheIterativeSolver) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1e5, 1e5);
  for (int i = 0; i < 20000; ++i) {
    const Vec6 sigma = (Vec6() << u(rng), u(rng), u(rng), u(rng), 0, 0).finished();
    expect_decomposition(sigma);
  }
}

TEST(PrincipalStress, RepeatedZeroAndNearlyDiagonalStresses) {
  const std::vector<Vec6> cases = {
      Vec6::Zero(),
      (Vec6() << -5e4, -5e4, -5e4, 0, 0, 0).finished(),         // isotropic
      (Vec6() << -5e4, -5e4, -2e4, 0, 0, 0).finished(),         // in-plane pair repeated
      (Vec6() << -2e4, -5e4, -2e4, 0, 0, 0).finished(),         // sigma_zz equal to one
      (Vec6() << -3e4, -1e4, -2e4, 1e4, 0, 0).finished(),       // sigma_zz equal to c
      (Vec6() << -1e8, -1e8 + 1e-3, 0, 1e-6, 0, 0).finished(),  // shear far below the scale
      (Vec6() << 1e-3, -1e8, -1e8, -1e-9, 0, 0).finished(),
      (Vec6() << 7.0, -3.0, 1.0, 0.0, 0, 0).finished(),  // already diagonal, h > 0
      (Vec6() << -3.0, 7.0, 1.0, 0.0, 0, 0).finished(),  // already diagonal, h < 0
      (Vec6() << 2.0, 2.0, 1.0, 3.0, 0, 0).finished(),   // h = 0: pure shear about c
  };
  for (const Vec6& sigma : cases) expect_decomposition(sigma);
}

TEST(PrincipalStress, DiagonalStressesKeepTheirAxes) {
  const Principal p = principal_stresses((Vec6() << -3.0, 7.0, 1.0, 0, 0, 0).finished());
  EXPECT_EQ(p.values, Vec3(7.0, 1.0, -3.0));
  EXPECT_EQ(p.vectors.col(0).cwiseAbs(), Vec3::UnitY());
  EXPECT_EQ(p.vectors.col(1).cwiseAbs(), Vec3::UnitZ());
  EXPECT_EQ(p.vectors.col(2).cwiseAbs(), Vec3::UnitX());
}

TEST(PrincipalStress, OutOfPlaneShearTakesTheGeneralSolver) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1e5, 1e5);
  for (int i = 0; i < 2000; ++i) {
    const Vec6 sigma = (Vec6() << u(rng), u(rng), u(rng), u(rng), u(rng), u(rng)).finished();
    expect_decomposition(sigma);
  }
  // A shear in the y-z plane alone: x is a principal direction, the y-z pair is not along axes.
  const Principal p = principal_stresses((Vec6() << 0.0, 1.0, 1.0, 0, 1.0, 0).finished());
  EXPECT_NEAR(p.values[0], 2.0, 1e-15);
  EXPECT_NEAR(std::abs(p.vectors(1, 0)), std::sqrt(0.5), 1e-15);
}

}  // namespace
}  // namespace unsatmpm::physics

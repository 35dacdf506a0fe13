#include <gtest/gtest.h>

#include <Eigen/LU>
#include <limits>
#include <numbers>
#include <random>

#include "numerics/explicit_transfers.hpp"
#include "numerics/point_models.hpp"

namespace unsatmpm::numerics {
namespace {

// The written-out 3D Jaumann rotation equals W s - s W formed with tensors.
TEST(Transfers, RotateStress3DMatchesTensorForm) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    physics::Vec6 s;
    for (int k = 0; k < 6; ++k) s[k] = 1e5 * u(rng);
    Eigen::Matrix3d l;
    for (int i = 0; i < 9; ++i) l.data()[i] = 1e-3 * u(rng);
    const Eigen::Matrix3d w = 0.5 * (l - l.transpose());
    const physics::Mat3 t = physics::stress_tensor(s);
    const physics::Vec6 expected = physics::stress_voigt(t + w * t - t * w);
    physics::Vec6 got = s;
    rotate_stress<3>(w, got);
    EXPECT_LT((got - expected).norm(), 1e-9 * s.norm());
    // The 2D form is the 3D one for an in-plane spin and plane stress components.
    physics::Vec6 s2 = s;
    s2[4] = s2[5] = 0.0;
    Eigen::Matrix3d w2 = Eigen::Matrix3d::Zero();
    w2(0, 1) = w(0, 1), w2(1, 0) = w(1, 0);
    physics::Vec6 got2 = s2, want2 = s2;
    rotate_stress<2>(w2.topLeftCorner<2, 2>(), got2);
    rotate_stress<3>(w2, want2);
    EXPECT_LT((got2 - want2).norm(), 1e-9 * s.norm());
  }
}

TEST(Transfers, DeterminantOfIdentityPlus) {
  Eigen::Matrix3d a;
  a << 0.1, -0.2, 0.05, 0.3, -0.1, 0.02, -0.04, 0.07, 0.2;
  EXPECT_NEAR(det_identity_plus<3>(a), (Eigen::Matrix3d::Identity() + a).determinant(), 1e-14);
  const Eigen::Matrix2d b = a.topLeftCorner<2, 2>();
  EXPECT_NEAR(det_identity_plus<2>(b), (Eigen::Matrix2d::Identity() + b).determinant(), 1e-14);
}

// at_apex: true after an apex return (hydrostatic tension on the cone), false after an elastic
// step, a face return, and for an elastic model; an isotropic tension inside the cone (reached
// elastically by a uniform 3D expansion) is not the apex. Wetting (lower suction, lower apex)
// keeps a point at the apex; it counts at the suction of its last update.
TEST(Transfers, AtApexOnlyAfterAnApexReturn) {
  const auto elastic = physics::LinearElastic::create(1e7, 0.3);
  const double deg = std::numbers::pi / 180.0;
  const auto mc = physics::SuctionMohrCoulomb::create(
      elastic, physics::SuctionStrength::create(1e3, 15e3, 0.7, 20 * deg, 0.1 * deg, 0.0,
                                                std::numeric_limits<double>::infinity()));
  const double s = 5e4;
  physics::MohrCoulombState state;
  physics::Vec6 sigma = physics::Vec6::Zero();
  // Small uniform expansion: elastic, isotropic tension below the apex.
  physics::Vec6 d_eps = physics::Vec6::Zero();
  d_eps.head<3>().setConstant(1e-6);
  EXPECT_EQ(mc.update(d_eps, s, sigma, state), physics::MohrCoulombReturn::elastic);
  EXPECT_FALSE(at_apex(mc, sigma, s));
  // Large expansion: apex return.
  d_eps.head<3>().setConstant(1e-2);
  EXPECT_EQ(mc.update(d_eps, s, sigma, state), physics::MohrCoulombReturn::apex);
  EXPECT_TRUE(at_apex(mc, sigma, s));
  EXPECT_TRUE(at_apex(mc, sigma, 0.5 * s));   // wetter: the apex is lower, still at or beyond
  EXPECT_FALSE(at_apex(mc, sigma, 2.0 * s));  // drier: inside the larger cone
  EXPECT_FALSE(at_apex(elastic, sigma, s));
  // Shear under compression: a face return, not hydrostatic.
  sigma = physics::Vec6(-1e5, -1e5, -1e5, 0, 0, 0);
  physics::Vec6 shear = physics::Vec6::Zero();
  shear[3] = 5e-2;
  const auto region = mc.update(shear, s, sigma, state);
  EXPECT_NE(region, physics::MohrCoulombReturn::elastic);
  EXPECT_FALSE(at_apex(mc, sigma, s));
}

}  // namespace
}  // namespace unsatmpm::numerics

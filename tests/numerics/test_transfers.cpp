#include <gtest/gtest.h>

#include <Eigen/LU>
#include <random>

#include "numerics/explicit_transfers.hpp"
#include "numerics/point_models.hpp"

namespace unsatmpm::numerics {
namespace test_transfers {

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

// A point's strength memo serves only the suction it was prepared at: through a sequence of held
// suctions (repeats, changes, returns) the memo path gives the plain path's stress and plastic
// strain bit for bit; a memo that kept a stale strength would leave the point elastic at s = 0.
TEST(StrengthMemo, ServesOnlyTheSuctionItWasPreparedAt) {
  constexpr double deg = 3.14159265358979323846 / 180.0;
  const auto law = physics::SuctionStrength::create(1e3, 15e3, 0.7, 20 * deg, 0.1 * deg, 0.0,
                                                    1e3 / std::tan(20 * deg));
  const auto model = physics::SuctionMohrCoulomb::create(physics::LinearElastic{10e6, 0.33}, law);
  physics::Vec6 a = (physics::Vec6() << -10e3, -30e3, -50e3, 0, 0, 0).finished(), b = a;
  double ea = 0.0, eb = 0.0;
  StrengthMemo memo;
  const physics::Vec6 d_eps = (physics::Vec6() << 2.0, -1.0, 0.5, 1.0, 0, 0).finished() * 1e-6;
  for (const double s : {800e3, 800e3, 0.0, 0.0, 200e3, 800e3, 800e3}) {
    stress_update(model, d_eps, HeldSuction{s, memo}, a, ea);
    stress_update(model, d_eps, s, b, eb);
    EXPECT_TRUE(a == b) << "s = " << s;
    EXPECT_EQ(ea, eb) << "s = " << s;
    EXPECT_EQ(memo.suction, s);
  }
  EXPECT_GT(eb, 0.0);  // the sequence did yield
}

}  // namespace test_transfers
}  // namespace unsatmpm::numerics

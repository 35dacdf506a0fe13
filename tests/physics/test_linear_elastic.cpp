// Isotropic linear elasticity: stiffness properties, the hot-loop increment, construction checks.
#include "physics/linear_elastic.hpp"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <limits>
#include <string>

#include "physics/parameter_error.hpp"

namespace unsatmpm::physics {
namespace test_linear_elastic {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

TEST(LinearElastic, StiffnessIsSymmetricPositiveDefinite) {
  for (const double nu : {0.0, 0.2, 0.3, 0.45, 0.499}) {
    const Mat6 d = LinearElastic::create(20e6, nu).stiffness();
    EXPECT_LE((d - d.transpose()).cwiseAbs().maxCoeff(), 1e-12 * d.cwiseAbs().maxCoeff());
    EXPECT_EQ(d.llt().info(), Eigen::Success) << "not positive definite, nu = " << nu;
  }
}

TEST(LinearElastic, StiffnessMatchesModuli) {
  const LinearElastic e = LinearElastic::create(20e6, 0.3);
  const Mat6 d = e.stiffness();
  EXPECT_NEAR(d(0, 0), e.constrained_modulus(), 1e-6);
  EXPECT_NEAR(d(0, 1), e.lame_lambda(), 1e-6);
  EXPECT_NEAR(d(3, 3), e.shear_modulus(), 1e-6);
  EXPECT_NEAR(e.shear_modulus(), 20e6 / 2.6, 1e-6);
  EXPECT_NEAR(e.bulk_modulus(), 20e6 / 1.2, 1e-6);
  // A uniform volumetric strain gives the bulk modulus; a pure engineering shear gives G.
  const Vec6 volumetric = (Vec6() << 1, 1, 1, 0, 0, 0).finished() * 1e-4;
  EXPECT_NEAR(mean_stress(d * volumetric), 3e-4 * e.bulk_modulus(), 1e-6);
  EXPECT_NEAR((d * Vec6::Unit(4))[4], e.shear_modulus(), 1e-6);
  EXPECT_NEAR((d * Vec6::Unit(4)).head<3>().norm(), 0.0, 1e-9);
}

TEST(LinearElastic, AddElasticIncrementEqualsStiffnessTimesStrain) {
  const LinearElastic e = LinearElastic::create(35e6, 0.27);
  const Vec6 sigma0 = (Vec6() << -1e5, -2e5, -1.5e5, 3e4, -1e4, 2e4).finished();
  const Vec6 d_eps = (Vec6() << 1e-4, -3e-4, 2e-4, 5e-4, -2e-4, 7e-4).finished();
  Vec6 sigma = sigma0;
  e.add_elastic_increment(d_eps, sigma);
  const Vec6 expected = sigma0 + e.stiffness() * d_eps;
  EXPECT_LE((sigma - expected).cwiseAbs().maxCoeff(), 1e-12 * expected.cwiseAbs().maxCoeff());
  // Each component on its own too, so a swapped column is caught.
  for (int k = 0; k < 6; ++k) {
    Vec6 s = Vec6::Zero();
    e.add_elastic_increment(Vec6::Unit(k), s);
    EXPECT_LE((s - e.stiffness().col(k)).cwiseAbs().maxCoeff(), 1e-6) << "component " << k;
  }
}

void expect_rejected(double young_modulus, double poisson_ratio, const std::string& parameter) {
  try {
    LinearElastic::create(young_modulus, poisson_ratio);
    ADD_FAILURE() << "accepted E = " << young_modulus << ", nu = " << poisson_ratio;
  } catch (const ParameterError& error) {
    EXPECT_EQ(error.parameter(), parameter);
    EXPECT_NE(std::string(error.what()).find(parameter), std::string::npos) << error.what();
  }
}

TEST(LinearElastic, CreateRejectsInvalidYoungModulus) {
  EXPECT_THROW(LinearElastic::create(0.0, 0.3), ParameterError);
  for (const double e : {0.0, -1e6, kNaN, kInf, -kInf}) expect_rejected(e, 0.3, "young_modulus");
}

TEST(LinearElastic, CreateRejectsInvalidPoissonRatio) {
  EXPECT_THROW(LinearElastic::create(1e7, 0.5), ParameterError);
  for (const double nu : {-0.1, 0.5, 0.6, kNaN, kInf}) expect_rejected(1e7, nu, "poisson_ratio");
}

TEST(LinearElastic, CreateAcceptsValidParameters) {
  const LinearElastic e = LinearElastic::create(1e7, 0.0);
  EXPECT_EQ(e.young_modulus, 1e7);
  EXPECT_EQ(e.poisson_ratio, 0.0);
  EXPECT_NO_THROW(LinearElastic::create(1e9, 0.499));
}

}  // namespace test_linear_elastic
}  // namespace unsatmpm::physics

// Mohr-Coulomb with tension cut-off: every return region, its consistency (yield, coaxiality, flow
// rule), the consistent tangent against finite differences and invariance under rotation.

#include "mohr_coulomb_fixture.hpp"

namespace unsatmpm::physics::test_mohr_coulomb {

class RegionTest : public testing::TestWithParam<RegionCase> {
 protected:
  const RegionCase& c = GetParam();
  const MohrCoulomb model = MohrCoulomb::create(kElastic, *c.strength);
  const Step step = make_step(c);
};

TEST_P(RegionTest, ReturnsToExpectedRegion) {
  EXPECT_EQ(run(model, *c.strength, step.sigma_n, step.d_eps).region, c.region);
}

TEST_P(RegionTest, ReturnedStressIsAdmissibleAndOnTheSurfaceWhenPlastic) {
  const Result r = run(model, *c.strength, step.sigma_n, step.d_eps);
  const double f = MohrCoulomb::yield_function(r.sigma, *c.strength);
  const double tol = 1e-8 * stress_scale(step.trial);
  EXPECT_LE(f, tol);
  if (c.region == MohrCoulombReturn::elastic) {
    EXPECT_LT(f, -tol);
    EXPECT_LE((r.sigma - step.trial).cwiseAbs().maxCoeff(), 1e-12 * stress_scale(step.trial));
  } else {
    EXPECT_NEAR(f, 0.0, tol);
    EXPECT_GT(MohrCoulomb::yield_function(step.trial, *c.strength), 1e3);
  }
}

TEST_P(RegionTest, PrincipalDirectionsAreThoseOfTheTrialStress) {
  const Result r = run(model, *c.strength, step.sigma_n, step.d_eps);
  const Mat3 s = stress_tensor(r.sigma), trial = stress_tensor(step.trial);
  const double commutator = (s * trial - trial * s).cwiseAbs().maxCoeff();
  EXPECT_LE(commutator, 1e-12 * stress_scale(r.sigma) * stress_scale(step.trial));
  // And the principal values are in the trial's axes: kAxes^T sigma kAxes is diagonal.
  Mat3 rotated = kAxes.transpose() * s * kAxes;
  rotated.diagonal().setZero();
  EXPECT_LE(rotated.cwiseAbs().maxCoeff(), 1e-9 * stress_scale(r.sigma));
}

TEST_P(RegionTest, PlasticStrainFollowsThePotential) {
  const Result r = run(model, *c.strength, step.sigma_n, step.d_eps);
  if (c.region == MohrCoulombReturn::elastic) {
    EXPECT_LE(plastic_strain(step, r.sigma).norm(), 1e-12 * step.d_eps.norm());
    return;
  }
  if (c.region == MohrCoulombReturn::apex) {
    // The book's apex return has no flow rule; it only removes the excess hydrostatic tension.
    EXPECT_GT(plastic_strain(step, r.sigma).head<3>().sum(), 1e-4);
    return;
  }
  const Mat3 principal = kAxes.transpose() * strain_tensor(plastic_strain(step, r.sigma)) * kAxes;
  const Vec3 eps_p = principal.diagonal();
  Mat3 off_diagonal = principal;
  off_diagonal.diagonal().setZero();
  EXPECT_LE(off_diagonal.cwiseAbs().maxCoeff(), 1e-9 * eps_p.norm());
  EXPECT_GT(eps_p.norm(), 1e-6);
  std::vector<Vec3> generators;
  for (const Flow flow : c.flows) {
    generators.push_back(flow_direction(flow, c.strength->dilatancy_angle));
  }
  EXPECT_TRUE(in_cone(eps_p, generators, 1e-8)) << "plastic strain " << eps_p.transpose();
  if (c.flows.size() == 1) {
    // One active plane: parallel to its potential gradient, pointing outwards.
    const Vec3& n = generators.front();
    EXPECT_NEAR(eps_p.normalized().dot(n.normalized()), 1.0, 1e-10);
  }
}

TEST_P(RegionTest, DeviatoricPlasticStrainMeasuresThePlasticIncrement) {
  const double history = 0.0123;
  const Result r = run(model, *c.strength, step.sigma_n, step.d_eps, history);
  const double expected = deviatoric_strain_norm(plastic_strain(step, r.sigma));
  EXPECT_NEAR(r.state.deviatoric_plastic_strain - history, expected, 1e-9 * expected + 1e-15);
  if (c.region == MohrCoulombReturn::elastic) {
    EXPECT_EQ(r.state.deviatoric_plastic_strain, history);
  } else {
    EXPECT_GT(r.state.deviatoric_plastic_strain - history, 1e-5);
  }
}

TEST_P(RegionTest, ElasticUnloadingFromTheReturnedState) {
  const Result loaded = run(model, *c.strength, step.sigma_n, step.d_eps);
  // Shrink the deviator by 5 % and compress by 1 kPa: inside every face of the surface.
  Vec6 d_sigma = -0.05 * loaded.sigma;
  d_sigma.head<3>().array() += 0.05 * mean_stress(loaded.sigma) - 1e3;
  const Vec6 d_eps = kElastic.stiffness().inverse() * d_sigma;
  const Result unloaded = run(model, *c.strength, loaded.sigma, d_eps, 0.5);
  EXPECT_EQ(unloaded.region, MohrCoulombReturn::elastic);
  const Vec6 expected = loaded.sigma + kElastic.stiffness() * d_eps;
  EXPECT_LE((unloaded.sigma - expected).cwiseAbs().maxCoeff(), 1e-9 * stress_scale(expected));
  EXPECT_EQ(unloaded.state.deviatoric_plastic_strain, 0.5);
}

TEST_P(RegionTest, RotatingTheInputRotatesTheOutput) {
  const Mat3 r = rotation(1.1, Vec3(0.3, -1, 2));
  const Result original = run(model, *c.strength, step.sigma_n, step.d_eps);
  const Result rotated =
      run(model, *c.strength, rotate_stress(r, step.sigma_n), rotate_strain(r, step.d_eps));
  EXPECT_EQ(rotated.region, original.region);
  const Vec6 expected = rotate_stress(r, original.sigma);
  EXPECT_LE((rotated.sigma - expected).cwiseAbs().maxCoeff(), 1e-9 * stress_scale(expected));
  EXPECT_NEAR(rotated.state.deviatoric_plastic_strain, original.state.deviatoric_plastic_strain,
              1e-9 * original.state.deviatoric_plastic_strain + 1e-15);
}

/// Central differences of `update` with respect to each Voigt component of d_eps.
Mat6 finite_difference_tangent(const MohrCoulomb& model, const MohrCoulombStrength& strength,
                               const Step& step, double h) {
  Mat6 t;
  for (int k = 0; k < 6; ++k) {
    const Vec6 plus = run(model, strength, step.sigma_n, step.d_eps + h * Vec6::Unit(k)).sigma;
    const Vec6 minus = run(model, strength, step.sigma_n, step.d_eps - h * Vec6::Unit(k)).sigma;
    t.col(k) = (plus - minus) / (2.0 * h);
  }
  return t;
}

TEST_P(RegionTest, TangentMatchesCentralFiniteDifferences) {
  const Mat6 tangent = model.consistent_tangent(step.sigma_n, step.d_eps, *c.strength);
  const double h = 1e-7 * step.d_eps.cwiseAbs().maxCoeff();
  const Mat6 fd = finite_difference_tangent(model, *c.strength, step, h);
  const double error = tangent_error(tangent, fd);
  std::ostringstream recorded;
  recorded << std::scientific << error;
  RecordProperty("fd_tangent_error", recorded.str());
  EXPECT_LT(error, 1e-6) << c.name << "\nanalytic\n" << tangent << "\nfd\n" << fd;
  if (c.region == MohrCoulombReturn::elastic) {
    EXPECT_EQ(tangent, kElastic.stiffness());
  } else {
    EXPECT_GT(tangent_error(tangent, kElastic.stiffness()), 0.05) << "plastic tangent is elastic";
  }
}

INSTANTIATE_TEST_SUITE_P(MohrCoulomb, RegionTest, testing::ValuesIn(region_cases()),
                         [](const testing::TestParamInfo<RegionCase>& info) {
                           return std::string(info.param.name);
                         });

}  // namespace unsatmpm::physics::test_mohr_coulomb

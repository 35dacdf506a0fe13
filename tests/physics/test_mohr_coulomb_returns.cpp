// Mohr-Coulomb with tension cut-off beyond the single return regions: random and near-surface
// trials, the apex, tension, non-finite and repeated inputs, the tangent's symmetry, the strength
// passed per call, the yield function, and parameter validation.

#include "mohr_coulomb_fixture.hpp"

namespace unsatmpm::physics::test_mohr_coulomb {

// Random trials around the surface: elastic exactly when the trial is admissible (this covers the
// cheap early test of update), otherwise returned onto the surface, for both strengths.
TEST(MohrCoulomb, RandomTrialsAreClassifiedByTheYieldFunction) {
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> principal(-60e3, 25e3);
  std::normal_distribution<double> normal;
  for (const MohrCoulombStrength* strength : {&kStrength, &kNoCutOff}) {
    const MohrCoulomb model = MohrCoulomb::create(kElastic, *strength);
    int n_elastic = 0, n_plastic = 0;
    for (int i = 0; i < 20000; ++i) {
      const Eigen::Quaterniond q(normal(rng), normal(rng), normal(rng), normal(rng));
      const Vec6 diagonal =
          (Vec6() << principal(rng), principal(rng), principal(rng), 0, 0, 0).finished();
      const Vec6 trial = rotate_stress(q.normalized().toRotationMatrix(), diagonal);
      const double f = MohrCoulomb::yield_function(trial, *strength);
      const double tol = 1e-8 * stress_scale(trial);
      if (std::abs(f) < tol) continue;
      const Result r = run(model, *strength, trial, Vec6::Zero());
      ASSERT_EQ(r.region == MohrCoulombReturn::elastic, f < 0) << "f = " << f;
      EXPECT_LE(MohrCoulomb::yield_function(r.sigma, *strength), tol);
      (f < 0 ? n_elastic : n_plastic)++;
    }
    EXPECT_GT(n_elastic, 1000);
    EXPECT_GT(n_plastic, 1000);
  }
}

// Trials a relative 1e-6 inside and outside the surface, along rays from the hydrostatic axis.
TEST(MohrCoulomb, TrialsJustInsideAreElasticAndJustOutsideArePlastic) {
  std::mt19937 rng(777);
  std::uniform_real_distribution<double> deviator(-1.0, 1.0), unit(0.0, 1.0);
  std::normal_distribution<double> normal;
  for (const MohrCoulombStrength* strength : {&kStrength, &kNoCutOff}) {
    const MohrCoulomb model = MohrCoulomb::create(kElastic, *strength);
    for (int i = 0; i < 2000; ++i) {
      const Eigen::Quaterniond q(normal(rng), normal(rng), normal(rng), normal(rng));
      Vec3 d(deviator(rng), deviator(rng), deviator(rng));
      d.array() -= d.mean();
      d.normalize();
      const Vec6 direction =
          rotate_stress(q.normalized().toRotationMatrix(), (Vec6() << d, 0, 0, 0).finished() * 1e3);
      // Mean stress from -80 kPa to just below the cut-off (or the apex).
      const double p = -80e3 + unit(rng) * (0.999 * strength->tensile_strength + 80e3);
      const Vec6 axis = (Vec6() << p, p, p, 0, 0, 0).finished();
      // Bisection for the surface: yield(axis) < 0 < yield(axis + 1e3 direction) (1 MPa deviator).
      double inside = 0.0, outside = 1e3;
      for (int k = 0; k < 80; ++k) {
        const double mid = 0.5 * (inside + outside);
        (MohrCoulomb::yield_function(axis + mid * direction, *strength) < 0 ? inside : outside) =
            mid;
      }
      EXPECT_EQ(run(model, *strength, axis + inside * (1 - 1e-6) * direction, Vec6::Zero()).region,
                MohrCoulombReturn::elastic);
      EXPECT_NE(run(model, *strength, axis + outside * (1 + 1e-6) * direction, Vec6::Zero()).region,
                MohrCoulombReturn::elastic);
    }
  }
}

TEST(MohrCoulomb, ApexReturnIsTheApex) {
  const MohrCoulomb model = MohrCoulomb::create(kElastic, kNoCutOff);
  const Vec6 trial = (Vec6() << 60e3, 40e3, 50e3, 5e3, -3e3, 2e3).finished();
  Vec6 sigma = trial;
  MohrCoulombState state;
  EXPECT_EQ(model.update(Vec6::Zero(), sigma, state), MohrCoulombReturn::apex);
  const double apex = 10e3 / std::tan(30 * kDeg);
  const Vec6 expected = (Vec6() << apex, apex, apex, 0, 0, 0).finished();
  EXPECT_LE((sigma - expected).cwiseAbs().maxCoeff(), 1e-9 * apex);
  EXPECT_EQ(model.consistent_tangent(trial, Vec6::Zero(), kNoCutOff), Mat6::Zero());
}

TEST(MohrCoulomb, CohesionlessSoilCannotCarryTension) {
  const MohrCoulombStrength sand{0.0, 35 * kDeg, 0.0, 0.0};
  const MohrCoulomb model = MohrCoulomb::create(kElastic, sand);
  Vec6 sigma = Vec6::Zero();
  MohrCoulombState state;
  const Vec6 stretch = (Vec6() << 1e-3, 2e-4, 0, 1e-4, 0, 0).finished();
  EXPECT_NE(model.update(stretch, sigma, state), MohrCoulombReturn::elastic);
  EXPECT_LE(sigma.cwiseAbs().maxCoeff(), 1e-9 * (kElastic.stiffness() * stretch).norm());
  // Compression of a stress-free sand is elastic.
  sigma.setZero();
  const Vec6 squeeze = (Vec6() << -1e-4, -1e-4, -1e-4, 0, 0, 0).finished();
  EXPECT_EQ(model.update(squeeze, sigma, state), MohrCoulombReturn::elastic);
}

// A strain increment that is not finite leaves a stress that is not finite, with and without the
// cut-off, so that the caller's blow-up check sees it (a return could map it onto the apex).
TEST(MohrCoulomb, ANonFiniteIncrementGivesANonFiniteStress) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const MohrCoulombStrength* strength : {&kStrength, &kNoCutOff}) {
    const MohrCoulomb model = MohrCoulomb::create(kElastic, *strength);
    for (const double bad : {nan, std::numeric_limits<double>::infinity()}) {
      const Vec6 d_eps = (Vec6() << 1e-4, bad, 0, 0, 0, 0).finished();
      const Vec6 start = (Vec6() << -10e3, -20e3, -30e3, 2e3, 0, 0).finished();
      const Result r = run(model, *strength, start, d_eps);
      EXPECT_FALSE(std::isfinite(r.sigma.sum())) << "increment " << bad;
    }
  }
}

TEST(MohrCoulomb, RepeatedTrialEigenvaluesGiveAnIsotropicReturn) {
  // Axisymmetric trial: s2 = s3 exactly, so the eigenvectors of s2, s3 are arbitrary.
  const MohrCoulomb model = MohrCoulomb::create(kElastic, kStrength);
  Vec6 sigma = (Vec6() << -10e3, -100e3, -100e3, 0, 0, 0).finished();
  MohrCoulombState state;
  EXPECT_EQ(model.update(Vec6::Zero(), sigma, state), MohrCoulombReturn::edge_right);
  EXPECT_NEAR(sigma[1], sigma[2], 1e-9 * 100e3);
  EXPECT_LE(sigma.tail<3>().cwiseAbs().maxCoeff(), 1e-9 * 100e3);
  // The tangent there is the limit of the tangent at nearby distinct eigenvalues.
  const Mat6 at = model.consistent_tangent((Vec6() << -10e3, -100e3, -100e3, 0, 0, 0).finished(),
                                           Vec6::Zero(), kStrength);
  const Mat6 near = model.consistent_tangent(
      (Vec6() << -10e3, -100e3, -100e3, 0, 1e-3, 0).finished(), Vec6::Zero(), kStrength);
  EXPECT_LT(tangent_error(at, near), 1e-6);
}

TEST(MohrCoulomb, AssociatedFaceTangentIsSymmetric) {
  const MohrCoulombStrength associated{10e3, 30 * kDeg, 30 * kDeg, 5e3};
  const MohrCoulomb model = MohrCoulomb::create(kElastic, associated);
  const RegionCase face{"face", {-10, -50, -100}, MohrCoulombReturn::face, &associated, {}};
  const Step step = make_step(face);
  ASSERT_EQ(run(model, associated, step.sigma_n, step.d_eps).region, MohrCoulombReturn::face);
  const Mat6 t = model.consistent_tangent(step.sigma_n, step.d_eps, associated);
  EXPECT_LT(tangent_error(t, t.transpose()), 1e-12);
  // Non-associated flow breaks the symmetry: the check above can fail.
  const Mat6 t_non = MohrCoulomb::create(kElastic, kStrength)
                         .consistent_tangent(step.sigma_n, step.d_eps, kStrength);
  EXPECT_GT(tangent_error(t_non, t_non.transpose()), 1e-3);
}

TEST(MohrCoulomb, StrengthPassedPerCallOverridesTheStoredOne) {
  const MohrCoulomb model = MohrCoulomb::create(kElastic, kStrength);
  const Vec6 sigma0 = (Vec6() << -10e3, -50e3, -100e3, 0, 0, 0).finished();
  Vec6 weak = sigma0, strong = sigma0, stored = sigma0;
  MohrCoulombState state;
  MohrCoulombStrength stronger = kStrength;
  stronger.cohesion = 40e3;
  EXPECT_EQ(model.update(Vec6::Zero(), stored, state), MohrCoulombReturn::face);
  EXPECT_EQ(model.update(Vec6::Zero(), kStrength, weak, state), MohrCoulombReturn::face);
  EXPECT_EQ(model.update(Vec6::Zero(), stronger, strong, state), MohrCoulombReturn::elastic);
  EXPECT_EQ(stored, weak);
  EXPECT_EQ(strong, sigma0);
}

TEST(MohrCoulomb, YieldFunctionValues) {
  // Principal stresses (-10, -50, -100) kPa in rotated axes: f = 90 - 55 - 17.32 kPa.
  Vec6 principal = (Vec6() << -50e3, -10e3, -100e3, 0, 0, 0).finished();
  const Vec6 sigma = rotate_stress(kAxes, principal);
  const double k = 2 * 10e3 * std::cos(30 * kDeg);
  EXPECT_NEAR(MohrCoulomb::yield_function(sigma, kStrength), 90e3 - 55e3 - k, 1e-6);
  // Hydrostatic tension p: the cut-off governs, f = p - t.
  principal << 4e3, 4e3, 4e3, 0, 0, 0;
  EXPECT_NEAR(MohrCoulomb::yield_function(principal, kStrength), -1e3, 1e-6);
  principal << 8e3, 8e3, 8e3, 0, 0, 0;
  EXPECT_NEAR(MohrCoulomb::yield_function(principal, kStrength), 3e3, 1e-6);
}

// --- Parameter validation ---------------------------------------------------------------------

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

void expect_rejected(const MohrCoulombStrength& s, const std::string& parameter) {
  EXPECT_THROW(MohrCoulomb::validate(s), ParameterError);
  try {
    MohrCoulomb::create(kElastic, s);
    ADD_FAILURE() << parameter << ": invalid strength accepted";
  } catch (const ParameterError& error) {
    EXPECT_EQ(error.parameter(), parameter);
    EXPECT_NE(std::string(error.what()).find(parameter), std::string::npos) << error.what();
  }
}

MohrCoulombStrength with(double MohrCoulombStrength::*field, double value) {
  MohrCoulombStrength s = kStrength;
  s.*field = value;
  return s;
}

TEST(MohrCoulombValidate, RejectsInvalidCohesion) {
  for (const double c : {-1.0, kNaN, kInf}) {
    expect_rejected(with(&MohrCoulombStrength::cohesion, c), "cohesion");
  }
}

TEST(MohrCoulombValidate, RejectsInvalidFrictionAngle) {
  for (const double phi : {0.0, -0.1, std::numbers::pi / 2, 2.0, kNaN}) {
    MohrCoulombStrength s = with(&MohrCoulombStrength::friction_angle, phi);
    s.dilatancy_angle = 0.0;
    s.tensile_strength = 0.0;
    expect_rejected(s, "friction_angle");
  }
}

TEST(MohrCoulombValidate, RejectsInvalidDilatancyAngle) {
  for (const double psi : {-0.01, 31 * kDeg, kNaN}) {
    expect_rejected(with(&MohrCoulombStrength::dilatancy_angle, psi), "dilatancy_angle");
  }
}

TEST(MohrCoulombValidate, RejectsInvalidTensileStrength) {
  for (const double t : {-1.0, 17.4e3, kNaN, kInf}) {
    expect_rejected(with(&MohrCoulombStrength::tensile_strength, t), "tensile_strength");
  }
  // A cohesionless soil has no tensile strength.
  MohrCoulombStrength sand{0.0, 35 * kDeg, 0.0, 1.0};
  expect_rejected(sand, "tensile_strength");
}

TEST(MohrCoulombValidate, AcceptsTheBoundsOfEveryRange) {
  EXPECT_NO_THROW(MohrCoulomb::validate({0.0, 1e-3, 0.0, 0.0}));
  EXPECT_NO_THROW(MohrCoulomb::validate({10e3, 89 * kDeg, 89 * kDeg, 0.0}));
  // t at the apex, computed as c cos(phi) / sin(phi) rather than c / tan(phi).
  const double phi = 30 * kDeg;
  EXPECT_NO_THROW(MohrCoulomb::validate({10e3, phi, phi, 10e3 * std::cos(phi) / std::sin(phi)}));
  const MohrCoulomb model = MohrCoulomb::create(kElastic, kStrength);
  EXPECT_EQ(model.strength.cohesion, kStrength.cohesion);
  EXPECT_EQ(model.elastic.young_modulus, kElastic.young_modulus);
}

TEST(MohrCoulombValidate, CreateRejectsInvalidElasticity) {
  EXPECT_THROW(MohrCoulomb::create(LinearElastic{-1.0, 0.3}, kStrength), ParameterError);
  EXPECT_THROW(MohrCoulomb::create(LinearElastic{1e7, 0.5}, kStrength), ParameterError);
}

}  // namespace unsatmpm::physics::test_mohr_coulomb

// Mohr-Coulomb with tension cut-off: every return region, its consistency (yield, coaxiality, flow
// rule), the consistent tangent against finite differences, invariance and parameter validation.
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

void PrintTo(MohrCoulombReturn r, std::ostream* os) {
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

Vec3 flow_direction(Flow flow, double psi) {
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

void PrintTo(const RegionCase& c, std::ostream* os) { *os << c.name; }

const std::vector<RegionCase>& region_cases() {
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

Mat3 rotation(double angle, const Vec3& axis) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

Vec6 rotate_stress(const Mat3& r, const Vec6& s) {
  return stress_voigt(r * stress_tensor(s) * r.transpose());
}

Vec6 rotate_strain(const Mat3& r, const Vec6& e) {
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

Step make_step(const RegionCase& c) {
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

Result run(const MohrCoulomb& model, const MohrCoulombStrength& strength, const Vec6& sigma_n,
           const Vec6& d_eps, double history = 0.0) {
  Result r{MohrCoulombReturn::elastic, sigma_n, MohrCoulombState{history}};
  r.region = model.update(d_eps, strength, r.sigma, r.state);
  return r;
}

double stress_scale(const Vec6& s) { return s.cwiseAbs().maxCoeff(); }

/// Plastic strain increment d_eps - D^-1 d_sigma (Voigt, engineering shear).
Vec6 plastic_strain(const Step& step, const Vec6& sigma) {
  return step.d_eps - kElastic.stiffness().inverse() * (sigma - step.sigma_n);
}

/// Nonnegative combination of the given directions equal to v, if one exists (up to tol).
bool in_cone(const Vec3& v, const std::vector<Vec3>& generators, double tol) {
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

// Error of the tangent relative to the elastic stiffness (the apex tangent is zero).
double tangent_error(const Mat6& tangent, const Mat6& reference) {
  return (tangent - reference).cwiseAbs().maxCoeff() / kElastic.stiffness().cwiseAbs().maxCoeff();
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

}  // namespace test_mohr_coulomb
}  // namespace unsatmpm::physics

// Suction-dependent Mohr-Coulomb strength: saturated values, monotonicity and limits, the paper's
// embankment values, derivatives against central differences, validity of the strength at any
// suction (the friction cap), the Mohr-Coulomb return with the strength of the current suction
// (drying holds a stress, wetting returns it), the consistent tangent, and parameter validation.
#include <gtest/gtest.h>

#include "tests/physics/physics_test_support.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "physics/mohr_coulomb.hpp"
#include "physics/parameter_error.hpp"
#include "physics/suction_strength.hpp"

namespace unsatmpm::physics {
namespace test_suction_strength {

using namespace test;

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kKpa = 1e3;
constexpr double kAtm = SuctionStrength::atmospheric_pressure;

// The paper's embankment (Table 2 and eqs. 13-14): c' = 1 kPa, phi' = 20 deg, dc_max = 15 kPa,
// B = 0.7, A = 0.1 deg per atmosphere, psi' = 0; t' = c' cot(phi'), the case parser's default.
const SuctionStrength kEmbankment =
    SuctionStrength::create(1e3, 15e3, 0.7, 20 * kDeg, 0.1 * kDeg, 0.0, 1e3 / std::tan(20 * kDeg));
// Strong suction effects that reach the friction cap early: phi = 89 deg at s = 29 P_atm = 2.9 MPa.
const SuctionStrength kSteep =
    SuctionStrength::create(0.0, 50e3, 3.0, 60 * kDeg, 1.0 * kDeg, 10 * kDeg, 0.0);
// A saturated friction angle above the cap, a dilatancy at the friction angle and a t' far above
// every apex (t = the apex at every suction).
const SuctionStrength kAboveCap =
    SuctionStrength::create(5e3, 5e3, 1.0, 89.5 * kDeg, 0.5 * kDeg, 89.5 * kDeg, 1e12);

const LinearElastic kElastic{10e6, 0.33};

/// 0 and `count` + 1 points from lo to hi (both > 0), evenly spaced in log.
std::vector<double> suctions(double lo, double hi, int count) {
  std::vector<double> s{0.0};
  for (int i = 0; i <= count; ++i) s.push_back(lo * std::pow(hi / lo, double(i) / count));
  return s;
}

TEST(SuctionStrength, SaturatedStrengthIsThePrimedParameters) {
  for (const SuctionStrength& law : {kEmbankment, kSteep, kAboveCap}) {
    for (const double s : {0.0, -1.0, -1e5, -kInf}) {
      EXPECT_EQ(law.cohesion_at(s), law.cohesion) << "s = " << s;
      EXPECT_EQ(law.friction_angle_at(s), law.friction_angle) << "s = " << s;
      EXPECT_EQ(law.d_cohesion(s), 0.0) << "s = " << s;
      EXPECT_EQ(law.d_friction_angle(s), 0.0) << "s = " << s;
      const MohrCoulombStrength m = law.at(s);
      EXPECT_EQ(m.cohesion, law.cohesion);
      EXPECT_EQ(m.friction_angle, law.friction_angle);
      EXPECT_EQ(m.dilatancy_angle, law.dilatancy_angle);
      EXPECT_EQ(m.tensile_strength,
                std::min(law.tensile_strength, law.cohesion / std::tan(law.friction_angle)));
    }
  }
  // Dilatancy is psi' at every suction.
  for (const double s : suctions(1.0, 1e9, 90)) {
    EXPECT_EQ(kSteep.at(s).dilatancy_angle, kSteep.dilatancy_angle) << "s = " << s;
  }
}

TEST(SuctionStrength, StrengthGrowsWithSuction) {
  for (const SuctionStrength& law : {kEmbankment, kSteep, kAboveCap}) {
    const std::vector<double> s = suctions(1e-2, 1e9, 330);  // 30 points per decade
    for (std::size_t i = 1; i < s.size(); ++i) {
      EXPECT_GE(law.cohesion_at(s[i]), law.cohesion_at(s[i - 1])) << "s = " << s[i];
      EXPECT_GE(law.friction_angle_at(s[i]), law.friction_angle_at(s[i - 1])) << "s = " << s[i];
      EXPECT_LE(law.cohesion_at(s[i]), law.cohesion + law.cohesion_increase);
    }
  }
  // Strictly, where the law says so: 0.5 MPa and 0.8 MPa of the embankment.
  EXPECT_GT(kEmbankment.cohesion_at(0.8e6), kEmbankment.cohesion_at(0.5e6));
  EXPECT_GT(kEmbankment.friction_angle_at(0.8e6), kEmbankment.friction_angle_at(0.5e6));
}

TEST(SuctionStrength, TensileStrengthGrowsWhileTheApexStaysAboveIt) {
  // Embankment, t' = c' cot(phi') = 2.75 kPa: the apex c(s) cot(phi(s)) stays above t' up to
  // s = 61 MPa (header), so t(s) is non-decreasing (here: constant) up to 60 MPa.
  const std::vector<double> s = suctions(1e-2, 60e6, 300);
  for (std::size_t i = 1; i < s.size(); ++i) {
    EXPECT_GE(kEmbankment.tensile_strength_at(s[i]), kEmbankment.tensile_strength_at(s[i - 1]))
        << "s = " << s[i];
  }
  EXPECT_EQ(kEmbankment.tensile_strength_at(0.8e6), kEmbankment.tensile_strength);
  // With no cut-off of its own (t' = 0) a soil keeps no tension at any suction.
  const SuctionStrength no_tension =
      SuctionStrength::create(1e3, 15e3, 0.7, 20 * kDeg, 0.1 * kDeg, 0.0, 0.0);
  for (const double x : suctions(1.0, 1e9, 45)) EXPECT_EQ(no_tension.at(x).tensile_strength, 0.0);
}

TEST(SuctionStrength, TensileStrengthIsLimitedByTheConeApex) {
  // t' far above every apex: t(s) = c(s) cot(phi(s)), which rises and then falls (header).
  const SuctionStrength apex =
      SuctionStrength::create(1e3, 15e3, 0.7, 20 * kDeg, 0.1 * kDeg, 0.0, 1e12);
  for (const double s : suctions(1e-2, 1e9, 110)) {
    EXPECT_DOUBLE_EQ(apex.tensile_strength_at(s),
                     apex.cohesion_at(s) / std::tan(apex.friction_angle_at(s)));
  }
  EXPECT_NEAR(apex.tensile_strength_at(0.0), 2747.477, 1e-3);  // 1 kPa / tan(20 deg)
  EXPECT_GT(apex.tensile_strength_at(0.69e6), apex.tensile_strength_at(0.3e6));
  EXPECT_LT(apex.tensile_strength_at(0.8e6), apex.tensile_strength_at(0.69e6));
  // At the cap: 16 kPa / tan(89 deg) = 16e3 * 0.0174551 = 279.28 Pa.
  EXPECT_NEAR(apex.tensile_strength_at(1e9), 279.281, 1e-3);
}

TEST(SuctionStrength, CohesionTendsToItsDryValue) {
  for (const SuctionStrength& law : {kEmbankment, kSteep, kAboveCap}) {
    const double dry = law.cohesion + law.cohesion_increase;
    EXPECT_DOUBLE_EQ(law.cohesion_at(1e9), dry);
    // Ten rate lengths P_atm / B: within exp(-10) of the dry value.
    const double s10 = 10.0 * kAtm / law.cohesion_rate;
    EXPECT_NEAR(law.cohesion_at(s10), dry - law.cohesion_increase * std::exp(-10.0), 1e-9 * dry);
    EXPECT_LT(law.cohesion_at(s10), dry);
  }
}

TEST(SuctionStrength, EmbankmentValuesAt800kPa) {
  // s / P_atm = 800e3 / 101325 = 7.8953861337
  // c   = 1 kPa + 15 kPa (1 - exp(-0.7 * 7.8953861337)) = 1 + 15 (1 - exp(-5.5267702936))
  //     = 1 + 15 (1 - 0.0039788188) = 1 + 14.9403177 = 15.9403177 kPa
  // phi = 20 deg + 0.1 deg * 7.8953861337 = 20.7895386134 deg
  EXPECT_NEAR(kEmbankment.cohesion_at(800e3), 15940.3177, 1e-3);
  EXPECT_NEAR(kEmbankment.friction_angle_at(800e3) / kDeg, 20.7895386134, 1e-9);
  const MohrCoulombStrength m = kEmbankment.at(800e3);
  EXPECT_NEAR(m.cohesion, 15940.3177, 1e-3);
  EXPECT_NEAR(m.friction_angle / kDeg, 20.7895386134, 1e-9);
}

TEST(SuctionStrength, DerivativesMatchCentralDifferences) {
  // Points on both sides of kSteep's cap at 29 P_atm = 2.938 MPa, the stencil never across it.
  for (const SuctionStrength& law : {kEmbankment, kSteep, kAboveCap}) {
    for (const double s : {1.0, 1e2, 1e3, 1e4, 5e4, 1e5, 3e5, 8e5, 2e6, 2.9e6, 3e6, 1e7, 1e8}) {
      const double h = 1e-4 * s;
      const double fd_c = central_difference([&](double x) { return law.cohesion_at(x); }, s, h);
      // Round-off of the difference quotient: about 1e-16 c / h.
      const double c_tol = 1e-6 * std::abs(fd_c) + 1e-14 * law.cohesion_at(s) / h;
      EXPECT_NEAR(law.d_cohesion(s), fd_c, c_tol) << "s = " << s;
      const double fd_phi =
          central_difference([&](double x) { return law.friction_angle_at(x); }, s, h);
      EXPECT_NEAR(law.d_friction_angle(s), fd_phi, 1e-6 * std::abs(fd_phi) + 1e-14 / h)
          << "s = " << s;
    }
  }
  // The derivatives are those of eqs. 13-14, not zero: dc/ds(0+) = dc_max B / P_atm.
  EXPECT_NEAR(kEmbankment.d_cohesion(1e-6), 15e3 * 0.7 / kAtm, 1e-9 * 15e3 * 0.7 / kAtm);
  EXPECT_DOUBLE_EQ(kEmbankment.d_friction_angle(1e5), 0.1 * kDeg / kAtm);
  EXPECT_EQ(kSteep.d_friction_angle(3e6), 0.0);  // beyond the cap
}

TEST(SuctionStrength, StrengthIsAValidMohrCoulombStrengthAtAnySuction) {
  for (const SuctionStrength& law : {kEmbankment, kSteep, kAboveCap}) {
    for (const double s : suctions(1e-3, 1e9, 360)) {
      EXPECT_NO_THROW(MohrCoulomb::validate(law.at(s))) << "s = " << s;
    }
  }
  // The cap holds phi at 89 deg, or at phi' when phi' is above it.
  EXPECT_DOUBLE_EQ(kEmbankment.friction_angle_at(1e9), 89 * kDeg);
  EXPECT_DOUBLE_EQ(kSteep.friction_angle_at(3e6), 89 * kDeg);
  EXPECT_LT(kSteep.friction_angle_at(2.9e6), 89 * kDeg);
  EXPECT_DOUBLE_EQ(kAboveCap.friction_angle_at(1e9), 89.5 * kDeg);
  EXPECT_LT(kAboveCap.at(1e9).friction_angle, std::numbers::pi / 2);
}

// --- The strength in the Mohr-Coulomb return ------------------------------------------------

Mat3 rotation(double angle, const Vec3& axis) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

// Generic principal axes, so that every Voigt component is used.
const Mat3 kAxes = rotation(0.7, Vec3(1, 2, 3)) * rotation(0.4, Vec3(-2, 1, 0.5));

/// The stress with principal values `principal` [kPa] in the axes kAxes.
Vec6 stress_in_axes(const Vec3& principal) {
  return stress_voigt(kAxes * (principal * kKpa).asDiagonal() * kAxes.transpose());
}

double stress_scale(const Vec6& s) { return s.cwiseAbs().maxCoeff(); }

/// kAxes diagonalises sigma: its largest off-diagonal component in those axes.
double off_axes(const Vec6& sigma) {
  Mat3 rotated = kAxes.transpose() * stress_tensor(sigma) * kAxes;
  rotated.diagonal().setZero();
  return rotated.cwiseAbs().maxCoeff();
}

TEST(SuctionStrength, ReturnIsOntoTheSurfaceOfTheCurrentSuction) {
  // Principal (-10, -30, -50) kPa: f = 40 - 60 sin(phi) - 2 c cos(phi) is
  // +17.6 kPa at s = 0 (c = 1 kPa, phi = 20 deg) and -11.1 kPa at 0.8 MPa (c = 15.9, phi = 20.8).
  const MohrCoulomb model = MohrCoulomb::create(kElastic, kEmbankment.at(0.0));
  const Vec6 trial = stress_in_axes(Vec3(-10, -30, -50));
  const double tol = 1e-8 * stress_scale(trial);
  const MohrCoulombStrength dry = kEmbankment.at(800e3), wet = kEmbankment.at(0.0);
  ASSERT_LT(MohrCoulomb::yield_function(trial, dry), -10 * kKpa);
  ASSERT_GT(MohrCoulomb::yield_function(trial, wet), 15 * kKpa);

  Vec6 sigma = trial;
  MohrCoulombState state;
  EXPECT_EQ(model.update(Vec6::Zero(), dry, sigma, state), MohrCoulombReturn::elastic);
  EXPECT_EQ(sigma, trial);
  EXPECT_EQ(state.deviatoric_plastic_strain, 0.0);

  EXPECT_NE(model.update(Vec6::Zero(), wet, sigma, state), MohrCoulombReturn::elastic);
  EXPECT_NEAR(MohrCoulomb::yield_function(sigma, wet), 0.0, tol);
  EXPECT_GT(state.deviatoric_plastic_strain, 0.0);
}

TEST(SuctionStrength, WettingReturnsAStressFromTheDrySurfaceToTheWetOne) {
  const MohrCoulomb model = MohrCoulomb::create(kElastic, kEmbankment.at(0.0));
  const MohrCoulombStrength dry = kEmbankment.at(800e3), wet = kEmbankment.at(0.0);
  // A stress on the dry surface: the return of a far trial with the strength at 0.8 MPa.
  const Vec6 far = stress_in_axes(Vec3(-10, -60, -200));
  const double tol = 1e-8 * stress_scale(far);
  Vec6 on_dry = far;
  MohrCoulombState state;
  ASSERT_NE(model.update(Vec6::Zero(), dry, on_dry, state), MohrCoulombReturn::elastic);
  ASSERT_NEAR(MohrCoulomb::yield_function(on_dry, dry), 0.0, tol);
  ASSERT_GT(MohrCoulomb::yield_function(on_dry, wet), 10 * kKpa);

  // Wetting to s = 0 at zero strain: back onto the smaller surface.
  Vec6 sigma = on_dry;
  const double history = state.deviatoric_plastic_strain;
  EXPECT_NE(model.update(Vec6::Zero(), wet, sigma, state), MohrCoulombReturn::elastic);
  EXPECT_NEAR(MohrCoulomb::yield_function(sigma, wet), 0.0, tol);
  EXPECT_LE(MohrCoulomb::yield_function(sigma, dry), tol);  // the wet surface lies inside
  EXPECT_GT(state.deviatoric_plastic_strain, history);
  // Principal directions unchanged: sigma commutes with the stress it started from and is
  // diagonal in the trial's axes.
  const Mat3 a = stress_tensor(sigma), b = stress_tensor(on_dry);
  EXPECT_LE((a * b - b * a).cwiseAbs().maxCoeff(), 1e-12 * stress_scale(sigma) * stress_scale(far));
  EXPECT_LE(off_axes(sigma), 1e-9 * stress_scale(far));
  EXPECT_GT((sigma - on_dry).cwiseAbs().maxCoeff(), 1 * kKpa);
}

TEST(SuctionMohrCoulomb, UpdateUsesTheStrengthOfTheSuctionItIsGiven) {
  // The model a three-phase material runs: the same stress stays at 0.8 MPa and yields at 0; the
  // result equals MohrCoulomb::update with kEmbankment.at(s), bit for bit, at several suctions.
  const SuctionMohrCoulomb model = SuctionMohrCoulomb::create(kElastic, kEmbankment);
  const MohrCoulomb plain = MohrCoulomb::create(kElastic, kEmbankment.at(0.0));
  const Vec6 start = stress_in_axes(Vec3(-10, -30, -50));
  const Vec6 d_eps = (Vec6() << 2.0, -1.0, 0.5, 1.0, -0.3, 0.4).finished() * 1e-5;
  for (const double s : {0.0, 50e3, 200e3, 800e3}) {
    Vec6 a = start, b = start;
    MohrCoulombState sa, sb;
    EXPECT_EQ(model.update(d_eps, s, a, sa), plain.update(d_eps, kEmbankment.at(s), b, sb));
    EXPECT_EQ(a, b) << "s = " << s;
    EXPECT_EQ(sa.deviatoric_plastic_strain, sb.deviatoric_plastic_strain);
    EXPECT_LE(MohrCoulomb::yield_function(a, kEmbankment.at(s)), 1e-8 * stress_scale(start));
  }
  Vec6 sigma = start;
  MohrCoulombState state;
  EXPECT_EQ(model.update(Vec6::Zero(), 800e3, sigma, state), MohrCoulombReturn::elastic);
  EXPECT_NE(model.update(Vec6::Zero(), 0.0, sigma, state), MohrCoulombReturn::elastic);
  EXPECT_GT(state.deviatoric_plastic_strain, 0.0);
  EXPECT_EQ(model.elastic().young_modulus, kElastic.young_modulus);
}

TEST(SuctionMohrCoulomb, CreateRejectsAnInvalidElasticityOrStrength) {
  EXPECT_THROW(SuctionMohrCoulomb::create(LinearElastic{-1.0, 0.3}, kEmbankment), ParameterError);
  EXPECT_NO_THROW(SuctionMohrCoulomb::create(kElastic, kAboveCap));
  // t' = +infinity: the cut-off is the apex at every suction; NaN and -infinity are rejected.
  const double inf = std::numeric_limits<double>::infinity();
  const SuctionStrength apex = SuctionStrength::create(1e3, 15e3, 0.7, 20 * kDeg, 0.0, 0.0, inf);
  EXPECT_DOUBLE_EQ(apex.tensile_strength_at(0.0), 1e3 / std::tan(20 * kDeg));
  EXPECT_THROW(SuctionStrength::create(1e3, 15e3, 0.7, 20 * kDeg, 0.0, 0.0, std::nan("")),
               ParameterError);
  EXPECT_THROW(SuctionStrength::create(1e3, 15e3, 0.7, 20 * kDeg, 0.0, 0.0, -inf), ParameterError);
}

/// Central differences of update() with respect to each Voigt component of d_eps.
Mat6 finite_difference_tangent(const MohrCoulomb& model, const MohrCoulombStrength& strength,
                               const Vec6& sigma_n, const Vec6& d_eps, double h) {
  Mat6 t;
  for (int k = 0; k < 6; ++k) {
    Vec6 plus = sigma_n, minus = sigma_n;
    MohrCoulombState state;
    model.update(d_eps + h * Vec6::Unit(k), strength, plus, state);
    model.update(d_eps - h * Vec6::Unit(k), strength, minus, state);
    t.col(k) = (plus - minus) / (2.0 * h);
  }
  return t;
}

TEST(SuctionStrength, ConsistentTangentMatchesCentralDifferencesAtTwoSuctions) {
  const MohrCoulomb model = MohrCoulomb::create(kElastic, kEmbankment.at(0.0));
  const Vec6 d_eps = (Vec6() << 1.0, -2.0, 0.5, 1.5, -0.7, 0.9).finished() * 1e-4;
  const Vec6 trial = stress_in_axes(Vec3(-10, -60, -200));
  const Vec6 sigma_n = trial - kElastic.stiffness() * d_eps;
  const double stiffness = kElastic.stiffness().cwiseAbs().maxCoeff();
  for (const double s : {100e3, 800e3}) {
    const MohrCoulombStrength strength = kEmbankment.at(s);
    Vec6 sigma = sigma_n;
    MohrCoulombState state;
    const MohrCoulombReturn region = model.update(d_eps, strength, sigma, state);
    ASSERT_NE(region, MohrCoulombReturn::elastic) << "s = " << s;
    ASSERT_NE(region, MohrCoulombReturn::apex) << "s = " << s;
    const Mat6 tangent = model.consistent_tangent(sigma_n, d_eps, strength);
    const double h = 1e-7 * d_eps.cwiseAbs().maxCoeff();
    const Mat6 fd = finite_difference_tangent(model, strength, sigma_n, d_eps, h);
    EXPECT_LT((tangent - fd).cwiseAbs().maxCoeff() / stiffness, 1e-6)
        << "s = " << s << "\nanalytic\n"
        << tangent << "\nfd\n"
        << fd;
    EXPECT_GT((tangent - kElastic.stiffness()).cwiseAbs().maxCoeff() / stiffness, 0.05)
        << "s = " << s << ": plastic tangent is elastic";
  }
}

// --- Parameter validation ---------------------------------------------------------------------

/// The embankment's parameters with one replaced by `value` (index in create's order).
SuctionStrength create_with(int index, double value) {
  double p[7] = {1e3, 15e3, 0.7, 20 * kDeg, 0.1 * kDeg, 0.0, 1e3};
  p[index] = value;
  return SuctionStrength::create(p[0], p[1], p[2], p[3], p[4], p[5], p[6]);
}

TEST(SuctionStrengthValidate, RejectsNegativeCohesionIncrease) {
  expect_parameter_error([] { create_with(1, -1.0); }, "cohesion_increase");
}

TEST(SuctionStrengthValidate, RejectsFrictionAngleOutOfRange) {
  for (const double phi : {0.0, -0.1, std::numbers::pi / 2, 2.0, kNaN}) {
    // psi' = 0 is within [0, phi'] for every valid phi', so only friction_angle can be named.
    expect_parameter_error([&] { create_with(3, phi); }, "friction_angle");
  }
}

TEST(SuctionStrengthValidate, RejectsDilatancyAboveFrictionAngle) {
  expect_parameter_error([] { create_with(5, 21 * kDeg); }, "dilatancy_angle");
  expect_parameter_error([] { create_with(5, -0.01); }, "dilatancy_angle");
}

TEST(SuctionStrengthValidate, RejectsEveryOtherInvalidParameter) {
  expect_parameter_error([] { create_with(0, -1.0); }, "cohesion");
  expect_parameter_error([] { create_with(0, kInf); }, "cohesion");
  expect_parameter_error([] { create_with(1, kNaN); }, "cohesion_increase");
  expect_parameter_error([] { create_with(2, -0.1); }, "cohesion_rate");
  expect_parameter_error([] { create_with(4, -0.1 * kDeg); }, "friction_increase");
  expect_parameter_error([] { create_with(6, -1.0); }, "tensile_strength");
  expect_parameter_error([] { create_with(6, -kInf); }, "tensile_strength");
  expect_parameter_error([] { create_with(6, kNaN); }, "tensile_strength");  // +inf: the apex
}

TEST(SuctionStrengthValidate, AcceptsTheBoundsOfEveryRange) {
  EXPECT_NO_THROW(SuctionStrength::create(0.0, 0.0, 0.0, 1e-3, 0.0, 0.0, 0.0));
  EXPECT_NO_THROW(SuctionStrength::create(1e3, 15e3, 0.7, 20 * kDeg, 0.1 * kDeg, 20 * kDeg, 1e9));
  const SuctionStrength law = create_with(2, 0.7);
  EXPECT_EQ(law.cohesion_rate, 0.7);
  EXPECT_EQ(law.friction_increase, 0.1 * kDeg);
}

}  // namespace test_suction_strength
}  // namespace unsatmpm::physics

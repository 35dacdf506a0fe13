// Mohr-Coulomb return mapping in principal stresses (see mohr_coulomb.hpp for the model).
//
// Principal stresses are sorted s1 >= s2 >= s3 (indices 0, 1, 2). Every yield plane is linear in
// principal space, f_i = a_i . s - k_i, with a constant flow direction n_i (the gradient of the
// potential), and the material is perfectly plastic. A return onto a set A of active planes is then
// the linear system (de Souza Neto et al. §8.2, written once for any number of planes)
//   s = x - sum_j dgamma_j D n_j,  a_i . s = k_i (i in A)  =>  M dgamma = f(x),  M = A^T D N,
// with x the trial principal stresses, and its derivative is ds/dx = I - D N M^-1 A^T.
//   face:       plane (1,3);
//   right edge: planes (1,3) and (1,2), s2 = s3;  left edge: planes (1,3) and (2,3), s1 = s2;
//   apex:       s = c cot(phi) (1, 1, 1), ds/dx = 0 (the book's apex return, H = 0).
// The Rankine cut-off s_i <= t is associated. It matters only when t < c cot(phi); its returns are
// tried when the Mohr-Coulomb return leaves s1 > t, over the active sets that can occur with s1 = t
// (kTensionSets), taking the one with dgamma >= 0 whose stress is admissible: the solution of the
// complementarity problem of the return (found unique by a brute-force search over all active sets
// of the six planes, for random trials and parameters, when this was written).
// The Cartesian stress is rebuilt with the eigenvectors of the trial stress; the tangent is the
// derivative of that isotropic tensor function (de Souza Neto et al., Appendix A).
#include "physics/mohr_coulomb.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>

#include "physics/parameter_error.hpp"
#include "physics/principal_stress.hpp"

namespace unsatmpm::physics {

namespace {

// Relative tolerances: of stresses against the stress scale of the call, and of the repeated
// eigenvalue test in the tangent.
constexpr double kStressTolerance = 1e-10;
constexpr double kRepeatedEigenvalue = 1e-9;

struct Plane {
  Vec3 a;    // gradient of the yield plane in principal space
  Vec3 n;    // gradient of the plastic potential (flow direction)
  double k;  // f = a . s - k [Pa]
};

enum PlaneId { kMain, kRight, kLeft, kTension1, kTension2, kTension3, kNumPlanes };

struct ActiveSet {
  int n_planes = 0;
  std::array<int, 3> planes{};
};

// Corners, edges and faces of the cut-off reachable with s1 = t (s1 >= s2 >= s3): the plane s1 = t,
// the lines s1 = s2 = t and {s1 = t, main MC plane}, and the points (t, t, t), (t, s3*, s3*) and
// (t, t, s3*); the last has four active planes, so every triple that spans its flow cone is tried.
constexpr std::array<ActiveSet, 9> kTensionSets{{
    {1, {kTension1}},
    {2, {kTension1, kTension2}},
    {2, {kTension1, kMain}},
    {3, {kTension1, kTension2, kTension3}},
    {3, {kTension1, kMain, kRight}},
    {3, {kTension1, kTension2, kMain}},
    {3, {kTension1, kTension2, kLeft}},
    {3, {kTension1, kMain, kLeft}},
    {3, {kTension2, kMain, kLeft}},
}};

// Everything a return needs that depends only on the elasticity and the strength of the call.
struct Setup : PreparedStrength {
  std::array<Plane, kNumPlanes> planes;
  Mat3 d;  // elastic stiffness in principal space
  double shear_modulus;
};

Setup make_setup(const LinearElastic& elastic, const PreparedStrength& prepared) {
  Setup setup;
  static_cast<PreparedStrength&>(setup) = prepared;
  setup.shear_modulus = elastic.shear_modulus();
  const double lambda = elastic.lame_lambda();
  setup.d = Mat3::Constant(lambda) + 2.0 * setup.shear_modulus * Mat3::Identity();

  const auto mohr_coulomb = [&](int major, int minor) {
    Plane p{Vec3::Zero(), Vec3::Zero(), setup.k};
    p.a[major] = 1.0 + setup.sin_phi;
    p.a[minor] = -(1.0 - setup.sin_phi);
    p.n[major] = 1.0 + setup.sin_psi;
    p.n[minor] = -(1.0 - setup.sin_psi);
    return p;
  };
  const auto rankine = [&](int i) {
    return Plane{Vec3::Unit(i), Vec3::Unit(i), setup.strength.tensile_strength};
  };
  setup.planes = {mohr_coulomb(0, 2), mohr_coulomb(0, 1), mohr_coulomb(1, 2),
                  rankine(0),         rankine(1),         rankine(2)};
  return setup;
}

/// Mohr-Coulomb yield function of sorted principal stresses [Pa].
double mohr_coulomb_yield(const Vec3& s, double sin_phi, double k) {
  return (s[0] - s[2]) + (s[0] + s[2]) * sin_phi - k;
}

/// Yield function of sorted principal stresses: the larger of Mohr-Coulomb and s1 - t [Pa].
double principal_yield(const Vec3& s, double sin_phi, double k, double t) {
  return std::max(mohr_coulomb_yield(s, sin_phi, k), s[0] - t);
}

// Cheap sufficient test for an elastic trial from p and J2 alone: with the Lode angle free,
// s1 - s3 <= 2 sqrt(J2), s1 + s3 <= 2p + sqrt(J2/3) and s1 <= p + 2 sqrt(J2/3). So the trial is
// inside Mohr-Coulomb if sqrt(J2) (2 + sin(phi)/sqrt(3)) < k - 2p sin(phi), and inside the cut-off
// if 2 sqrt(J2/3) < t - p: both tested squared, without a root or a division (the test runs for
// every point at every step). A trial that is not finite passes as elastic, unchanged, so that
// the caller's blow-up check sees it (a return could map it onto the apex, a finite stress).
bool surely_elastic(const Vec6& trial, const PreparedStrength& setup) {
  const double j2 = second_invariant(trial);
  const double p = mean_stress(trial);
  if (!std::isfinite(j2 + p)) return true;
  const double room = setup.k - 2.0 * p * setup.sin_phi;
  if (!(room > 0.0 && j2 * setup.j2_factor < room * room)) return false;
  if (!setup.cut_off) return true;
  const double tension_room = setup.strength.tensile_strength - p;
  return tension_room > 0.0 && 4.0 / 3.0 * j2 < tension_room * tension_room;
}

// Dynamic size bounded by 3: stored inline, never on the heap.
using SmallMat = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 3, 3>;
using SmallVec = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 3, 1>;
using Columns = Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, 3>;

struct ActiveSystem {
  Columns a;   // yield gradients of the active planes
  Columns dn;  // D n of the active planes
  SmallVec k;
};

ActiveSystem gather(const Setup& setup, const ActiveSet& set) {
  ActiveSystem sys{Columns(3, set.n_planes), Columns(3, set.n_planes), SmallVec(set.n_planes)};
  for (int j = 0; j < set.n_planes; ++j) {
    const Plane& plane = setup.planes[set.planes[j]];
    sys.a.col(j) = plane.a;
    sys.dn.col(j) = setup.d * plane.n;
    sys.k[j] = plane.k;
  }
  return sys;
}

/// Return of x onto the planes of `set`; false if M is singular or a multiplier is negative.
bool project(const Setup& setup, const ActiveSet& set, const Vec3& x, double scale, Vec3& y) {
  const ActiveSystem sys = gather(setup, set);
  const SmallMat m = sys.a.transpose() * sys.dn;
  const Eigen::FullPivLU<SmallMat> lu(m);
  if (!lu.isInvertible()) return false;
  const SmallVec f = sys.a.transpose() * x - sys.k;
  const SmallVec dgamma = lu.solve(f);
  // dgamma * 2G is a stress: compare it with the stress scale.
  if ((dgamma.array() * setup.shear_modulus < -kStressTolerance * scale).any()) return false;
  y = x - sys.dn * dgamma;
  return true;
}

/// ds/dx of the return onto the planes of `set`: I - D N M^-1 A^T.
Mat3 projection_derivative(const Setup& setup, const ActiveSet& set) {
  const ActiveSystem sys = gather(setup, set);
  const SmallMat m = sys.a.transpose() * sys.dn;
  const SmallMat m_inv_at = m.fullPivLu().solve(SmallMat(sys.a.transpose()));
  return Mat3::Identity() - sys.dn * m_inv_at;
}

bool is_sorted(const Vec3& s, double scale) {
  const double tol = kStressTolerance * scale;
  return s[0] >= s[1] - tol && s[1] >= s[2] - tol;
}

struct PrincipalReturn {
  MohrCoulombReturn region = MohrCoulombReturn::elastic;
  Vec3 stress = Vec3::Zero();
  ActiveSet active;  // empty for the elastic and apex returns
};

/// The book's return: face, then the edge the trial points at, else the apex.
PrincipalReturn mohr_coulomb_return(const Setup& setup, const Vec3& x, double scale) {
  PrincipalReturn r;
  r.active = {1, {kMain}};
  if (project(setup, r.active, x, scale, r.stress) && is_sorted(r.stress, scale)) {
    r.region = MohrCoulombReturn::face;
    return r;
  }
  const bool right = (1.0 - setup.sin_psi) * x[0] - 2.0 * x[1] + (1.0 + setup.sin_psi) * x[2] > 0;
  r.active = {2, {kMain, right ? kRight : kLeft}};
  if (project(setup, r.active, x, scale, r.stress) && is_sorted(r.stress, scale)) {
    r.region = right ? MohrCoulombReturn::edge_right : MohrCoulombReturn::edge_left;
    return r;
  }
  r.region = MohrCoulombReturn::apex;
  r.active = {};
  r.stress = Vec3::Constant(setup.apex);
  return r;
}

/// Return involving the cut-off: the first candidate set giving an admissible stress.
PrincipalReturn tension_return(const Setup& setup, const Vec3& x, double scale) {
  PrincipalReturn r;
  r.region = MohrCoulombReturn::tension;
  const double tol = kStressTolerance * scale;
  for (const ActiveSet& set : kTensionSets) {
    if (!project(setup, set, x, scale, r.stress)) continue;
    Vec3 sorted = r.stress;
    std::sort(sorted.begin(), sorted.end(), std::greater<>());
    if (principal_yield(sorted, setup.sin_phi, setup.k, setup.strength.tensile_strength) <= tol) {
      r.active = set;
      return r;
    }
  }
  // Never reached in the tests nor in the random search above (the candidates cover every corner
  // of the cut-off); the cut-off apex is an admissible answer.
  r.active = kTensionSets[3];
  r.stress = Vec3::Constant(setup.strength.tensile_strength);
  return r;
}

PrincipalReturn principal_return(const Setup& setup, const Vec3& x) {
  const double scale = std::max({std::abs(x[0]), std::abs(x[2]), setup.k, 1e-300});
  const double t = setup.strength.tensile_strength;
  const bool mc_admissible = mohr_coulomb_yield(x, setup.sin_phi, setup.k) <= 0.0;
  if (mc_admissible && (!setup.cut_off || x[0] <= t)) return PrincipalReturn{};
  if (!mc_admissible) {
    const PrincipalReturn r = mohr_coulomb_return(setup, x, scale);
    if (!setup.cut_off || r.stress[0] <= t + kStressTolerance * scale) return r;
  }
  return tension_return(setup, x, scale);
}

/// ds/dx (3x3, sorted principal space) of a return.
Mat3 principal_derivative(const Setup& setup, const PrincipalReturn& r) {
  if (r.region == MohrCoulombReturn::elastic) return Mat3::Identity();
  if (r.region == MohrCoulombReturn::apex) return Mat3::Zero();
  return projection_derivative(setup, r.active);
}

/// Derivative of the isotropic tensor function sigma = sum_i y_i(x) e_i (x) e_i of the trial stress
/// as a Voigt 6x6 (de Souza Neto et al., App. A): normal part dy/dx; shear part
/// (y_i - y_j)/(x_i - x_j), or its limit dy_i/dx_i - dy_i/dx_j for repeated eigenvalues.
Mat6 isotropic_derivative(const Principal& trial, const Vec3& y, const Mat3& dy_dx) {
  const Vec3& x = trial.values;
  const double scale = std::max({std::abs(x[0]), std::abs(x[2]), 1e-300});
  Mat3 shear = Mat3::Zero();
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      if (i == j) continue;
      shear(i, j) = std::abs(x[i] - x[j]) > kRepeatedEigenvalue * scale
                        ? (y[i] - y[j]) / (x[i] - x[j])
                        : dy_dx(i, i) - dy_dx(i, j);
    }
  }
  const Mat3& q = trial.vectors;
  Mat6 l;
  for (int k = 0; k < 6; ++k) {
    const Mat3 h = q.transpose() * stress_tensor(Vec6::Unit(k)) * q;
    Mat3 response = shear.cwiseProduct(h);
    response.diagonal() = dy_dx * h.diagonal();
    l.col(k) = stress_voigt(q * response * q.transpose());
  }
  return l;
}

/// sqrt(2/3 de_p:de_p) of the plastic strain D^-1 (x - y): its deviatoric part is dev(x - y)/2G.
double plastic_deviatoric_strain(const Vec3& x, const Vec3& y, double shear_modulus) {
  const Vec3 ds = x - y;
  const Vec3 dev = ds.array() - ds.mean();
  return std::sqrt(2.0 / 3.0) * dev.norm() / (2.0 * shear_modulus);
}

}  // namespace

MohrCoulomb MohrCoulomb::create(const LinearElastic& elastic, const MohrCoulombStrength& strength) {
  validate(strength);
  return MohrCoulomb{LinearElastic::create(elastic.young_modulus, elastic.poisson_ratio), strength};
}

void MohrCoulomb::validate(const MohrCoulombStrength& s) {
  require_in_range("cohesion", s.cohesion, 0.0, std::numeric_limits<double>::infinity(), "Pa");
  require_in_open_range("friction_angle", s.friction_angle, 0.0, std::numbers::pi / 2.0, "rad");
  require_in_range("dilatancy_angle", s.dilatancy_angle, 0.0, s.friction_angle, "rad");
  // The relative slack admits a c / tan(phi) that the caller computed another way.
  const double apex = s.cohesion / std::tan(s.friction_angle) * (1.0 + 1e-12);
  require_in_range("tensile_strength", s.tensile_strength, 0.0, apex, "Pa");
}

double MohrCoulomb::yield_function(const Vec6& sigma, const MohrCoulombStrength& strength) {
  const Vec3 s = principal_stresses(sigma).values;
  const double k = 2.0 * strength.cohesion * std::cos(strength.friction_angle);
  return principal_yield(s, std::sin(strength.friction_angle), k, strength.tensile_strength);
}

PreparedStrength MohrCoulomb::prepare(const MohrCoulombStrength& s) {
  PreparedStrength r;
  r.strength = s;
  r.sin_phi = std::sin(s.friction_angle);
  r.sin_psi = std::sin(s.dilatancy_angle);
  const double cos_phi = std::cos(s.friction_angle);
  r.k = 2.0 * s.cohesion * cos_phi;
  r.apex = s.cohesion * cos_phi / r.sin_phi;
  r.cut_off = s.tensile_strength < r.apex;
  const double bound = 2.0 + r.sin_phi / std::sqrt(3.0);
  r.j2_factor = bound * bound;
  return r;
}

MohrCoulombReturn MohrCoulomb::update(const Vec6& d_eps, const PreparedStrength& current,
                                      Vec6& sigma, MohrCoulombState& state) const {
  Vec6 trial = sigma;
  elastic.add_elastic_increment(d_eps, trial);
  if (surely_elastic(trial, current)) {
    sigma = trial;
    return MohrCoulombReturn::elastic;
  }
  const Setup setup = make_setup(elastic, current);
  const Principal principal = principal_stresses(trial);
  const PrincipalReturn r = principal_return(setup, principal.values);
  if (r.region == MohrCoulombReturn::elastic) {
    sigma = trial;
    return r.region;
  }
  const Mat3& q = principal.vectors;
  sigma = stress_voigt(q * r.stress.asDiagonal() * q.transpose());
  state.deviatoric_plastic_strain +=
      plastic_deviatoric_strain(principal.values, r.stress, setup.shear_modulus);
  return r.region;
}

Mat6 MohrCoulomb::consistent_tangent(const Vec6& sigma_n, const Vec6& d_eps,
                                     const MohrCoulombStrength& current) const {
  Vec6 trial = sigma_n;
  elastic.add_elastic_increment(d_eps, trial);
  const PreparedStrength prepared = prepare(current);
  if (surely_elastic(trial, prepared)) return elastic.stiffness();
  const Setup setup = make_setup(elastic, prepared);
  const Principal principal = principal_stresses(trial);
  const PrincipalReturn r = principal_return(setup, principal.values);
  if (r.region == MohrCoulombReturn::elastic) return elastic.stiffness();
  const Mat3 dy_dx = principal_derivative(setup, r);
  return isotropic_derivative(principal, r.stress, dy_dx) * elastic.stiffness();
}

}  // namespace unsatmpm::physics

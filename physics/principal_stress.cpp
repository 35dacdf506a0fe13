#include "physics/principal_stress.hpp"

#include <Eigen/Eigenvalues>
#include <array>
#include <cmath>
#include <utility>

namespace unsatmpm::physics {

namespace {

/// The in-plane pair and sigma_zz (see the header), sorted.
Principal in_plane(const Vec6& sigma) {
  const double c = 0.5 * (sigma[0] + sigma[1]), h = 0.5 * (sigma[0] - sigma[1]), b = sigma[3];
  const double r = std::sqrt(h * h + b * b);  // stresses far below 1e150 Pa: no overflow
  double ux = 1.0, uy = 0.0;  // the major in-plane direction; any unit vector when r = 0
  if (r > 0.0) {
    ux = h >= 0.0 ? h + r : b;
    uy = h >= 0.0 ? b : r - h;
    const double norm = std::sqrt(ux * ux + uy * uy);
    ux /= norm, uy /= norm;
  }
  std::array<double, 3> values{c + r, c - r, sigma[2]};
  std::array<Vec3, 3> vectors{Vec3(ux, uy, 0.0), Vec3(-uy, ux, 0.0), Vec3::UnitZ()};
  // Three compares sort them descending, each value with its vector.
  const auto order = [&](int i, int j) {
    if (values[i] < values[j]) std::swap(values[i], values[j]), std::swap(vectors[i], vectors[j]);
  };
  order(1, 2), order(0, 1), order(1, 2);
  Principal p;
  for (int i = 0; i < 3; ++i) p.values[i] = values[i], p.vectors.col(i) = vectors[i];
  return p;
}

}  // namespace

Principal principal_stresses(const Vec6& sigma) {
  if (sigma[4] == 0.0 && sigma[5] == 0.0) return in_plane(sigma);
  const Eigen::SelfAdjointEigenSolver<Mat3> solver(stress_tensor(sigma));
  return {solver.eigenvalues().reverse(), solver.eigenvectors().rowwise().reverse()};
}

}  // namespace unsatmpm::physics

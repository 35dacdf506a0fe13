#include "physics/linear_elastic.hpp"

#include "physics/parameter_error.hpp"

namespace unsatmpm::physics {

LinearElastic LinearElastic::create(double young_modulus, double poisson_ratio) {
  require_in_open_range("young_modulus", young_modulus, 0.0, 1e15, "Pa");
  // nu = 0.5 makes the bulk modulus infinite; negative nu is admissible in theory but never a soil.
  require_in_range("poisson_ratio", poisson_ratio, 0.0, 0.499, "-");
  return LinearElastic{young_modulus, poisson_ratio};
}

Mat6 LinearElastic::stiffness() const {
  const double lambda = lame_lambda(), g = shear_modulus();
  Mat6 d = Mat6::Zero();
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) d(i, j) = lambda;
    d(i, i) = lambda + 2.0 * g;
    d(i + 3, i + 3) = g;
  }
  return d;
}

}  // namespace unsatmpm::physics

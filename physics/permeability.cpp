#include "physics/permeability.hpp"

#include "physics/parameter_error.hpp"

namespace unsatmpm::physics {

// Parameter names are the input keys: the case parser reports the error at the key it names.
PowerRelPerm PowerRelPerm::create(double exponent) {
  require_in_range("exponent", exponent, 1.0, 20.0, "-");
  return {exponent};
}

MualemVanGenuchten MualemVanGenuchten::create(double lambda) {
  require_in_open_range("lambda", lambda, 0.0, 1.0, "-");
  return {lambda};
}

GasPowerRelPerm GasPowerRelPerm::create(double exponent) {
  require_in_range("exponent", exponent, 1.0, 20.0, "-");
  return {exponent};
}

}  // namespace unsatmpm::physics

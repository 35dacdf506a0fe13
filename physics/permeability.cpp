#include "physics/permeability.hpp"

#include "physics/parameter_error.hpp"

#include <string>

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

TabulatedRelPerm TabulatedRelPerm::create(const std::vector<std::array<double, 2>>& points,
                                          bool gas) {
  if (!points.empty() && points.front()[0] != 0.0)
    throw ParameterError("points[0]", "the first point must be at effective saturation 0, got " +
                                          number_text(points.front()[0]));
  TabulatedRelPerm k{MonotoneTable::create(
      points, gas ? MonotoneTable::Direction::decreasing : MonotoneTable::Direction::increasing,
      0.0, 1.0, "effective saturation", "relative permeability")};
  if (k.table.last_x() != 1.0)
    throw ParameterError(
        "points[" + std::to_string(points.size() - 1) + "]",
        "the last point must be at effective saturation 1, got " + number_text(k.table.last_x()));
  return k;
}

}  // namespace unsatmpm::physics

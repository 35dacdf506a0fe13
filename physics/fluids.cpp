#include "physics/fluids.hpp"

#include "physics/parameter_error.hpp"

namespace unsatmpm::physics {

CompressibleFluid CompressibleFluid::create(double reference_density, double reference_pressure,
                                            double bulk_modulus) {
  // Parameter names are the input keys: the case parser reports the error at the key it names.
  require_in_open_range("density", reference_density, 0.0, 1e5, "kg/m^3");
  require_in_range("reference_pressure", reference_pressure, -1e9, 1e9, "Pa");
  require_in_open_range("bulk_modulus", bulk_modulus, 0.0, 1e13, "Pa");
  return {reference_density, reference_pressure, bulk_modulus};
}

IdealGas IdealGas::create(double reference_density) {
  require_in_open_range("density", reference_density, 0.0, 1e3, "kg/m^3");
  return {reference_density};
}

}  // namespace unsatmpm::physics

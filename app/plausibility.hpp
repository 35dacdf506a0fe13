// Warnings for physics parameters that no soil has, the marks of a value in the wrong unit
// (docs/input.md, "Rules": units): the input accepts any value the models are defined for, so a
// Young's modulus of 10 Pa meant as 10 MPa ran and failed at its second step with a numerical
// failure (docs/known_failures.md). Warnings, not errors: a model may be meant for another
// material.
#pragma once

#include <string>
#include <vector>

#include "input/case.hpp"

namespace unsatmpm {

/// One message per parameter outside the range of soils: Young's modulus outside
/// [1e4, 1e12] Pa, a solid or grain density outside [100, 2e4] kg/m^3, an intrinsic permeability
/// above 1e-7 m^2 (a gravel's is about 1e-9; a hydraulic conductivity in m/s given as kappa is the
/// usual slip).
std::vector<std::string> implausible_parameters(const Case& c);

}  // namespace unsatmpm

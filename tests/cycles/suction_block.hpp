// A block of van Genuchten soil at a uniform suction, standing free in a 2 m x 2 m grid, for the
// explicit three-phase cycle's tests (test_three_phase_cycle.cpp, test_three_phase_masses.cpp).
#pragma once

#include <string>

#include "input/case_parser.hpp"

namespace unsatmpm::test_blocks {

/// A block at a uniform suction of 10 kPa (van Genuchten soil) standing free in a 2 m x 2 m grid,
/// with the `gravity` and `box` given (YAML flow sequences and maps).
inline Case block_under_suction(const std::string& gravity, const std::string& box) {
  return parse_case_text(R"(
name: block
dimension: 2
grid: {origin: [0, 0], size: [2, 2], cells: [20, 20]}
shape_function: gimp
gravity: )" + gravity + R"(
phases: solid_liquid_gas
fluids:
  liquid: {density: 1000, bulk_modulus: 2.0e+8, viscosity: 1.0e-3}
  gas: {model: ideal, density: 1.2, viscosity: 1.8e-5}
mass_balance: full
materials:
  - {name: soil, model: linear_elastic, young_modulus: 1.0e+6, poisson_ratio: 0.3,
     solid_density: 2700, porosity: 0.4, intrinsic_permeability: 1.0e-11,
     retention: {model: van_genuchten, p0: 2.0e+4, lambda: 0.4, residual_saturation: 0.1},
     liquid_relative_permeability: {model: mualem_van_genuchten, lambda: 0.4},
     gas_relative_permeability: {model: power, exponent: 3}}
bodies:
  - {name: block, material: soil, points_per_cell: 2, box: )" +
                             box + R"(,
     initial_state: {suction: 1.0e+4, gas_pressure: 0}}
solver: {end_time: 1, damping: 0}
output: {times: [1]}
)",
                         "<test>");
}

}  // namespace unsatmpm::test_blocks

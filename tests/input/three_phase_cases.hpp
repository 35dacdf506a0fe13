// Three-phase case texts shared by the case-parser tests (test_case_parser_hydraulics.cpp,
// test_case_parser_implicit.cpp).
#pragma once

#include <string>

namespace unsatmpm::test_support {

// The paper's infiltration column (verification/infiltration), as in docs/input.md.
inline const std::string column_1d = R"(name: infiltration
dimension: 1
grid: {origin: [0], size: [1], cells: [40]}
shape_function: linear
gravity: [0]
phases: solid_liquid_gas
fluids:
  liquid: {density: 1000, bulk_modulus: 8.0e7, viscosity: 1.0e-3}
  gas: {model: ideal, density: 1.2, viscosity: 1.8e-5}
mass_balance: full
skeleton: rigid
materials:
  - name: soil
    model: linear_elastic
    young_modulus: 1.0e7
    poisson_ratio: 0.3
    solid_density: 2700
    porosity: 0.3
    intrinsic_permeability: 5.0e-11
    retention: {model: linear, a_s: 1.0e-6}
    liquid_relative_permeability: {model: constant}
    gas_relative_permeability: {model: constant}
bodies:
  - name: column
    material: soil
    points_per_cell: 4
    box: {min: [0], max: [1]}
    initial_state: {suction: 5.0e5, gas_pressure: 0}
boundaries:
  - name: top
    plane: {axis: x, at: 1}
    liquid: {suction: 0}
    gas: {pressure: 0}
  - name: bottom
    plane: {axis: x, at: 0}
    gas: {pressure: 0}
solver:
  end_time: 6
  damping: 0
output: {}
)";

// Every other model and form: van Genuchten, Mualem, power laws, a gas with a bulk modulus, a
// ramp, a table, a liquid-pressure initial state, boundaries with and without mechanics.
inline const std::string slope_2d = R"(name: slope_rain
dimension: 2
grid: {origin: [0, 0], size: [4, 2], cells: [8, 4]}
shape_function: gimp
gravity: [0, -9.81]
phases: solid_liquid_gas
fluids:
  liquid: {density: 1000, bulk_modulus: 1.0e8, viscosity: 1.0e-3, reference_pressure: 100}
  gas: {model: bulk_modulus, density: 1, bulk_modulus: 1.0e4, viscosity: 1.8e-5}
mass_balance: simplified
pressure_update: pointwise
materials:
  - name: clay
    model: mohr_coulomb
    young_modulus: 1.0e7
    poisson_ratio: 0.33
    cohesion: 1000
    friction_angle: 20
    solid_density: 2700
    porosity: 0.35
    intrinsic_permeability: 1.0e-10
    retention: {model: van_genuchten, p0: 2.0e4, lambda: 0.4, residual_saturation: 0.1}
    liquid_relative_permeability: {model: mualem_van_genuchten, lambda: 0.4}
    gas_relative_permeability: {model: power, exponent: 3}
    maximum_porosity: 0.6
  - {name: sand, model: linear_elastic, young_modulus: 5.0e7, poisson_ratio: 0.25,
     solid_density: 2650, porosity: 0.4, intrinsic_permeability: 1.0e-11,
     retention: {model: linear, a_s: 1.0e-5, residual_saturation: 0.05},
     liquid_relative_permeability: {model: power, exponent: 3},
     gas_relative_permeability: {model: constant}}
bodies:
  - name: ground
    material: clay
    points_per_cell: 2
    box: {min: [0, 0], max: [4, 1]}
    initial_state: {liquid_pressure: -8.0e5, gas_pressure: 0}
  - {name: layer, material: sand, points_per_cell: 2, box: {min: [0, 1], max: [4, 2]},
     initial_state: {suction: 2.0e4, gas_pressure: 100}}
boundaries:
  - {name: base, plane: {axis: y, at: 0}, mechanical: fixed}
  - name: surface
    plane: {axis: y, at: 2}
    liquid: {suction: {ramp: {from: 8.0e5, to: 0, start: 0, end: 10}}}
    gas: {pressure: 0}
  - name: right
    plane: {axis: x, at: 4}
    mechanical: roller
    liquid: {pressure: {table: [[0, 0], [5, 1.0e4], [20, 2.5e4]]}}
solver: {end_time: 20, damping: 0.05}
output: {}
)";

inline const std::string solid_1d = R"(name: bar
dimension: 1
grid: {origin: [0], size: [1], cells: [10]}
shape_function: linear
gravity: [0]
materials: [{name: m, density: 1000, model: linear_elastic, young_modulus: 1e6, poisson_ratio: 0}]
bodies: [{name: bar, material: m, points_per_cell: 2, box: {min: [0], max: [1]}}]
boundaries: [{name: base, plane: {axis: x, at: 0}, mechanical: fixed}]
solver: {end_time: 1, damping: 0}
output: {}
)";

}  // namespace unsatmpm::test_support

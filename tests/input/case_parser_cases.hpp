// The case texts the case-parser tests edit (test_case_parser.cpp, test_case_parser_errors.cpp):
// a 2D column with two bodies and boundaries, a 1D bar with a sine velocity, a 3D slope.
#pragma once

#include <string>

namespace unsatmpm::test_case_parser {

inline const std::string case_2d = R"(name: column_selfweight
dimension: 2
grid: {origin: [0, 0], size: [1.0, 4.0], cells: [4, 16]}
shape_function: linear
gravity: [0, -9.81]
materials:
  - name: soil
    density: 1800
    model: mohr_coulomb
    young_modulus: 1.0e7
    poisson_ratio: 0.3
    cohesion: 5000
    friction_angle: 30
  - {name: stiff, density: 2000, model: linear_elastic, young_modulus: 1.0e8, poisson_ratio: 0.25}
bodies:
  - name: column
    material: soil
    points_per_cell: 2
    box: {min: [0, 0], max: [1, 2]}
  - name: wedge
    material: stiff
    points_per_cell: 3
    polygon: {vertices: [[0, 2], [1, 2], [0, 4]]}
    initial_velocity: [0, -0.5]
boundaries:
  - name: base
    plane: {axis: y, at: 0.0}
    mechanical: fixed
  - {name: left, plane: {axis: x, at: 0}, mechanical: roller}
solver:
  end_time: 1.0
  damping: 0.05
output:
  times: [0.1, 0.2]
  control_points:
    - {name: tip, position: [0.5, 4.0]}
)";

inline const std::string case_1d = R"(name: bar
dimension: 1
grid: {origin: [-1], size: [2], cells: [20]}
shape_function: gimp
gravity: [0]
materials: [{name: m, density: 1000, model: linear_elastic, young_modulus: 1e6, poisson_ratio: 0}]
bodies:
  - {name: bar, material: m, points_per_cell: 4, box: {min: [-1], max: [1]},
     initial_velocity: {sine: {amplitude: [0.01], axis: x, wavenumber: 1.5708}}}
solver: {end_time: 2, time_step: {fixed: 1.0e-4}, damping: 0, flip_fraction: 0.99}
output: {history_interval: 0.01, write_grid: false}
)";

inline const std::string case_3d = R"(name: slope
dimension: 3
grid: {origin: [0, 0, 0], size: [10, 5, 1], cells: [20, 10, 2]}
shape_function: gimp
gravity: [0, -9.81, 0]
materials:
  - {name: clay, density: 1900, model: mohr_coulomb, young_modulus: 2e7, poisson_ratio: 0.3,
     cohesion: 10e3, friction_angle: 20, dilatancy_angle: 5, tensile_strength: 1000}
bodies:
  - {name: slope, material: clay, points_per_cell: 2,
     polygon: {vertices: [[0, 0], [10, 0], [10, 2], [0, 5]], extrude_z: [0, 1]}}
boundaries:
  - {name: back, plane: {axis: z, at: 0.5}, mechanical: roller}
solver: {end_time: 3, time_step: {cfl_safety: 0.8}, damping: 0.1}
output: {}
)";

}  // namespace unsatmpm::test_case_parser

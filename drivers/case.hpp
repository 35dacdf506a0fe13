// The case: everything a run needs, parsed from one YAML file (docs/input.md documents each key).
//
// Dimension-independent: vectors are std::vector<double> whose length the parser checks against
// `dimension`. Every physics parameter is required; numerical parameters have stated defaults that
// the effective configuration echoes. Units are SI throughout (m, s, kg, Pa); angles are given in
// degrees in the file and stored in radians here.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "physics/linear_elastic.hpp"
#include "physics/mohr_coulomb.hpp"

namespace unsatmpm::drivers {

struct GridSpec {
  std::vector<double> origin;  // lower corner [m], `dimension` entries
  std::vector<double> size;    // extent [m], > 0
  std::vector<int> cells;      // cells per direction, >= 2 (GIMP needs 3 nodes)
};

enum class ShapeFunctionKind { linear, gimp };

/// A solid material: density of the (dry, one-phase) continuum and its constitutive model.
struct MaterialSpec {
  std::string name;
  double density;  // [kg/m^3]
  std::variant<physics::LinearElastic, physics::MohrCoulomb> model;
};

struct BoxGeometry {
  std::vector<double> min, max;  // [m]
};
/// A polygon in the x-y plane (2D), or extruded along z from z_min to z_max (3D).
struct PolygonGeometry {
  std::vector<std::array<double, 2>> vertices;     // counter-clockwise or clockwise, >= 3
  std::optional<std::array<double, 2>> extrude_z;  // required in 3D, forbidden in 1D/2D
};
using Geometry = std::variant<BoxGeometry, PolygonGeometry>;

/// v(x) = amplitude * sin(wavenumber * (x[axis] - origin)): a mode shape for vibration tests.
struct SineVelocity {
  std::vector<double> amplitude;  // [m/s]
  int axis;                       // 0 = x, 1 = y, 2 = z
  double wavenumber;              // [1/m]
  double origin;                  // [m]
};
using InitialVelocity = std::variant<std::vector<double>, SineVelocity>;  // constant or sine

struct BodySpec {
  std::string name;
  int material;         // index into Case::materials (parsed from the material's name)
  int points_per_cell;  // k: k^D points per cell, evenly spaced at cell fractions (i + 1/2)/k
  Geometry geometry;
  InitialVelocity initial_velocity;  // default: zero
};

/// Axis-aligned plane {x[axis] == coordinate}; selects the grid nodes on it.
struct PlaneRegion {
  int axis;
  double coordinate;  // [m]; must coincide with a grid node plane
};

enum class MechanicalCondition { fixed, roller };

struct BoundarySpec {
  std::string name;
  PlaneRegion region;
  MechanicalCondition mechanical;
};

struct TimeStepSpec {
  std::optional<double> fixed;  // [s]; when absent the CFL estimate is used
  double cfl_safety = 0.5;      // fraction of the CFL limit, in (0, 1]
};

struct SolverSpec {
  double end_time;  // [s] > 0
  TimeStepSpec time_step;
  double damping;              // local damping alpha in [0, 1); required
  double flip_fraction = 1.0;  // FLIP/PIC blend of the G2P velocity update, in [0, 1]
};

struct ControlPoint {
  std::string name;
  std::vector<double> position;  // [m]; the material point nearest to it at t = 0 is tracked
};

struct OutputSpec {
  std::vector<double> times;                 // [s], ascending; t = 0 and end_time always written
  std::vector<ControlPoint> control_points;  // CSV histories, every `history_interval`
  double history_interval = 0.0;             // [s]; 0 = every step
  bool write_grid = true;                    // grid .vtu beside the MP .vtu
};

struct Case {
  std::string file;  // path of the YAML file it came from
  std::string name;
  int dimension;  // 1, 2 or 3
  GridSpec grid;
  ShapeFunctionKind shape_function;
  std::vector<double> gravity;  // [m/s^2], `dimension` entries (required: write zeros for none)
  std::vector<MaterialSpec> materials;
  std::vector<BodySpec> bodies;
  std::vector<BoundarySpec> boundaries;
  SolverSpec solver;
  OutputSpec output;
};

}  // namespace unsatmpm::drivers

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

#include "physics/fluids.hpp"
#include "physics/hydrostatic.hpp"
#include "physics/linear_elastic.hpp"
#include "physics/mohr_coulomb.hpp"
#include "physics/permeability.hpp"
#include "physics/retention.hpp"
#include "physics/scheme.hpp"
#include "physics/suction_strength.hpp"

namespace unsatmpm {

struct GridSpec {
  std::vector<double> origin;  // lower corner [m], `dimension` entries
  std::vector<double> size;    // extent [m], > 0
  std::vector<int> cells;      // cells per direction, >= 2 (GIMP needs 3 nodes)
};

enum class ShapeFunctionKind { linear, gimp };

/// Hydraulic properties of a material in a three-phase case (docs/models.md).
struct HydraulicSpec {
  double solid_density;           // rho_s of the grains [kg/m^3]
  double porosity;                // initial n [-], in (0, 1)
  double intrinsic_permeability;  // kappa [m^2]
  physics::RetentionCurve retention;
  physics::LiquidRelPerm liquid_relative_permeability;
  physics::GasRelPerm gas_relative_permeability;
  std::optional<double> maximum_porosity = {};  // n_max in (n, 1); absent: no bound
};

/// A solid material and its constitutive model. `density` is the mass of solid per unit volume
/// of mixture [kg/m^3]: the bulk density of a dry case, (1 - n) rho_s of a three-phase case
/// (where the file gives solid_density and porosity instead, in `hydraulic`).
struct MaterialSpec {
  std::string name;
  double density;  // [kg/m^3]
  physics::SolidModel model;
  std::optional<HydraulicSpec> hydraulic = {};  // present exactly in three-phase cases
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

/// A function of time: piecewise linear through (t, value) points, constant before the first
/// and after the last. One point is a constant; two make a ramp. Times strictly ascending.
struct TimeFunction {
  std::vector<std::array<double, 2>> points;  // (time [s], value)
  double operator()(double t) const {
    if (t <= points.front()[0]) return points.front()[1];
    for (std::size_t i = 1; i < points.size(); ++i)
      if (t < points[i][0]) {
        const auto& a = points[i - 1];
        const auto& b = points[i];
        return a[1] + (b[1] - a[1]) * (t - a[0]) / (b[0] - a[0]);
      }
    return points.back()[1];
  }
  /// Mean over [t0, t1] (t1 > t0; exact for the piecewise-linear function), or the value at t0
  /// if t1 <= t0.
  double mean(double t0, double t1) const {
    if (!(t1 > t0)) return (*this)(t0);
    // Integrate segment by segment between t0, the breakpoints inside (t0, t1), and t1.
    double integral = 0.0, ta = t0, va = (*this)(t0);
    for (const auto& p : points)
      if (p[0] > t0 && p[0] < t1) {
        integral += 0.5 * (va + p[1]) * (p[0] - ta);
        ta = p[0], va = p[1];
      }
    integral += 0.5 * (va + (*this)(t1)) * (t1 - ta);
    return integral / (t1 - t0);
  }
  /// d/dt [1/s times the value's unit]: the slope of the segment t lies in (the later segment at
  /// a breakpoint), 0 before the first and after the last point.
  double rate(double t) const {
    for (std::size_t i = 1; i < points.size(); ++i)
      if (t >= points[i - 1][0] && t < points[i][0])
        return (points[i][1] - points[i - 1][1]) / (points[i][0] - points[i - 1][0]);
    return 0.0;
  }
};

/// A body's initial pore pressures [Pa, gauge, compression positive]: uniform (liquid_pressure,
/// gas_pressure); at rest about a water table (physics/hydrostatic.hpp), whose gas_pressure is
/// the gas pressure at the table; or a liquid pressure tabulated against elevation.
struct InitialPressures {
  double liquid_pressure;  // [Pa]; unused with a water table or a profile
  double gas_pressure;     // [Pa]
  std::optional<physics::WaterTable> water_table = {};
  // P_l [Pa] against elevation [m] (against gravity), piecewise linear, constant beyond its ends;
  // held in the time-function type, its abscissa the elevation.
  std::optional<TimeFunction> liquid_profile = {};
};

struct BodySpec {
  std::string name;
  int material;         // index into Case::materials (parsed from the material's name)
  int points_per_cell;  // k: k^D points per cell, evenly spaced at cell fractions (i + 1/2)/k
  Geometry geometry;
  InitialVelocity initial_velocity;                        // default: zero
  std::optional<InitialPressures> initial_pressures = {};  // required in three-phase cases
  std::optional<double> k0 = {};  // initial_stress.k0: K0 stresses (cycles/initial_stress.hpp)
};

/// A prescribed liquid condition: the liquid pressure itself, or the suction P_g - P_l (then the
/// liquid pressure is the boundary's gas pressure minus it, and the boundary must prescribe gas).
struct LiquidCondition {
  enum class Kind { pressure, suction } kind;
  TimeFunction value;  // [Pa]
};

/// Axis-aligned plane {x[axis] == coordinate}; selects the grid nodes on it.
struct PlaneRegion {
  int axis;
  double coordinate;  // [m]; must coincide with a grid node plane
};

/// fixed: every velocity component zero; roller: the normal one; rigid_plate: the nodes share one
/// normal velocity, free along the plane (a rigid frictionless plate, numerics/rigid_plates.hpp).
enum class MechanicalCondition { fixed, roller, rigid_plate };

/// A surface load on a boundary plane (cycles/tractions.hpp), in both cycles: a normal pressure
/// that pushes into the body, and optionally a shear traction along a grid axis in the plane.
/// It is a total-stress load: the mixture carries it, the fluids see it through the skeleton.
struct TractionSpec {
  TimeFunction normal;                  // [Pa], compression positive (pushes into the body)
  int shear_axis = -1;                  // grid axis of the shear, in the plane; -1: no shear
  TimeFunction shear = {{{0.0, 0.0}}};  // [Pa], along +shear_axis
  std::string where;  // "FILE:LINE:COLUMN: KEY.PATH" of the key, for set-up errors
};

/// A boundary region and what it prescribes. Absent conditions are free (mechanics: traction
/// free; liquid and gas: impervious).
struct BoundarySpec {
  std::string name;
  PlaneRegion region;
  std::optional<MechanicalCondition> mechanical = {};
  std::optional<LiquidCondition> liquid = {};     // three-phase cases only
  std::optional<TimeFunction> gas_pressure = {};  // [Pa]; three-phase cases only
  std::optional<TractionSpec> traction = {};
};

/// Fluid conditions on the free surface of the bodies (three-phase cases, implicit cycle): the
/// outer layer of the active grid region (numerics::PressureSystem::set_surface_prescribed),
/// found again at every coupling interval, so the condition follows the body as it deforms.
/// Conditions on planes take precedence where both apply.
/// Rainfall: an intensity [mm/h] falling along gravity; each grid column's rain reaches the
/// topmost material point in it, which passes it to its free-surface nodes (cycles/rainfall.hpp);
/// a node whose suction reaches zero ponds (zero suction, held) until the soil would
/// take more than the rain brings, and any surface node where the liquid pressure reaches the
/// gas pressure becomes a seepage face (cycles/implicit_solver.hpp).
struct SurfaceSpec {
  std::optional<LiquidCondition> liquid = {};     // prescribed pressure or suction, or
  std::optional<TimeFunction> rainfall = {};      // rainfall intensity [mm/h] (one of the two)
  std::optional<TimeFunction> gas_pressure = {};  // [Pa]
};

enum class Phases { solid, solid_liquid_gas };
// Where the explicit cycle solves the fluid mass balances: at each point (the paper's), or at the
// nodes with the increments interpolated back to the points (docs/balance_laws.md).
enum class PressureUpdate { pointwise, nodal };

/// The pore fluids of a three-phase case.
struct FluidsSpec {
  physics::CompressibleFluid liquid;
  double liquid_viscosity;  // mu_l [Pa s]
  physics::GasLaw gas;
  double gas_viscosity;  // mu_g [Pa s]
};

struct TimeStepSpec {
  std::optional<double> fixed;  // [s]; when absent the CFL estimate is used
  double cfl_safety = 0.5;      // fraction of the CFL limit, in (0, 1]
};

/// The computational cycle (docs/cycles.md): the paper's explicit dynamic one, or explicit
/// mechanics with the fluid mass balances as an implicit ODE in the nodal pressures (three-phase
/// only).
enum class Cycle { explicit_dynamic, implicit_pressure };

/// The linear solver of the flow's Newton systems (solver.implicit.linear_solver): a sparse LU,
/// GMRES with algebraic multigrid, or chosen by the number of pressure unknowns.
enum class FlowLinearSolver { automatic, direct, iterative };
/// The sparse LU of the direct solver (solver.implicit.direct_solver): UMFPACK or KLU.
enum class FlowDirectSolver { umfpack, klu };

/// Where the flow takes each point's relative permeabilities
/// (solver.implicit.relative_permeability, docs/balance_laws.md "The relative permeability at the
/// points or from the nodes"): the laws at the point's interpolated pressures, or the points'
/// weights over the laws at each stencil node's pressures.
enum class RelativePermeabilityAt { points, nodes };

/// Settings of the implicit cycle (solver.implicit).
struct ImplicitSpec {
  double relative_tolerance = 1e-6;  // CVODE's local error test [-]
  double absolute_tolerance = 1.0;   // [Pa], on the nodal pressures
  // Interval [s] of the staggered coupling: mechanics sub-cycles over it, then the flow is
  // integrated once. Absent: chosen automatically (see ImplicitSolver).
  std::optional<double> coupling_interval;
  FlowLinearSolver linear_solver = FlowLinearSolver::automatic;
  FlowDirectSolver direct_solver = FlowDirectSolver::umfpack;
  // The free surface's liquid condition as a penalty on the face's trace with this factor [-]
  // (numerics/pressure/surface_penalty.hpp); 0: the surface node layer held.
  double surface_penalty = 0.0;
  RelativePermeabilityAt relative_permeability = RelativePermeabilityAt::points;
};

/// Gravity loading before t = 0 (solver.gravity_loading): explicit mechanics steps under gravity
/// with the fluid pressures held, and local damping, until the nodal forces balance; then
/// displacements, velocities and plastic strains are reset and the run starts from the stresses
/// reached. Balance: sum over free nodal force components |f| <= tolerance * sum_i m_i |g|.
struct GravityLoadingSpec {
  double damping;    // local damping alpha during the loading, in [0, 1)
  double tolerance;  // force ratio [-], in (0, 1)
  double max_time;   // [s] of loading time; not balanced by then: an error
};

/// When a run ends before its end time because the body has come to rest
/// (solver.stop_at_rest; app/rest_monitor.hpp).
struct RestSpec {
  double fraction;  // of the largest kinetic energy so far, in (0, 1)
  double hold;      // [s] > 0 the kinetic energy stays below that fraction
  double min_peak;  // [J, per metre out of plane in 2D] > 0 the peak must exceed first
};

struct SolverSpec {
  double end_time;  // [s] > 0
  TimeStepSpec time_step;
  double damping;              // local damping alpha in [0, 1); required
  double flip_fraction = 1.0;  // FLIP/PIC blend of the G2P velocity update, in [0, 1]
  Cycle cycle = Cycle::explicit_dynamic;
  ImplicitSpec implicit;
  std::optional<GravityLoadingSpec> gravity_loading;  // absent: the run starts as given
  std::optional<RestSpec> stop_at_rest;               // absent: the run goes to end_time
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
  Phases phases = Phases::solid;
  // Three-phase cases only (phases: solid_liquid_gas):
  std::optional<FluidsSpec> fluids;
  physics::MassBalance mass_balance = physics::MassBalance::full;
  physics::Skeleton skeleton = physics::Skeleton::deformable;
  PressureUpdate pressure_update = PressureUpdate::nodal;
  std::vector<MaterialSpec> materials;
  std::vector<BodySpec> bodies;
  std::vector<BoundarySpec> boundaries;
  std::optional<SurfaceSpec> free_surface;  // three-phase cases (rainfall: implicit cycle)
  SolverSpec solver;
  OutputSpec output;
};

/// The grid axis gravity acts along (rain falls along it), or -1 if gravity has no component or
/// more than one.
inline int gravity_axis(const Case& c) {
  int axis = -1;
  for (int d = 0; d < c.dimension; ++d)
    if (c.gravity[d] != 0.0) {
      if (axis >= 0) return -1;
      axis = d;
    }
  return axis;
}

}  // namespace unsatmpm

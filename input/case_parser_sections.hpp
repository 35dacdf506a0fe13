// Internal to the case parser: the readers of its sections, shared by case_parser*.cpp and
// case_configuration.cpp (the writer). Not part of the input layer's interface.
#pragma once

#include <initializer_list>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "input/case.hpp"
#include "input/input_node.hpp"

namespace unsatmpm::case_sections {

// Names of the enumerations as written in the file (the writer uses the same tables).
extern const std::vector<std::pair<std::string, ShapeFunctionKind>> shape_function_names;
extern const std::vector<std::pair<std::string, MechanicalCondition>> mechanical_names;
extern const std::vector<std::string> axis_names;   // x, y, z
extern const std::vector<std::string> model_names;  // linear_elastic, mohr_coulomb (variant order)
extern const std::vector<std::pair<std::string, Phases>> phases_names;
extern const std::vector<std::pair<std::string, physics::MassBalance>> mass_balance_names;
extern const std::vector<std::pair<std::string, PressureUpdate>> pressure_update_names;
extern const std::vector<std::pair<std::string, Cycle>> cycle_names;
extern const std::vector<std::pair<std::string, FlowLinearSolver>> linear_solver_names;
extern const std::vector<std::pair<std::string, FlowDirectSolver>> direct_solver_names;
extern const std::vector<std::pair<std::string, RelativePermeabilityAt>>
    relative_permeability_names;
extern const std::vector<std::pair<std::string, physics::Skeleton>> skeleton_names;
// Names of the variant alternatives, in variant order (index() of the variant).
extern const std::vector<std::string> gas_model_names;       // bulk_modulus, ideal
extern const std::vector<std::string> retention_names;       // linear, van_genuchten, table
extern const std::vector<std::string> liquid_relperm_names;  // constant, power, mualem_..., table
extern const std::vector<std::string> gas_relperm_names;     // constant, power, table

/// Angles are degrees in the file and radians in a Case; these two are the only conversions.
double degrees_to_radians(double degrees);
double radians_to_degrees(double radians);

/// A list of `c.dimension` finite numbers (the message states the dimension).
std::vector<double> read_vector(const InputNode& node, int dimension,
                                const Range& range = Range::any());
/// An axis name x | y | z, restricted to the case's dimension; returns 0, 1 or 2.
int read_axis(const InputNode& node, int dimension);
/// Grid spacing along an axis and the tolerance (1e-9 spacing) used for "on the grid" tests.
double grid_spacing(const GridSpec& grid, int axis);
/// Fails at `where` unless x (c.dimension entries) lies in the grid box (within the tolerance).
void require_inside_grid(const InputNode& where, const std::vector<double>& x, const Case& c);
/// Fails at `where` if `name` repeats one of `seen` (kind: "material", "body", ...), then adds it.
void require_unique_name(const InputNode& where, const std::string& name, const char* kind,
                         std::vector<std::pair<std::string, int>>& seen);

/// Called in a catch block: throws e with the hint appended if it is about one of `keys` being
/// unknown in `map`, else rethrows the exception being handled.
[[noreturn]] void rethrow_with_hint(const InputError& e, const InputNode& map,
                                    std::initializer_list<std::string_view> keys,
                                    const std::string& hint);
/// Runs `read`, which reads the map `map`. If it reports one of `keys` as an unknown key of
/// `map` itself, the message gets " (hint)" appended: the key exists, but not in this kind of
/// case (e.g. a three-phase key in a solid case).
template <class F>
auto with_unknown_key_hint(const InputNode& map, std::initializer_list<std::string_view> keys,
                           const std::string& hint, F&& read) {
  try {
    return read();
  } catch (const InputError& e) {
    rethrow_with_hint(e, map, keys, hint);
  }
}
/// The hint for three-phase keys met in a solid case.
extern const std::string three_phase_hint;  // "a key of three-phase cases: set phases: ..."

/// Sections that need the already-parsed part of the case (dimension, grid, phases, fluids,
/// materials).
FluidsSpec parse_fluids(const InputNode& node);
std::vector<MaterialSpec> parse_materials(const InputNode& node, const Case& c);
std::vector<BodySpec> parse_bodies(const InputNode& node, const Case& c);
std::vector<BoundarySpec> parse_boundaries(const InputNode& node, const Case& c);

// Three-phase pieces (case_parser_hydraulics.cpp).
/// A number (constant), {ramp: {from, to, start, end}} or {table: [[t, v], ...]}; every value
/// within `values`.
TimeFunction read_time_function(const InputNode& node, const Range& values);
/// `initial_state` of a body: {liquid_pressure, gas_pressure} or {suction, gas_pressure}.
InitialPressures read_initial_state(const InputNode& node, const Case& c);
/// The `liquid` and `gas` keys of one boundary (declared by the caller): on an outer face of the
/// grid, suction only with a gas condition, no fluid already prescribed on the same plane by one
/// of the `earlier` boundaries.
void read_fluid_conditions(MapReader& m, const Case& c, const std::vector<BoundarySpec>& earlier,
                           BoundarySpec& boundary);
/// `free_surface`: {liquid: {pressure|suction|rainfall: f(t)}, gas: {pressure: f(t)}}; rainfall
/// needs the implicit cycle (c.solver parsed first).
SurfaceSpec parse_free_surface(const InputNode& node, const Case& c);
/// Admissible gas pressures [Pa]: above -P_atm (absolute pressure positive) for an ideal gas.
Range gas_pressure_range(const Case& c);

}  // namespace unsatmpm::case_sections

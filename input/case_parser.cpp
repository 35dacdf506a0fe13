// The case reader: top level, grid, solver and output sections, and the helpers the other
// sections share (case_parser_materials.cpp, case_parser_geometry.cpp).
#include "input/case_parser.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <numbers>

#include "input/case_parser_sections.hpp"

namespace unsatmpm {

namespace case_sections {

const std::vector<std::pair<std::string, ShapeFunctionKind>> shape_function_names = {
    {"linear", ShapeFunctionKind::linear}, {"gimp", ShapeFunctionKind::gimp}};
const std::vector<std::pair<std::string, MechanicalCondition>> mechanical_names = {
    {"fixed", MechanicalCondition::fixed},
    {"roller", MechanicalCondition::roller},
    {"rigid_plate", MechanicalCondition::rigid_plate}};
const std::vector<std::string> axis_names = {"x", "y", "z"};
const std::vector<std::string> model_names = {"linear_elastic", "mohr_coulomb"};
const std::vector<std::pair<std::string, Phases>> phases_names = {
    {"solid", Phases::solid}, {"solid_liquid_gas", Phases::solid_liquid_gas}};
const std::vector<std::pair<std::string, physics::MassBalance>> mass_balance_names = {
    {"full", physics::MassBalance::full}, {"simplified", physics::MassBalance::simplified}};
const std::vector<std::pair<std::string, Cycle>> cycle_names = {
    {"explicit", Cycle::explicit_dynamic}, {"implicit", Cycle::implicit_pressure}};
const std::vector<std::pair<std::string, FlowLinearSolver>> linear_solver_names = {
    {"auto", FlowLinearSolver::automatic},
    {"direct", FlowLinearSolver::direct},
    {"iterative", FlowLinearSolver::iterative}};
const std::vector<std::pair<std::string, FlowDirectSolver>> direct_solver_names = {
    {"umfpack", FlowDirectSolver::umfpack}, {"klu", FlowDirectSolver::klu}};
const std::vector<std::pair<std::string, RelativePermeabilityAt>> relative_permeability_names = {
    {"points", RelativePermeabilityAt::points}, {"nodes", RelativePermeabilityAt::nodes}};
const std::vector<std::pair<std::string, PressureUpdate>> pressure_update_names = {
    {"pointwise", PressureUpdate::pointwise}, {"nodal", PressureUpdate::nodal}};
const std::vector<std::pair<std::string, physics::Skeleton>> skeleton_names = {
    {"deformable", physics::Skeleton::deformable}, {"rigid", physics::Skeleton::rigid}};
const std::vector<std::string> gas_model_names = {"bulk_modulus", "ideal"};
const std::vector<std::string> retention_names = {"linear", "van_genuchten", "table"};
const std::vector<std::string> liquid_relperm_names = {"constant", "power", "mualem_van_genuchten",
                                                       "table"};
const std::vector<std::string> gas_relperm_names = {"constant", "power", "table"};
const std::string three_phase_hint = "a key of three-phase cases: set phases: solid_liquid_gas";

double degrees_to_radians(double degrees) { return degrees * (std::numbers::pi / 180.0); }
double radians_to_degrees(double radians) { return radians * (180.0 / std::numbers::pi); }

namespace {

/// A sequence must have `dimension` entries (the message says why).
void require_dimension_entries(const InputNode& node, int dimension) {
  const auto n = static_cast<std::size_t>(dimension);
  if (node.is_sequence() && node.size() != n)
    node.fail("expected " + std::to_string(n) + " numbers (one per dimension; dimension is " +
              std::to_string(dimension) + "), got " + std::to_string(node.size()));
}

}  // namespace

std::vector<double> read_vector(const InputNode& node, int dimension, const Range& range) {
  require_dimension_entries(node, dimension);
  return node.as_vector(static_cast<std::size_t>(dimension), range);
}

int read_axis(const InputNode& node, int dimension) {
  const auto axis = static_cast<int>(node.as_choice(axis_names));
  if (axis >= dimension) {
    std::string list;
    for (int d = 0; d < dimension; ++d) list += (d ? ", " : "") + axis_names[d];
    node.fail("axis '" + axis_names[axis] + "' does not exist in " + std::to_string(dimension) +
              "D; valid axes: " + list);
  }
  return axis;
}

double grid_spacing(const GridSpec& grid, int axis) { return grid.size[axis] / grid.cells[axis]; }

namespace {

std::string grid_box_text(const Case& c) {
  std::string text;
  for (int d = 0; d < c.dimension; ++d)
    text += (d ? " x [" : "[") + format_number(c.grid.origin[d]) + ", " +
            format_number(c.grid.origin[d] + c.grid.size[d]) + "]";
  return text;
}

std::string point_text(const std::vector<double>& x) {
  std::string text = "[";
  for (std::size_t d = 0; d < x.size(); ++d) text += (d ? ", " : "") + format_number(x[d]);
  return text + "]";
}

}  // namespace

void require_inside_grid(const InputNode& where, const std::vector<double>& x, const Case& c) {
  for (std::size_t d = 0; d < x.size(); ++d) {
    const int axis = static_cast<int>(d);
    const double tol = 1e-9 * grid_spacing(c.grid, axis);
    const double lo = c.grid.origin[d], hi = c.grid.origin[d] + c.grid.size[d];
    if (x[d] < lo - tol || x[d] > hi + tol)
      where.fail(point_text(x) + " lies outside the grid " + grid_box_text(c) + " (" +
                 axis_names[d] + " = " + format_number(x[d]) + ")");
  }
}

void rethrow_with_hint(const InputError& e, const InputNode& map,
                       std::initializer_list<std::string_view> keys, const std::string& hint) {
  const std::string message = e.what();
  const std::string where = map.path().empty() ? " at top level;" : " in " + map.path() + ";";
  for (const std::string_view key : keys)
    if (message.find("unknown key '" + std::string(key) + "'" + where) != std::string::npos)
      throw InputError(message + " (" + hint + ")");
  throw;
}

void require_unique_name(const InputNode& where, const std::string& name, const char* kind,
                         std::vector<std::pair<std::string, int>>& seen) {
  for (const auto& [other, line] : seen)
    if (other == name)
      where.fail(std::string("duplicate ") + kind + " name '" + name + "' (first defined at line " +
                 std::to_string(line) + ")");
  seen.emplace_back(name, where.line());
}

}  // namespace case_sections

namespace {

using namespace case_sections;

GridSpec parse_grid(const InputNode& node, int dimension) {
  return node.read_map({"origin", "size", "cells"}, [&](MapReader& m) {
    GridSpec grid;
    grid.origin = read_vector(m.required("origin"), dimension);
    grid.size = read_vector(m.required("size"), dimension, Range::positive());
    const InputNode cells = m.required("cells");
    require_dimension_entries(cells, dimension);
    grid.cells = cells.as_int_vector(dimension, 2, std::numeric_limits<int>::max() - 1);
    return grid;
  });
}

TimeStepSpec parse_time_step(const InputNode& node, double end_time) {
  return node.read_map({"fixed", "cfl_safety"}, [&](MapReader& m) {
    TimeStepSpec spec;
    const auto fixed = m.optional("fixed");
    const auto cfl = m.optional("cfl_safety");
    if (fixed && cfl) m.node().fail("fixed and cfl_safety are mutually exclusive; give one");
    if (!fixed && !cfl) m.node().fail("expected one of fixed, cfl_safety");
    if (fixed) spec.fixed = fixed->as_double(Range::open_closed(0.0, end_time));
    if (cfl) spec.cfl_safety = cfl->as_double(Range::open_closed(0.0, 1.0));
    return spec;
  });
}

ImplicitSpec parse_implicit(const InputNode& node, double end_time) {
  return node.read_map(
      {"relative_tolerance", "absolute_tolerance", "coupling_interval", "linear_solver",
       "direct_solver", "surface_penalty", "relative_permeability"},
      [&](MapReader& m) {
        ImplicitSpec spec;
        spec.relative_tolerance = m.optional_double("relative_tolerance", spec.relative_tolerance,
                                                    Range::open_closed(0.0, 1.0));
        spec.absolute_tolerance =
            m.optional_double("absolute_tolerance", spec.absolute_tolerance, Range::positive());
        if (const auto interval = m.optional("coupling_interval")) {
          const bool scalar =
              !interval->is_null() && !interval->is_map() && !interval->is_sequence();
          const std::string text = scalar ? interval->as_string() : std::string();
          char* end = nullptr;
          std::strtod(text.c_str(), &end);
          if (scalar && text != "auto" && (text.empty() || *end != '\0'))
            interval->fail("expected a time > 0 [s] or auto, got '" + text + "'");
          if (text != "auto")
            spec.coupling_interval = interval->as_double(Range::open_closed(0.0, end_time));
        }
        if (const auto solver = m.optional("linear_solver"))
          spec.linear_solver = solver->as_enum(linear_solver_names);
        if (const auto solver = m.optional("direct_solver"))
          spec.direct_solver = solver->as_enum(direct_solver_names);
        spec.surface_penalty = m.optional_double("surface_penalty", 0.0, Range::non_negative());
        if (const auto at = m.optional("relative_permeability"))
          spec.relative_permeability = at->as_enum(relative_permeability_names);
        return spec;
      });
}

SolverSpec parse_solver(const InputNode& node, Phases phases) {
  return node.read_map(
      {"end_time", "time_step", "damping", "flip_fraction", "cycle", "implicit", "gravity_loading",
       "stop_at_rest"},
      [&](MapReader& m) {
        SolverSpec solver;
        solver.end_time = m.required_double("end_time", Range::positive());
        if (const auto time_step = m.optional("time_step"))
          solver.time_step = parse_time_step(*time_step, solver.end_time);
        solver.damping = m.required_double("damping", Range::closed_open(0.0, 1.0));
        solver.flip_fraction = m.optional_double("flip_fraction", 1.0, Range::closed(0.0, 1.0));
        if (const auto cycle = m.optional("cycle")) {
          solver.cycle = cycle->as_enum(cycle_names);
          if (solver.cycle == Cycle::implicit_pressure && phases != Phases::solid_liquid_gas)
            cycle->fail(
                "the implicit cycle integrates the pore fluids' mass balances: it needs "
                "phases: solid_liquid_gas");
        }
        if (const auto implicit = m.optional("implicit")) {
          if (solver.cycle != Cycle::implicit_pressure)
            implicit->fail("settings of the implicit cycle: set cycle: implicit, or remove them");
          solver.implicit = parse_implicit(*implicit, solver.end_time);
        }
        if (const auto loading = m.optional("gravity_loading"))
          solver.gravity_loading =
              loading->read_map({"damping", "tolerance", "max_time"}, [](MapReader& g) {
                return GravityLoadingSpec{
                    g.required_double("damping", Range::closed_open(0.0, 1.0)),
                    g.required_double("tolerance", Range::open(0.0, 1.0)),
                    g.required_double("max_time", Range::positive())};
              });
        if (const auto rest = m.optional("stop_at_rest"))
          solver.stop_at_rest = rest->read_map({"fraction", "hold", "min_peak"}, [&](MapReader& r) {
            return RestSpec{r.required_double("fraction", Range::open(0.0, 1.0)),
                            r.required_double("hold", Range::open_closed(0.0, solver.end_time)),
                            r.required_double("min_peak", Range::positive())};
          });
        return solver;
      });
}

std::vector<double> parse_output_times(const InputNode& node, double end_time) {
  std::vector<double> times;
  for (const InputNode& item : node.items()) {
    const double t = item.as_double(Range::open_closed(0.0, end_time));
    if (!times.empty() && t <= times.back())
      item.fail("output times must be strictly ascending: " + format_number(t) + " follows " +
                format_number(times.back()));
    times.push_back(t);
  }
  return times;
}

std::vector<ControlPoint> parse_control_points(const InputNode& node, const Case& c) {
  std::vector<ControlPoint> points;
  std::vector<std::pair<std::string, int>> names;
  for (const InputNode& item : node.items()) {
    points.push_back(item.read_map({"name", "position"}, [&](MapReader& m) {
      const InputNode name = m.required("name");
      ControlPoint point{name.as_string(), {}};
      require_unique_name(name, point.name, "control point", names);
      const InputNode position = m.required("position");
      point.position = read_vector(position, c.dimension);
      require_inside_grid(position, point.position, c);
      return point;
    }));
  }
  return points;
}

OutputSpec parse_output(const InputNode& node, const Case& c) {
  return node.read_map(
      {"times", "history_interval", "write_grid", "control_points"}, [&](MapReader& m) {
        OutputSpec output;
        if (const auto times = m.optional("times"))
          output.times = parse_output_times(*times, c.solver.end_time);
        output.history_interval = m.optional_double("history_interval", 0.0, Range::non_negative());
        output.write_grid = m.optional_bool("write_grid", true);
        if (const auto points = m.optional("control_points"))
          output.control_points = parse_control_points(*points, c);
        return output;
      });
}

/// The case name names the default output folder (output/NAME), so it must be a plain name and
/// never a path: letters, digits, '_', '-' and '.', starting with a letter or a digit, at most
/// 100 characters. It is rejected, not sanitised, so the folder is the one the user wrote.
std::string parse_case_name(const InputNode& node) {
  std::string name = node.as_string();
  const auto plain = [](char ch) {
    return (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') ||
           ch == '_' || ch == '-' || ch == '.';
  };
  const bool starts_well =
      !name.empty() && plain(name[0]) && name[0] != '_' && name[0] != '-' && name[0] != '.';
  if (!starts_well || name.size() > 100 || !std::all_of(name.begin(), name.end(), plain))
    node.fail(
        fmt::format("'{}' is not a plain name: the case name names the output folder, so "
                    "it may hold only letters, digits, '_', '-' and '.', must start with a "
                    "letter or a digit and have at most 100 characters (no '/' or '..')",
                    name));
  return name;
}

/// The sections in dependency order: vectors need `dimension`, materials and bodies need the
/// phases (and the fluids), bodies need the grid and the materials, output times need the end
/// time. The three-phase keys are known keys only once `phases` says so.
Case read_case(MapReader& m) {
  Case c;
  c.file = m.node().file();
  c.name = parse_case_name(m.required("name"));
  // The phases first: a missing key is reported after any unknown one (a misspelt key explains
  // a missing one), and the three-phase keys must be known by then.
  if (const auto phases = m.optional("phases")) c.phases = phases->as_enum(phases_names);
  if (c.phases == Phases::solid_liquid_gas)
    m.allow({"fluids", "mass_balance", "pressure_update", "skeleton", "free_surface"});
  c.dimension = m.required_int("dimension", 1, 3);
  c.grid = parse_grid(m.required("grid"), c.dimension);
  c.shape_function = m.required("shape_function").as_enum(shape_function_names);
  c.gravity = read_vector(m.required("gravity"), c.dimension);
  if (c.phases == Phases::solid_liquid_gas) {
    c.fluids = parse_fluids(m.required("fluids"));
    c.mass_balance = m.required("mass_balance").as_enum(mass_balance_names);
    if (const auto skeleton = m.optional("skeleton"))
      c.skeleton = skeleton->as_enum(skeleton_names);
    if (const auto update = m.optional("pressure_update"))
      c.pressure_update = update->as_enum(pressure_update_names);
  }
  c.materials = parse_materials(m.required("materials"), c);
  c.bodies = parse_bodies(m.required("bodies"), c);
  if (const auto boundaries = m.optional("boundaries"))
    c.boundaries = parse_boundaries(*boundaries, c);
  c.solver = parse_solver(m.required("solver"), c.phases);
  if (c.solver.gravity_loading && c.skeleton == physics::Skeleton::rigid)
    m.required("solver").fail(
        "gravity_loading needs a deformable skeleton (skeleton: rigid has no mechanics)");
  if (c.solver.gravity_loading &&
      std::any_of(c.bodies.begin(), c.bodies.end(), [](const BodySpec& b) { return b.k0; }))
    m.required("solver").fail(
        "gravity_loading and a body's initial_stress both set the initial stresses: give one");
  if (c.phases == Phases::solid_liquid_gas)
    if (const auto surface = m.optional("free_surface"))
      c.free_surface = parse_free_surface(*surface, c);
  if (c.solver.implicit.surface_penalty > 0.0 &&
      !(c.free_surface && (c.free_surface->liquid || c.free_surface->rainfall)))
    m.required("solver").fail(
        "implicit.surface_penalty applies to a liquid pressure, suction or rainfall on the free "
        "surface (free_surface: {liquid: ...}), which this case does not have");
  c.output = parse_output(m.required("output"), c);
  return c;
}

Case parse_case(const InputNode& root) {
  return with_unknown_key_hint(
      root, {"fluids", "mass_balance", "pressure_update", "skeleton", "free_surface"},
      three_phase_hint, [&] {
        return root.read_map({"name", "dimension", "grid", "shape_function", "gravity", "phases",
                              "materials", "bodies", "boundaries", "solver", "output"},
                             read_case);
      });
}

}  // namespace

Case parse_case_file(const std::string& path) { return parse_case(InputNode::load_file(path)); }

Case parse_case_text(const std::string& text, const std::string& file_name) {
  return parse_case(InputNode::load_text(text, file_name));
}

}  // namespace unsatmpm

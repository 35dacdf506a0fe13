// The effective configuration: a Case written back as YAML in the input schema, every default
// spelt out. Numbers are written in their shortest exact decimal form and angles in degrees chosen
// to convert back to the very same radians, so that parsing the text gives an equal Case.
// Materials and fluids are written by input/case_configuration_materials.cpp.
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "input/case_parser.hpp"
#include "input/case_parser_sections.hpp"
#include "input/configuration_writer.hpp"

namespace unsatmpm {

namespace configuration {

using namespace case_sections;

/// Shortest decimal degrees that convert back to exactly `radians` (searching a few ulps
/// around the direct conversion, which alone can be off by one ulp).
std::string degrees_text(double radians) {
  const double direct = radians_to_degrees(radians);
  std::string best = format_number(direct);
  bool found = false;
  double below = direct, above = direct;
  for (int step = 0; step < 64; ++step) {
    for (const double candidate : {below, above}) {
      const std::string text = format_number(candidate);
      if (degrees_to_radians(candidate) == radians && (!found || text.size() < best.size()))
        best = text, found = true;
    }
    if (found && step >= 4) break;
    below = std::nextafter(below, -INFINITY);
    above = std::nextafter(above, INFINITY);
  }
  return best;
}

YAML::Emitter& operator<<(YAML::Emitter& out, const std::vector<double>& v) {
  out << YAML::Flow << YAML::BeginSeq;
  for (const double x : v) out << format_number(x);
  return out << YAML::EndSeq;
}

/// `key: value` with the value a number.
void write_number(YAML::Emitter& out, const char* key, double value) {
  out << YAML::Key << key << YAML::Value << format_number(value);
}

}  // namespace configuration

namespace {

using namespace configuration;
using namespace case_sections;

template <class Names, class Value>
std::string name_of(const Names& names, Value value) {
  for (const auto& [name, v] : names)
    if (v == value) return name;
  return "?";
}

void write_grid(YAML::Emitter& out, const GridSpec& grid) {
  out << YAML::Key << "grid" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "origin" << YAML::Value << grid.origin;
  out << YAML::Key << "size" << YAML::Value << grid.size;
  out << YAML::Key << "cells" << YAML::Value << YAML::Flow << grid.cells;
  out << YAML::EndMap;
}

/// A number when constant from t = 0, a ramp for two points from t >= 0, else a table; each
/// reads back to the very same points.
void write_time_function(YAML::Emitter& out, const TimeFunction& f) {
  const auto& p = f.points;
  if (p.size() == 1 && p[0][0] == 0.0) {
    out << format_number(p[0][1]);
    return;
  }
  out << YAML::Flow << YAML::BeginMap;
  if (p.size() == 2 && p[0][0] >= 0.0) {
    out << YAML::Key << "ramp" << YAML::Value << YAML::BeginMap;
    write_number(out, "from", p[0][1]);
    write_number(out, "to", p[1][1]);
    write_number(out, "start", p[0][0]);
    write_number(out, "end", p[1][0]);
    out << YAML::EndMap;
  } else {
    out << YAML::Key << "table" << YAML::Value << YAML::BeginSeq;
    for (const auto& [t, value] : p) out << std::vector<double>{t, value};
    out << YAML::EndSeq;
  }
  out << YAML::EndMap;
}

void write_fluid_conditions(YAML::Emitter& out, const std::optional<LiquidCondition>& liquid,
                            const std::optional<TimeFunction>& gas_pressure,
                            const std::optional<TimeFunction>& rainfall = {}) {
  if (rainfall) {
    out << YAML::Key << "liquid" << YAML::Value << YAML::BeginMap;
    out << YAML::Key << "rainfall" << YAML::Value;
    write_time_function(out, *rainfall);
    out << YAML::EndMap;
  }
  if (liquid) {
    const bool suction = liquid->kind == LiquidCondition::Kind::suction;
    out << YAML::Key << "liquid" << YAML::Value << YAML::BeginMap;
    out << YAML::Key << (suction ? "suction" : "pressure") << YAML::Value;
    write_time_function(out, liquid->value);
    out << YAML::EndMap;
  }
  if (gas_pressure) {
    out << YAML::Key << "gas" << YAML::Value << YAML::BeginMap;
    out << YAML::Key << "pressure" << YAML::Value;
    write_time_function(out, *gas_pressure);
    out << YAML::EndMap;
  }
}

void write_geometry(YAML::Emitter& out, const Geometry& geometry) {
  if (const auto* box = std::get_if<BoxGeometry>(&geometry)) {
    out << YAML::Key << "box" << YAML::Value << YAML::Flow << YAML::BeginMap;
    out << YAML::Key << "min" << YAML::Value << box->min;
    out << YAML::Key << "max" << YAML::Value << box->max << YAML::EndMap;
    return;
  }
  const auto& polygon = std::get<PolygonGeometry>(geometry);
  out << YAML::Key << "polygon" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "vertices" << YAML::Value << YAML::Flow << YAML::BeginSeq;
  for (const auto& v : polygon.vertices) out << std::vector<double>{v[0], v[1]};
  out << YAML::EndSeq;
  if (polygon.extrude_z) {
    const auto& z = *polygon.extrude_z;
    out << YAML::Key << "extrude_z" << YAML::Value << std::vector<double>{z[0], z[1]};
  }
  out << YAML::EndMap;
}

void write_velocity(YAML::Emitter& out, const InitialVelocity& velocity) {
  out << YAML::Key << "initial_velocity" << YAML::Value;
  if (const auto* constant = std::get_if<std::vector<double>>(&velocity)) {
    out << *constant;
    return;
  }
  const auto& sine = std::get<SineVelocity>(velocity);
  out << YAML::Flow << YAML::BeginMap << YAML::Key << "sine" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "amplitude" << YAML::Value << sine.amplitude;
  out << YAML::Key << "axis" << YAML::Value << axis_names[sine.axis];
  out << YAML::Key << "wavenumber" << YAML::Value << format_number(sine.wavenumber);
  out << YAML::Key << "origin" << YAML::Value << format_number(sine.origin);
  out << YAML::EndMap << YAML::EndMap;
}

void write_bodies(YAML::Emitter& out, const Case& c) {
  out << YAML::Key << "bodies" << YAML::Value << YAML::BeginSeq;
  for (const BodySpec& b : c.bodies) {
    out << YAML::BeginMap << YAML::Key << "name" << YAML::Value << b.name;
    out << YAML::Key << "material" << YAML::Value << c.materials[b.material].name;
    out << YAML::Key << "points_per_cell" << YAML::Value << b.points_per_cell;
    write_geometry(out, b.geometry);
    write_velocity(out, b.initial_velocity);
    if (b.k0) {
      out << YAML::Key << "initial_stress" << YAML::Value << YAML::Flow << YAML::BeginMap;
      write_number(out, "k0", *b.k0);
      out << YAML::EndMap;
    }
    if (b.initial_pressures) {
      out << YAML::Key << "initial_state" << YAML::Value << YAML::Flow << YAML::BeginMap;
      if (const auto& w = b.initial_pressures->water_table) {
        out << YAML::Key << "water_table" << YAML::Value << YAML::BeginMap;
        write_number(out, "elevation", w->elevation);
        write_number(out, "max_suction", w->max_suction);
        out << YAML::EndMap;
      } else if (const auto& profile = b.initial_pressures->liquid_profile) {
        out << YAML::Key << "liquid_pressure" << YAML::Value << YAML::BeginMap;
        out << YAML::Key << "table" << YAML::Value << YAML::BeginSeq;
        for (const auto& [z, value] : profile->points) out << std::vector<double>{z, value};
        out << YAML::EndSeq << YAML::EndMap;
      } else {
        write_number(out, "liquid_pressure", b.initial_pressures->liquid_pressure);
      }
      write_number(out, "gas_pressure", b.initial_pressures->gas_pressure);
      out << YAML::EndMap;
    }
    out << YAML::EndMap;
  }
  out << YAML::EndSeq;
}

void write_boundaries(YAML::Emitter& out, const std::vector<BoundarySpec>& boundaries) {
  out << YAML::Key << "boundaries" << YAML::Value;
  if (boundaries.empty()) out << YAML::Flow;
  out << YAML::BeginSeq;
  for (const BoundarySpec& b : boundaries) {
    out << YAML::Flow << YAML::BeginMap << YAML::Key << "name" << YAML::Value << b.name;
    out << YAML::Key << "plane" << YAML::Value << YAML::BeginMap;
    out << YAML::Key << "axis" << YAML::Value << axis_names[b.region.axis];
    out << YAML::Key << "at" << YAML::Value << format_number(b.region.coordinate) << YAML::EndMap;
    if (b.mechanical)
      out << YAML::Key << "mechanical" << YAML::Value << name_of(mechanical_names, *b.mechanical);
    if (b.traction) {
      out << YAML::Key << "traction" << YAML::Value << YAML::BeginMap;
      out << YAML::Key << "normal" << YAML::Value;
      write_time_function(out, b.traction->normal);
      if (b.traction->shear_axis >= 0) {
        out << YAML::Key << "shear" << YAML::Value << YAML::BeginMap;
        out << YAML::Key << "axis" << YAML::Value << axis_names[b.traction->shear_axis];
        out << YAML::Key << "value" << YAML::Value;
        write_time_function(out, b.traction->shear);
        out << YAML::EndMap;
      }
      out << YAML::EndMap;
    }
    write_fluid_conditions(out, b.liquid, b.gas_pressure);
    out << YAML::EndMap;
  }
  out << YAML::EndSeq;
}

void write_solver(YAML::Emitter& out, const SolverSpec& solver) {
  out << YAML::Key << "solver" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "end_time" << YAML::Value << format_number(solver.end_time);
  out << YAML::Key << "time_step" << YAML::Value << YAML::Flow << YAML::BeginMap;
  if (solver.time_step.fixed)
    out << YAML::Key << "fixed" << YAML::Value << format_number(*solver.time_step.fixed);
  else
    out << YAML::Key << "cfl_safety" << YAML::Value << format_number(solver.time_step.cfl_safety);
  out << YAML::EndMap;
  out << YAML::Key << "damping" << YAML::Value << format_number(solver.damping);
  out << YAML::Key << "flip_fraction" << YAML::Value << format_number(solver.flip_fraction);
  out << YAML::Key << "cycle" << YAML::Value << name_of(cycle_names, solver.cycle);
  if (solver.cycle == Cycle::implicit_pressure) {
    const ImplicitSpec& s = solver.implicit;
    out << YAML::Key << "implicit" << YAML::Value << YAML::Flow << YAML::BeginMap;
    out << YAML::Key << "relative_tolerance" << YAML::Value << format_number(s.relative_tolerance);
    out << YAML::Key << "absolute_tolerance" << YAML::Value << format_number(s.absolute_tolerance);
    out << YAML::Key << "coupling_interval" << YAML::Value
        << (s.coupling_interval ? format_number(*s.coupling_interval) : std::string("auto"));
    out << YAML::Key << "linear_solver" << YAML::Value
        << name_of(linear_solver_names, s.linear_solver);
    out << YAML::Key << "direct_solver" << YAML::Value
        << name_of(direct_solver_names, s.direct_solver);
    out << YAML::Key << "surface_penalty" << YAML::Value << format_number(s.surface_penalty);
    out << YAML::Key << "relative_permeability" << YAML::Value
        << name_of(relative_permeability_names, s.relative_permeability);
    out << YAML::EndMap;
  }
  if (const auto& g = solver.gravity_loading) {
    out << YAML::Key << "gravity_loading" << YAML::Value << YAML::Flow << YAML::BeginMap;
    out << YAML::Key << "damping" << YAML::Value << format_number(g->damping);
    out << YAML::Key << "tolerance" << YAML::Value << format_number(g->tolerance);
    out << YAML::Key << "max_time" << YAML::Value << format_number(g->max_time);
    out << YAML::EndMap;
  }
  if (const auto& r = solver.stop_at_rest) {
    out << YAML::Key << "stop_at_rest" << YAML::Value << YAML::Flow << YAML::BeginMap;
    out << YAML::Key << "fraction" << YAML::Value << format_number(r->fraction);
    out << YAML::Key << "hold" << YAML::Value << format_number(r->hold);
    out << YAML::Key << "min_peak" << YAML::Value << format_number(r->min_peak);
    out << YAML::EndMap;
  }
  out << YAML::EndMap;
}

void write_output(YAML::Emitter& out, const OutputSpec& output) {
  out << YAML::Key << "output" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "times" << YAML::Value << output.times;
  out << YAML::Key << "history_interval" << YAML::Value << format_number(output.history_interval);
  out << YAML::Key << "write_grid" << YAML::Value << output.write_grid;
  out << YAML::Key << "control_points" << YAML::Value;
  if (output.control_points.empty()) out << YAML::Flow;
  out << YAML::BeginSeq;
  for (const ControlPoint& p : output.control_points) {
    out << YAML::Flow << YAML::BeginMap << YAML::Key << "name" << YAML::Value << p.name;
    out << YAML::Key << "position" << YAML::Value << p.position << YAML::EndMap;
  }
  out << YAML::EndSeq << YAML::EndMap;
}

}  // namespace

std::string effective_configuration(const Case& c) {
  YAML::Emitter out;
  out << YAML::Comment("effective configuration of " + c.file +
                       " (defaults included; SI units, angles in degrees)");
  out << YAML::BeginMap;
  out << YAML::Key << "name" << YAML::Value << c.name;
  out << YAML::Key << "dimension" << YAML::Value << c.dimension;
  write_grid(out, c.grid);
  out << YAML::Key << "shape_function" << YAML::Value
      << name_of(shape_function_names, c.shape_function);
  out << YAML::Key << "gravity" << YAML::Value << c.gravity;
  out << YAML::Key << "phases" << YAML::Value << name_of(phases_names, c.phases);
  if (c.phases == Phases::solid_liquid_gas) {
    write_fluids(out, c.fluids.value());
    out << YAML::Key << "mass_balance" << YAML::Value
        << name_of(mass_balance_names, c.mass_balance);
    out << YAML::Key << "pressure_update" << YAML::Value
        << name_of(pressure_update_names, c.pressure_update);
    out << YAML::Key << "skeleton" << YAML::Value << name_of(skeleton_names, c.skeleton);
  }
  write_materials(out, c.materials);
  write_bodies(out, c);
  write_boundaries(out, c.boundaries);
  if (c.free_surface) {
    out << YAML::Key << "free_surface" << YAML::Value << YAML::Flow << YAML::BeginMap;
    write_fluid_conditions(out, c.free_surface->liquid, c.free_surface->gas_pressure,
                           c.free_surface->rainfall);
    out << YAML::EndMap;
  }
  write_solver(out, c.solver);
  write_output(out, c.output);
  out << YAML::EndMap;
  if (!out.good()) throw std::logic_error("effective_configuration: " + out.GetLastError());
  return std::string(out.c_str()) + "\n";
}

}  // namespace unsatmpm

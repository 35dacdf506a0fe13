// Shared by the case-parser tests (test_case_parser*.cpp): parsing and editing case text, checking
// an error's file, line and key path, and comparing two cases number by number.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <concepts>
#include <initializer_list>
#include <stdexcept>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "input/case_parser.hpp"

namespace unsatmpm::test_support {

inline Case parse(const std::string& text) { return parse_case_text(text, "case.yaml"); }

/// The text with the first occurrence of `from` replaced by `to` (which must exist).
inline std::string edit(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  if (at == std::string::npos) throw std::logic_error("test text lacks: " + from);
  return text.replace(at, from.size(), to);
}

/// 1-based line of the first occurrence of `marker`.
inline int line_of(const std::string& text, const std::string& marker) {
  const auto at = text.find(marker);
  if (at == std::string::npos) throw std::logic_error("test text lacks: " + marker);
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + at, '\n'));
}

template <std::invocable F>
std::string error_of(F&& read) {
  try {
    read();
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError";
  return "";
}
inline std::string error_of(const std::string& text) {
  return error_of([&] { parse(text); });
}

/// The message starts with case.yaml:LINE: (line of `marker` in `text`) and contains the
/// key path and the description.
inline void expect_error(const std::string& text, const std::string& marker,
                         const std::string& path, const std::string& what) {
  const std::string message = error_of(text);
  const std::string prefix = "case.yaml:" + std::to_string(line_of(text, marker)) + ":";
  EXPECT_EQ(message.rfind(prefix, 0), 0u) << message << "\nexpected prefix " << prefix;
  EXPECT_NE(message.find(": " + path + ":"), std::string::npos) << message << "\npath " << path;
  EXPECT_NE(message.find(what), std::string::npos) << message << "\nexpected: " << what;
}

// The parameters of each physics law, for flatten().
inline std::vector<double> parameters(const physics::LinearRetention& r) {
  return {r.a_s, r.s_min};
}
inline std::vector<double> table_parameters(const physics::MonotoneTable& t) {
  std::vector<double> x = t.xs();
  x.insert(x.end(), t.ys().begin(), t.ys().end());
  return x;
}
inline std::vector<double> parameters(const physics::TabulatedRetention& r) {
  return table_parameters(r.table);
}
inline std::vector<double> parameters(const physics::TabulatedRelPerm& k) {
  return table_parameters(k.table);
}
inline std::vector<double> parameters(const physics::VanGenuchten& r) {
  return {r.p0, r.lambda, r.s_min, r.s_max};
}
inline std::vector<double> parameters(const physics::ConstantRelPerm&) { return {}; }
inline std::vector<double> parameters(const physics::PowerRelPerm& k) { return {k.exponent}; }
inline std::vector<double> parameters(const physics::GasPowerRelPerm& k) { return {k.exponent}; }
inline std::vector<double> parameters(const physics::MualemVanGenuchten& k) { return {k.lambda}; }
inline std::vector<double> parameters(const physics::CompressibleFluid& f) {
  return {f.reference_density, f.reference_pressure, f.bulk_modulus};
}
inline std::vector<double> parameters(const physics::IdealGas& g) { return {g.reference_density}; }

/// Appends the numbers of the three-phase parts of a case (all absent in a solid case).
inline void flatten_three_phase(const Case& c, std::vector<double>& x) {
  const auto add = [&x](const auto& v) { x.insert(x.end(), v.begin(), v.end()); };
  const auto add_law = [&](const auto& variant) {
    x.push_back(double(variant.index()));
    std::visit([&](const auto& law) { add(parameters(law)); }, variant);
  };
  const auto add_function = [&](const TimeFunction& f) {
    x.push_back(double(f.points.size()));
    for (const auto& point : f.points) add(point);
  };
  x.insert(x.end(), {double(c.phases), double(c.mass_balance), double(c.skeleton),
                     double(c.fluids.has_value())});
  if (c.fluids) {
    add(parameters(c.fluids->liquid));
    add_law(c.fluids->gas);
    x.insert(x.end(), {c.fluids->liquid_viscosity, c.fluids->gas_viscosity});
  }
  for (const MaterialSpec& m : c.materials) {
    x.push_back(double(m.hydraulic.has_value()));
    if (!m.hydraulic) continue;
    const HydraulicSpec& h = *m.hydraulic;
    x.insert(x.end(), {h.solid_density, h.porosity, h.intrinsic_permeability});
    add_law(h.retention), add_law(h.liquid_relative_permeability);
    add_law(h.gas_relative_permeability);
    x.push_back(h.maximum_porosity.value_or(-1.0));
  }
  for (const BodySpec& b : c.bodies) {
    x.push_back(double(b.initial_pressures.has_value()));
    if (b.initial_pressures)
      x.insert(x.end(), {b.initial_pressures->liquid_pressure, b.initial_pressures->gas_pressure});
  }
  for (const BoundarySpec& b : c.boundaries) {
    x.insert(x.end(), {double(b.liquid.has_value()), double(b.gas_pressure.has_value())});
    if (b.liquid) x.push_back(double(b.liquid->kind)), add_function(b.liquid->value);
    if (b.gas_pressure) add_function(*b.gas_pressure);
  }
}

/// Every number (enums, indices, variant kinds too) and every name of a case, in a fixed order.
inline std::pair<std::vector<double>, std::string> flatten(const Case& c) {
  std::vector<double> x{double(c.dimension), double(c.shape_function)};
  std::string names = c.name;
  const auto add = [&x](const auto& v) { x.insert(x.end(), v.begin(), v.end()); };
  const auto add_numbers = [&x](std::initializer_list<double> v) { x.insert(x.end(), v); };
  add(c.grid.origin), add(c.grid.size), add(c.grid.cells), add(c.gravity);
  for (const MaterialSpec& m : c.materials) {
    names += " " + m.name;
    add_numbers({m.density, double(m.model.index())});
    if (const auto* e = std::get_if<physics::LinearElastic>(&m.model))
      add_numbers({e->young_modulus, e->poisson_ratio});
    if (const auto* mc = std::get_if<physics::MohrCoulomb>(&m.model))
      add_numbers({mc->elastic.young_modulus, mc->elastic.poisson_ratio, mc->strength.cohesion,
                   mc->strength.friction_angle, mc->strength.dilatancy_angle,
                   mc->strength.tensile_strength});
    if (const auto* smc = std::get_if<physics::SuctionMohrCoulomb>(&m.model)) {
      const physics::SuctionStrength& s = smc->strength;
      add_numbers({smc->elastic().young_modulus, smc->elastic().poisson_ratio, s.cohesion,
                   s.cohesion_increase, s.cohesion_rate, s.friction_angle, s.friction_increase,
                   s.dilatancy_angle, s.tensile_strength});
    }
  }
  for (const BodySpec& b : c.bodies) {
    names += " " + b.name;
    add_numbers({double(b.material), double(b.points_per_cell), double(b.geometry.index()),
                 double(b.initial_velocity.index())});
    if (const auto* box = std::get_if<BoxGeometry>(&b.geometry)) add(box->min), add(box->max);
    if (const auto* p = std::get_if<PolygonGeometry>(&b.geometry)) {
      for (const auto& xy : p->vertices) add(xy);
      add(p->extrude_z.value_or(std::array<double, 2>{-1.0, -1.0}));
    }
    if (const auto* v = std::get_if<std::vector<double>>(&b.initial_velocity)) add(*v);
    if (const auto* s = std::get_if<SineVelocity>(&b.initial_velocity))
      add(s->amplitude), add_numbers({double(s->axis), s->wavenumber, s->origin});
  }
  for (const BoundarySpec& b : c.boundaries) {
    names += " " + b.name;
    add_numbers({double(b.region.axis), b.region.coordinate, double(b.mechanical.has_value()),
                 double(b.mechanical.value_or(MechanicalCondition::fixed)),
                 double(b.traction.has_value())});
    if (b.traction) {
      for (const auto& point : b.traction->normal.points) add(point);
      add_numbers({double(b.traction->shear_axis)});
      for (const auto& point : b.traction->shear.points) add(point);
    }
  }
  const SolverSpec& s = c.solver;
  add_numbers({s.end_time, s.time_step.fixed.value_or(-1.0), s.time_step.cfl_safety, s.damping,
               s.flip_fraction, c.output.history_interval, double(c.output.write_grid)});
  if (const auto& r = s.stop_at_rest) add_numbers({r->fraction, r->hold, r->min_peak});
  add(c.output.times);
  for (const ControlPoint& p : c.output.control_points) names += " " + p.name, add(p.position);
  flatten_three_phase(c, x);
  return {x, names};
}

/// The effective configuration of the parsed text reads back to exactly the same case, and
/// writing that again gives the same text (but for the file name in the first line).
inline void expect_round_trip(const std::string& text) {
  const Case a = parse(text);
  const std::string yaml = effective_configuration(a);
  const Case b = parse_case_text(yaml, "effective.yaml");
  SCOPED_TRACE(yaml);
  EXPECT_EQ(flatten(a), flatten(b));  // exact equality of every number
  const std::string again = effective_configuration(b);
  EXPECT_EQ(again.substr(again.find('\n')), yaml.substr(yaml.find('\n')));
}

}  // namespace unsatmpm::test_support

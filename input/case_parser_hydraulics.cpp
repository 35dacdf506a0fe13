// The case reader: the three-phase parts of bodies and boundaries — initial fluid pressures, the
// liquid and gas conditions of a boundary, and the time functions they are given as.
//
// Hydraulic conditions act on the grid's outer faces only (cycles/three_phase_setup.hpp: every
// other outer face is impervious, a body surface inside the grid is at zero gauge pressure), so a
// condition on an inner plane is an error rather than silently ignored.
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <variant>
#include <vector>

#include "input/case_parser_sections.hpp"
#include "physics/fluids.hpp"

namespace unsatmpm::case_sections {

namespace {

using TimePoint = std::array<double, 2>;  // (t [s], value)

TimeFunction read_ramp(const InputNode& node, const Range& values) {
  return node.read_map({"from", "to", "start", "end"}, [&](MapReader& m) {
    const double from = m.required_double("from", values);
    const double to = m.required_double("to", values);
    const double start = m.required_double("start", Range::non_negative());
    const InputNode end = m.required("end");
    const double t1 = end.as_double();
    if (t1 <= start)
      end.fail("a ramp must end after it starts: end " + format_number(t1) + " <= start " +
               format_number(start));
    return TimeFunction{{TimePoint{start, from}, TimePoint{t1, to}}};
  });
}

TimeFunction read_table(const InputNode& node, const Range& values,
                        const std::string& abscissa = "time") {
  if (node.is_sequence() && node.size() == 0)
    node.fail("a table needs at least one [" + abscissa.substr(0, 1) + ", value] point");
  TimeFunction f;
  for (const InputNode& row : node.items(1)) {
    if (!row.is_sequence() || row.size() != 2)
      row.fail("expected a [" + abscissa + ", value] pair, got " + row.describe());
    const std::vector<InputNode> pair = row.items();
    const double t = pair[0].as_double();
    if (!f.points.empty() && t <= f.points.back()[0])
      pair[0].fail("table " + abscissa + "s must be strictly ascending: " + format_number(t) +
                   " follows " + format_number(f.points.back()[0]));
    f.points.push_back({t, pair[1].as_double(values)});
  }
  return f;
}

/// The outer face of the grid that the plane is, along its axis: "min", "max", or "" (inside).
std::string outer_face(const PlaneRegion& plane, const Case& c) {
  const double h = grid_spacing(c.grid, plane.axis), lo = c.grid.origin[plane.axis];
  const double hi = lo + c.grid.size[plane.axis];
  if (std::abs(plane.coordinate - lo) <= 1e-9 * h) return "min";
  if (std::abs(plane.coordinate - hi) <= 1e-9 * h) return "max";
  return "";
}

std::string plane_text(const PlaneRegion& plane) {
  return axis_names[plane.axis] + " = " + format_number(plane.coordinate);
}

/// Fails at `where` unless the boundary's plane is an outer face of the grid.
void require_outer_face(const InputNode& where, const char* fluid, const PlaneRegion& plane,
                        const Case& c) {
  if (!outer_face(plane, c).empty()) return;
  const double lo = c.grid.origin[plane.axis], hi = lo + c.grid.size[plane.axis];
  const std::string& axis = axis_names[plane.axis];
  where.fail(std::string("a ") + fluid + " condition must lie on an outer face of the grid, but " +
             "plane " + plane_text(plane) + " is inside it (outer faces: " + axis + " = " +
             format_number(lo) + " and " + axis + " = " + format_number(hi) + ")");
}

/// Fails at `where` if one of `earlier` prescribes the same fluid on the same face.
template <class Prescribes>
void require_first_on_face(const InputNode& where, const char* fluid, const BoundarySpec& boundary,
                           const std::vector<BoundarySpec>& earlier, const Case& c,
                           Prescribes&& prescribes) {
  for (const BoundarySpec& other : earlier)
    if (prescribes(other) && other.region.axis == boundary.region.axis &&
        outer_face(other.region, c) == outer_face(boundary.region, c))
      where.fail(std::string("a ") + fluid + " condition on plane " + plane_text(boundary.region) +
                 " is already given by boundary '" + other.name +
                 "'; each fluid takes at most one condition per plane");
}

/// {pressure: f(t)}, {suction: f(t)} or, where `rainfall` is given (the free surface),
/// {rainfall: f(t) [mm/h]}; a rainfall leaves the LiquidCondition empty.
std::optional<LiquidCondition> read_liquid(const InputNode& node,
                                           std::optional<TimeFunction>* rainfall = nullptr) {
  return node.read_map({"pressure", "suction", "rainfall"}, [&](MapReader& m) {
    const auto pressure = m.optional("pressure");
    const auto suction = m.optional("suction");
    const auto rain = m.optional("rainfall");
    const int given = int(pressure.has_value()) + int(suction.has_value()) + int(rain.has_value());
    const std::string choices = rainfall ? "pressure, suction, rainfall" : "pressure, suction";
    if (rain && !rainfall)
      rain->fail(
          "rainfall is a condition on the free surface (free_surface: {liquid: ...}), "
          "not on a plane");
    if (given > 1)  // reported at the later of the two
      (rain ? *rain : *suction)
          .fail("give exactly one of " + choices + " (" + std::to_string(given) + " given)");
    if (given == 0) m.node().fail("expected one of " + choices);
    if (rain) {
      *rainfall = read_time_function(*rain, Range::non_negative());
      return std::optional<LiquidCondition>{};
    }
    if (pressure)
      return std::optional<LiquidCondition>{LiquidCondition{
          LiquidCondition::Kind::pressure, read_time_function(*pressure, Range::any())}};
    return std::optional<LiquidCondition>{LiquidCondition{
        LiquidCondition::Kind::suction, read_time_function(*suction, Range::non_negative())}};
  });
}

}  // namespace

Range gas_pressure_range(const Case& c) {
  if (std::holds_alternative<physics::IdealGas>(c.fluids.value().gas))
    return Range::open(-physics::IdealGas::atmospheric_pressure,
                       std::numeric_limits<double>::infinity());
  return Range::any();
}

TimeFunction read_time_function(const InputNode& node, const Range& values) {
  if (node.is_map())
    return node.read_map({"ramp", "table"}, [&](MapReader& m) {
      const auto ramp = m.optional("ramp");
      const auto table = m.optional("table");
      if (ramp && table) table->fail("give exactly one of ramp, table (both given)");
      if (!ramp && !table) m.node().fail("expected a number, {ramp: {...}} or {table: [...]}");
      return ramp ? read_ramp(*ramp, values) : read_table(*table, values);
    });
  if (node.is_sequence() || node.is_null())
    node.fail("expected a number, {ramp: {...}} or {table: [...]}, got " + node.describe());
  return TimeFunction{{TimePoint{0.0, node.as_double(values)}}};
}

namespace {

/// The elevations (against gravity, physics/hydrostatic.hpp) of the grid's lowest and highest
/// corners, and |g|.
std::array<double, 3> grid_elevations(const Case& c) {
  double g2 = 0.0;
  for (const double v : c.gravity) g2 += v * v;
  const double g = std::sqrt(g2);
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (int corner = 0; corner < (1 << c.dimension); ++corner) {
    double z = 0.0;
    for (int d = 0; d < c.dimension; ++d)
      z -= c.gravity[d] / g * (c.grid.origin[d] + ((corner >> d) & 1 ? c.grid.size[d] : 0.0));
    lo = std::min(lo, z), hi = std::max(hi, z);
  }
  return {lo, hi, g};
}

/// `water_table: {elevation, max_suction}` with the body's gas pressure at the table; the
/// pressures it gives must exist over the whole grid.
physics::WaterTable read_water_table(const InputNode& node, double gas_pressure, const Case& c) {
  const auto [lo, hi, g] = grid_elevations(c);
  if (!(g > 0.0))
    node.fail("a water table needs gravity: the pressures are at rest under it (gravity is zero)");
  return node.read_map({"elevation", "max_suction"}, [&](MapReader& m) {
    const InputNode elevation = m.required("elevation");
    physics::WaterTable w{elevation.as_double(), gas_pressure,
                          m.required_double("max_suction", Range::non_negative())};
    for (const double z : {lo, hi}) {
      const auto p = physics::water_table_pressures(c.fluids->liquid, c.fluids->gas, w, g, z);
      if (!std::isfinite(p.liquid))
        elevation.fail("the liquid cannot be at rest " + format_number(w.elevation - z) +
                       " m below its table: its bulk modulus allows at most " +
                       format_number(c.fluids->liquid.bulk_modulus /
                                     (c.fluids->liquid.density(gas_pressure) * g)) +
                       " m");
      if (!gas_pressure_range(c).contains(p.gas))
        elevation.fail("the gas at rest would reach an absolute pressure <= 0 at elevation " +
                       format_number(z) + " m of the grid");
    }
    return w;
  });
}

}  // namespace

InitialPressures read_initial_state(const InputNode& node, const Case& c) {
  return node.read_map(
      {"liquid_pressure", "suction", "water_table", "gas_pressure"}, [&](MapReader& m) {
        const auto liquid = m.optional("liquid_pressure");
        const auto suction = m.optional("suction");
        const auto table = m.optional("water_table");
        if ((liquid ? 1 : 0) + (suction ? 1 : 0) + (table ? 1 : 0) > 1)
          (table ? *table : *suction)
              .fail("give exactly one of liquid_pressure, suction, water_table (more given)");
        if (!liquid && !suction && !table)
          m.node().fail("expected one of liquid_pressure, suction, water_table");
        const double gas = m.required_double("gas_pressure", gas_pressure_range(c));
        if (table) return InitialPressures{gas, gas, read_water_table(*table, gas, c)};
        if (liquid && liquid->is_map())
          return liquid->read_map({"table"}, [&](MapReader& t) {
            if (!(grid_elevations(c)[2] > 0.0))
              t.node().fail(
                  "a table against elevation needs gravity (elevation is measured against "
                  "it; gravity is zero)");
            InitialPressures p{gas, gas};
            p.liquid_profile = read_table(t.required("table"), Range::any(), "elevation");
            return p;
          });
        if (liquid) return InitialPressures{liquid->as_double(), gas};
        return InitialPressures{gas - suction->as_double(Range::non_negative()), gas};
      });
}

SurfaceSpec parse_free_surface(const InputNode& node, const Case& c) {
  return node.read_map({"liquid", "gas"}, [&](MapReader& m) {
    SurfaceSpec surface;
    const auto liquid = m.optional("liquid");
    const auto gas = m.optional("gas");
    if (!liquid && !gas) m.node().fail("expected at least one of liquid, gas");
    if (liquid) surface.liquid = read_liquid(*liquid, &surface.rainfall);
    if (gas)
      surface.gas_pressure = gas->read_map({"pressure"}, [&](MapReader& g) {
        return read_time_function(g.required("pressure"), gas_pressure_range(c));
      });
    if (surface.liquid && surface.liquid->kind == LiquidCondition::Kind::suction && !gas)
      liquid->fail(
          "a suction condition needs a gas condition on the free surface too (the liquid "
          "pressure is the gas pressure minus the suction); add gas: {pressure: ...}");
    if (surface.rainfall && !gas)
      liquid->fail(
          "rainfall needs a gas condition on the free surface too (a ponded node holds zero "
          "suction: the liquid pressure equals the gas pressure); add gas: {pressure: ...}");
    if (surface.rainfall && gravity_axis(c) < 0)
      liquid->fail("rainfall falls along gravity, which must then point along one grid axis");
    return surface;
  });
}

void read_fluid_conditions(MapReader& m, const Case& c, const std::vector<BoundarySpec>& earlier,
                           BoundarySpec& boundary) {
  const auto liquid = m.optional("liquid");
  const auto gas = m.optional("gas");
  if (liquid) {
    boundary.liquid = read_liquid(*liquid);  // never empty without a rainfall pointer
    require_outer_face(*liquid, "liquid", boundary.region, c);
    require_first_on_face(*liquid, "liquid", boundary, earlier, c,
                          [](const BoundarySpec& b) { return b.liquid.has_value(); });
  }
  if (gas) {
    boundary.gas_pressure = gas->read_map({"pressure"}, [&](MapReader& g) {
      return read_time_function(g.required("pressure"), gas_pressure_range(c));
    });
    require_outer_face(*gas, "gas", boundary.region, c);
    require_first_on_face(*gas, "gas", boundary, earlier, c,
                          [](const BoundarySpec& b) { return b.gas_pressure.has_value(); });
  }
  if (boundary.liquid && boundary.liquid->kind == LiquidCondition::Kind::suction && !gas)
    liquid->fail(
        "a suction condition needs a gas condition on the same boundary (the liquid "
        "pressure is the gas pressure minus the suction); add gas: {pressure: ...}");
}

}  // namespace unsatmpm::case_sections

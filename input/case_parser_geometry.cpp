// The case reader: the `bodies` and `boundaries` sections, with their geometric checks (inside
// the grid, boxes with max > min, simple polygons of non-zero area, planes on grid node planes).
// Their three-phase keys (initial_state, liquid, gas) are read in case_parser_hydraulics.cpp.
#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "input/case_parser_sections.hpp"

namespace unsatmpm::case_sections {

namespace {

using Point2 = std::array<double, 2>;

double orientation(const Point2& a, const Point2& b, const Point2& c) {
  return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

/// q on the segment [p, r], given p, q, r collinear.
bool within(const Point2& p, const Point2& q, const Point2& r) {
  return std::min(p[0], r[0]) <= q[0] && q[0] <= std::max(p[0], r[0]) &&
         std::min(p[1], r[1]) <= q[1] && q[1] <= std::max(p[1], r[1]);
}

/// Closed segments [a, b] and [c, d] share at least one point.
bool segments_touch(const Point2& a, const Point2& b, const Point2& c, const Point2& d) {
  const double o1 = orientation(c, d, a), o2 = orientation(c, d, b);
  const double o3 = orientation(a, b, c), o4 = orientation(a, b, d);
  if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0)))
    return true;
  return (o1 == 0 && within(c, a, d)) || (o2 == 0 && within(c, b, d)) ||
         (o3 == 0 && within(a, c, b)) || (o4 == 0 && within(a, d, b));
}

std::string edge_text(std::size_t i, std::size_t n) {
  return "edge " + std::to_string(i) + " (vertices " + std::to_string(i) + "-" +
         std::to_string((i + 1) % n) + ")";
}

/// Fails unless the closed polygon has distinct consecutive vertices, no edge folding back onto
/// its neighbour, no two other edges touching, and a non-zero area. O(n^2) edge pairs.
void require_simple_polygon(const InputNode& where, const std::vector<Point2>& v) {
  const std::size_t n = v.size();
  double twice_area = 0.0, extent = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const Point2 &a = v[i], &b = v[(i + 1) % n], &c = v[(i + 2) % n];
    if (a == b)
      where.fail("vertices " + std::to_string(i) + " and " + std::to_string((i + 1) % n) +
                 " coincide");
    if (orientation(a, b, c) == 0 &&
        (b[0] - a[0]) * (c[0] - b[0]) + (b[1] - a[1]) * (c[1] - b[1]) < 0)
      where.fail(edge_text((i + 1) % n, n) + " folds back onto " + edge_text(i, n));
    twice_area += a[0] * b[1] - b[0] * a[1];
    extent = std::max({extent, std::abs(a[0] - b[0]), std::abs(a[1] - b[1])});
  }
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;  // neighbours through vertex 0
      if (segments_touch(v[i], v[(i + 1) % n], v[j], v[(j + 1) % n]))
        where.fail(edge_text(i, n) + " and " + edge_text(j, n) +
                   " intersect: the polygon must be simple");
    }
  if (std::abs(twice_area) <= 1e-12 * extent * extent) where.fail("the polygon has zero area");
}

BoxGeometry parse_box(const InputNode& node, const Case& c) {
  return node.read_map({"min", "max"}, [&](MapReader& m) {
    const InputNode min = m.required("min"), max = m.required("max");
    BoxGeometry box{read_vector(min, c.dimension), read_vector(max, c.dimension)};
    for (int d = 0; d < c.dimension; ++d)
      if (box.max[d] <= box.min[d])
        max.fail("max must exceed min along every axis; along " + axis_names[d] + ": " +
                 format_number(box.max[d]) + " <= " + format_number(box.min[d]));
    require_inside_grid(min, box.min, c);
    require_inside_grid(max, box.max, c);
    return box;
  });
}

std::array<double, 2> read_extrusion(const InputNode& node, const Case& c) {
  const std::vector<double> z = node.as_vector(2);
  if (z[1] <= z[0])
    node.fail("expected [z_min, z_max] with z_max > z_min, got [" + format_number(z[0]) + ", " +
              format_number(z[1]) + "]");
  const double tol = 1e-9 * grid_spacing(c.grid, 2);
  const double lo = c.grid.origin[2], hi = lo + c.grid.size[2];
  if (z[0] < lo - tol || z[1] > hi + tol)
    node.fail("the extrusion lies outside the grid's z range [" + format_number(lo) + ", " +
              format_number(hi) + "]");
  return {z[0], z[1]};
}

PolygonGeometry parse_polygon(const InputNode& node, const Case& c) {
  if (c.dimension == 1) node.fail("a polygon is not allowed in 1D; use box");
  return node.read_map({"vertices", "extrude_z"}, [&](MapReader& m) {
    PolygonGeometry polygon;
    const InputNode vertices = m.required("vertices");
    if (vertices.is_sequence() && vertices.size() < 3)
      vertices.fail("a polygon needs at least 3 vertices, got " + std::to_string(vertices.size()));
    for (const InputNode& vertex : vertices.items(3)) {
      const std::vector<double> xy = vertex.as_vector(2);
      require_inside_grid(vertex, xy, c);
      polygon.vertices.push_back({xy[0], xy[1]});
    }
    require_simple_polygon(vertices, polygon.vertices);
    const auto extrusion = m.optional("extrude_z");
    if (extrusion && c.dimension != 3)
      extrusion->fail("extrude_z is allowed only in 3D (dimension is " +
                      std::to_string(c.dimension) + ")");
    if (!extrusion && c.dimension == 3)
      m.node().fail("missing required key 'extrude_z' (a polygon needs it in 3D)");
    if (extrusion) polygon.extrude_z = read_extrusion(*extrusion, c);
    return polygon;
  });
}

Geometry parse_geometry(MapReader& m, const Case& c) {
  const auto box = m.optional("box");
  const auto polygon = m.optional("polygon");
  if (box && polygon) polygon->fail("give exactly one of box, polygon (both given)");
  if (!box && !polygon) m.node().fail("missing geometry: give exactly one of box, polygon");
  if (box) return parse_box(*box, c);
  return parse_polygon(*polygon, c);
}

SineVelocity parse_sine(const InputNode& node, const Case& c) {
  return node.read_map({"amplitude", "axis", "wavenumber", "origin"}, [&](MapReader& m) {
    SineVelocity sine;
    sine.amplitude = read_vector(m.required("amplitude"), c.dimension);
    sine.axis = read_axis(m.required("axis"), c.dimension);
    sine.wavenumber = m.required_double("wavenumber");
    sine.origin = m.optional_double("origin", 0.0);
    return sine;
  });
}

InitialVelocity parse_velocity(const InputNode& node, const Case& c) {
  if (node.is_sequence()) return read_vector(node, c.dimension);
  if (!node.is_map())
    node.fail("expected a list of " + std::to_string(c.dimension) +
              " numbers or {sine: {...}}, got " + node.describe());
  return node.read_map({"sine"}, [&](MapReader& m) { return parse_sine(m.required("sine"), c); });
}

int find_material(const InputNode& node, const std::vector<MaterialSpec>& materials) {
  const std::string name = node.as_string();
  std::string known;
  for (std::size_t i = 0; i < materials.size(); ++i) {
    if (materials[i].name == name) return static_cast<int>(i);
    known += (i ? ", " : "") + materials[i].name;
  }
  node.fail("unknown material '" + name + "'; known materials: " + known);
}

/// A uniform initial state must leave the soil some water: where the retention law gives S_l = 0
/// (the linear law past 1 / a_s with no residual saturation) the liquid's mass holds no pressure,
/// and the first step fails with a message that does not name the cause. (Not checked here: a
/// water table's or a table's pressures, which vary over the body.)
void require_some_water(const InputNode& state, const InitialPressures& p,
                        const MaterialSpec& material) {
  if (p.water_table || p.liquid_profile || !material.hydraulic) return;
  const double s = p.gas_pressure - p.liquid_pressure;
  const double s_l =
      std::visit([&](const auto& law) { return law.saturation(s); }, material.hydraulic->retention);
  if (!(s_l > 0.0))
    state.fail(
        "a suction of " + format_number(s) + " Pa leaves no water in material '" + material.name +
        "' (its retention law gives S_l = 0 there), and a soil without water has no "
        "liquid pressure to start from: give a smaller suction, or the law a "
        "residual_saturation above 0 (a linear law's a_s is per Pa: 1e-3 1/kPa = 1e-6 1/Pa)");
}

BodySpec read_body(MapReader& m, const Case& c, std::vector<std::pair<std::string, int>>& names) {
  BodySpec body;
  const InputNode name = m.required("name");
  body.name = name.as_string();
  require_unique_name(name, body.name, "body", names);
  body.material = find_material(m.required("material"), c.materials);
  body.points_per_cell = m.required_int("points_per_cell", 1, 6);
  body.geometry = parse_geometry(m, c);
  const auto velocity = m.optional("initial_velocity");
  body.initial_velocity = velocity ? parse_velocity(*velocity, c)
                                   : InitialVelocity(std::vector<double>(c.dimension, 0.0));
  if (c.phases == Phases::solid_liquid_gas) {
    const InputNode state = m.required("initial_state");
    body.initial_pressures = read_initial_state(state, c);
    require_some_water(state, *body.initial_pressures, c.materials[body.material]);
  }
  if (const auto stress = m.optional("initial_stress"))
    body.k0 = stress->read_map({"k0"}, [&](MapReader& s) {
      if (!std::holds_alternative<BoxGeometry>(body.geometry))
        s.node().fail(
            "K0 stresses need a horizontal top surface: give the body as a box (a polygon's top "
            "is not known to be horizontal)");
      if (gravity_axis(c) < 0)
        s.node().fail(
            "K0 stresses need gravity along one grid axis (the box's top is then horizontal)");
      return s.required_double("k0", Range::open_closed(0.0, 10.0));
    });
  return body;
}

PlaneRegion parse_plane(const InputNode& node, const Case& c) {
  return node.read_map({"axis", "at"}, [&](MapReader& m) {
    PlaneRegion plane;
    plane.axis = read_axis(m.required("axis"), c.dimension);
    const InputNode at = m.required("at");
    plane.coordinate = at.as_double();
    const double h = grid_spacing(c.grid, plane.axis), origin = c.grid.origin[plane.axis];
    const double cells = c.grid.cells[plane.axis];
    const double k = std::round((plane.coordinate - origin) / h);
    const std::string where = axis_names[plane.axis] + " = " + format_number(plane.coordinate);
    const double end = origin + c.grid.size[plane.axis];
    if (k < 0 || k > cells || plane.coordinate < origin - 1e-9 * h ||
        plane.coordinate > end + 1e-9 * h)
      at.fail("plane " + where + " lies outside the grid [" + format_number(origin) + ", " +
              format_number(end) + "]");
    if (std::abs(plane.coordinate - (origin + k * h)) > 1e-9 * h) {
      const double below = origin + std::floor((plane.coordinate - origin) / h) * h;
      at.fail("plane " + where + " is not on a grid node plane (nearest: " + format_number(below) +
              " and " + format_number(below + h) + "; spacing " + format_number(h) + ")");
    }
    return plane;
  });
}

/// `traction: {normal: F, shear: {axis: a, value: F}}` of a boundary on `plane` (the shear's axis
/// lies in the plane).
TractionSpec read_traction(const InputNode& node, const PlaneRegion& plane, const Case& c) {
  return node.read_map({"normal", "shear"}, [&](MapReader& m) {
    TractionSpec t;
    t.where = node.location();
    t.normal = read_time_function(m.required("normal"), Range::any());
    if (const auto shear = m.optional("shear"))
      shear->read_map({"axis", "value"}, [&](MapReader& s) {
        const InputNode axis = s.required("axis");
        t.shear_axis = read_axis(axis, c.dimension);
        if (t.shear_axis == plane.axis)
          axis.fail("a shear traction acts in the plane: its axis must differ from the plane's (" +
                    axis_names[plane.axis] + ")");
        t.shear = read_time_function(s.required("value"), Range::any());
        return 0;
      });
    return t;
  });
}

bool on_same_plane(const PlaneRegion& a, const PlaneRegion& b, const Case& c) {
  return a.axis == b.axis &&
         std::abs(a.coordinate - b.coordinate) <= 1e-9 * grid_spacing(c.grid, a.axis);
}

/// A traction acts on nodes that can move along it: not on a fixed plane, and its normal part not
/// on a roller (which holds the normal component). A rigid plate carries it.
void require_free_to_load(const BoundarySpec& loaded, const std::vector<BoundarySpec>& all,
                          const Case& c) {
  bool normal_load = false;
  for (const auto& p : loaded.traction->normal.points) normal_load = normal_load || p[1] != 0.0;
  for (const BoundarySpec& other : all) {
    if (!other.mechanical || !on_same_plane(other.region, loaded.region, c)) continue;
    if (*other.mechanical == MechanicalCondition::rigid_plate) continue;
    if (*other.mechanical == MechanicalCondition::fixed || normal_load)
      throw InputError(loaded.traction->where + ": boundary '" + loaded.name + "' loads plane " +
                       axis_names[loaded.region.axis] + " = " +
                       format_number(loaded.region.coordinate) + ", whose nodes boundary '" +
                       other.name + "' holds (" +
                       (*other.mechanical == MechanicalCondition::fixed ? "fixed" : "roller") +
                       "): the load would act on held nodes");
  }
}

/// Whether `other` prescribes the normal motion of rigid plate `plate`'s nodes: a fixed plane
/// crossing it or on it, or a roller or another plate on the same plane.
bool holds_plate_normal(const BoundarySpec& other, const BoundarySpec& plate, const Case& c) {
  if (!other.mechanical) return false;
  const bool same = on_same_plane(other.region, plate.region, c);
  return *other.mechanical == MechanicalCondition::fixed
             ? (same || other.region.axis != plate.region.axis)
             : same;
}

/// Refuses, at `boundary`'s `mechanical` key, a rigid plate whose normal motion another boundary
/// parsed before it prescribes, in either order.
void require_free_plates(const BoundarySpec& boundary, const std::vector<BoundarySpec>& before,
                         const InputNode& key, const Case& c) {
  const auto plane = [](const BoundarySpec& b) {
    return std::string(axis_names[b.region.axis]) + " = " + format_number(b.region.coordinate);
  };
  for (const BoundarySpec& other : before) {
    const bool plate_here = boundary.mechanical == MechanicalCondition::rigid_plate &&
                            holds_plate_normal(other, boundary, c);
    const bool plate_there = other.mechanical == MechanicalCondition::rigid_plate &&
                             holds_plate_normal(boundary, other, c);
    if (!plate_here && !plate_there) continue;
    const BoundarySpec& plate = plate_here ? boundary : other;
    const BoundarySpec& holder = plate_here ? other : boundary;
    key.fail("boundary '" + plate.name + "' is a rigid plate on plane " + plane(plate) +
             ", whose nodes' normal motion boundary '" + holder.name + "' (plane " + plane(holder) +
             ") also prescribes; a rigid plate needs that motion free");
  }
}

}  // namespace

std::vector<BodySpec> parse_bodies(const InputNode& node, const Case& c) {
  if (node.is_sequence() && node.size() == 0) node.fail("at least one body is required");
  std::vector<BodySpec> bodies;
  std::vector<std::pair<std::string, int>> names;
  const bool three_phase = c.phases == Phases::solid_liquid_gas;
  for (const InputNode& item : node.items(1))
    bodies.push_back(with_unknown_key_hint(item, {"initial_state"}, three_phase_hint, [&] {
      return item.read_map({"name", "material", "points_per_cell", "box", "polygon",
                            "initial_velocity", "initial_stress"},
                           [&](MapReader& m) {
                             if (three_phase) m.allow({"initial_state"});
                             return read_body(m, c, names);
                           });
    }));
  return bodies;
}

/// A boundary prescribes at least one thing: in a solid case `mechanical` is required; in a
/// three-phase case any of `mechanical`, `liquid`, `gas`.
std::vector<BoundarySpec> parse_boundaries(const InputNode& node, const Case& c) {
  std::vector<BoundarySpec> boundaries;
  std::vector<std::pair<std::string, int>> names;
  const bool three_phase = c.phases == Phases::solid_liquid_gas;
  const auto read = [&](MapReader& m) {
    if (three_phase) m.allow({"liquid", "gas"});
    const InputNode name = m.required("name");
    BoundarySpec boundary{name.as_string(), {}, std::nullopt};
    require_unique_name(name, boundary.name, "boundary", names);
    boundary.region = parse_plane(m.required("plane"), c);
    if (m.has("mechanical") || (!three_phase && !m.has("traction"))) {
      const InputNode key = m.required("mechanical");
      boundary.mechanical = key.as_enum(mechanical_names);
      require_free_plates(boundary, boundaries, key, c);
    }
    if (three_phase) read_fluid_conditions(m, c, boundaries, boundary);
    if (const auto traction = m.optional("traction"))
      boundary.traction = read_traction(*traction, boundary.region, c);
    if (!boundary.mechanical && !boundary.liquid && !boundary.gas_pressure && !boundary.traction)
      m.node().fail("boundary '" + boundary.name + "' prescribes nothing: give at least one of " +
                    (three_phase ? "mechanical, traction, liquid, gas" : "mechanical, traction"));
    return boundary;
  };
  for (const InputNode& item : node.items())
    boundaries.push_back(with_unknown_key_hint(item, {"liquid", "gas"}, three_phase_hint, [&] {
      return item.read_map({"name", "plane", "mechanical", "traction"}, read);
    }));
  for (const BoundarySpec& b : boundaries)
    if (b.traction) require_free_to_load(b, boundaries, c);
  return boundaries;
}

}  // namespace unsatmpm::case_sections

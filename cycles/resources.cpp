#include "cycles/resources.hpp"

#include <fmt/core.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <variant>

#include "numerics/geometry.hpp"

namespace unsatmpm {

namespace {

// The memory model (docs/input.md, "Resource limits"): peak resident memory of `unsatmpm run`
// measured on Release builds (GIMP, 1 to 9 points per cell, 1e4 to 3.6e5 points, one thread),
// rounded up. A bound for the safeguard, not a promise: within a factor of about 1.5.
constexpr double base_bytes = 20e6;  // the program and its libraries
// Per material point: solid only; the explicit three-phase cycle; the main cycle.
constexpr double point_bytes_solid = 700.0, point_bytes_three_phase = 1100.0,
                 point_bytes_main = 1700.0;
// Per grid node: the mechanics' nodal arrays, and per extra thread its scatter buffers.
constexpr double node_bytes_solid = 200.0, node_bytes_three_phase = 500.0;
constexpr double thread_node_bytes_solid = 50.0, thread_node_bytes_three_phase = 250.0;
// The main cycle's flow (pressure system, Jacobian pattern, LU factors) covers the cells the
// bodies occupy and grows faster than them: measured 75 MB at 10,000 occupied cells and 0.80 GB
// at 90,000 in 2D (exponent 1.08), 68 MB at 1,728 and 0.59 GB at 8,000 in 3D (exponent 1.41).
// 1D is bounded by the 2D rate per cell. Checked with UMFPACK (the scaling study's blocks,
// docs/performance.md): 2D, 298,764 unknowns, 2.42 GB measured against 2.53 GB estimated; 3D with
// the direct solver forced, 98,568 unknowns, 6.0 GB against 7.8 GB.
double flow_bytes(int dimension, double cells) {
  if (dimension == 3) return 68e6 * std::pow(cells / 1728.0, 1.41);
  if (dimension == 2) return 75e6 * std::pow(cells / 10000.0, 1.08);
  return 7.5e3 * cells;
}

// A polygon's points are counted one sample at a time up to this many samples in its bounding
// box (about 0.1 s); beyond, the bounding box's samples bound them.
constexpr double max_counted_samples = 2e7;

/// The sample coordinates (j + 1/2) h / k + origin (j = 0 .. cells k - 1) of one axis in
/// [lo, hi]: the first index and how many.
std::pair<double, double> samples_in(const GridSpec& g, int axis, int k, double lo, double hi) {
  const double step = g.size[axis] / g.cells[axis] / k;
  const double total = static_cast<double>(g.cells[axis]) * k;
  const double eps = 1e-9;
  const double first = std::max(0.0, std::ceil((lo - g.origin[axis]) / step - 0.5 - eps));
  const double last = std::min(total - 1.0, std::floor((hi - g.origin[axis]) / step - 0.5 + eps));
  return {first, last >= first ? last - first + 1.0 : 0.0};
}

/// A body's points: exact for a box (the samples inside it) and for a polygon whose bounding box
/// holds at most max_counted_samples samples, else at most those of that box. Overlaps with
/// earlier bodies are not subtracted (an upper bound).
double body_points(const GridSpec& g, int dimension, const BodySpec& b, bool& exact) {
  std::vector<double> lo(dimension), hi(dimension);
  const auto* poly = std::get_if<PolygonGeometry>(&b.geometry);
  if (const auto* box = std::get_if<BoxGeometry>(&b.geometry)) {
    lo = box->min, hi = box->max;
  } else {
    for (int d = 0; d < 2; ++d) {
      lo[d] = hi[d] = poly->vertices.front()[d];
      for (const auto& v : poly->vertices)
        lo[d] = std::min(lo[d], v[d]), hi[d] = std::max(hi[d], v[d]);
    }
    if (dimension == 3) lo[2] = (*poly->extrude_z)[0], hi[2] = (*poly->extrude_z)[1];
  }
  const int k = b.points_per_cell;
  std::vector<std::pair<double, double>> axes(dimension);
  double n = 1.0;
  for (int d = 0; d < dimension; ++d) {
    axes[d] = samples_in(g, d, k, lo[d], hi[d]);
    n *= axes[d].second;
  }
  if (!poly || n == 0.0) return n;
  if (n > max_counted_samples) {
    exact = false;
    return n;
  }
  // Count the x-y samples inside the polygon; the extrusion's z samples multiply them.
  const double hx = g.size[0] / g.cells[0] / k, hy = g.size[1] / g.cells[1] / k;
  const auto [x0, nx] = axes[0];
  const auto [y0, ny] = axes[1];
  double inside = 0.0;
  for (double i = x0; i < x0 + nx; ++i)
    for (double j = y0; j < y0 + ny; ++j)
      inside += numerics::inside_polygon(poly->vertices, g.origin[0] + hx * (i + 0.5),
                                         g.origin[1] + hy * (j + 0.5));
  return dimension == 3 ? inside * axes[2].second : inside;
}

}  // namespace

ResourceEstimate estimate_resources(const Case& c, int n_threads) {
  ResourceEstimate e;
  e.nodes = 1.0;
  for (int d = 0; d < c.dimension; ++d) e.nodes *= c.grid.cells[d] + 1.0;
  double most = -1.0, cells = 0.0;
  for (std::size_t b = 0; b < c.bodies.size(); ++b) {
    const double n = body_points(c.grid, c.dimension, c.bodies[b], e.points_exact);
    e.points += n;
    e.body_points.push_back(n);
    cells += n / std::pow(c.bodies[b].points_per_cell, c.dimension);
    if (n > most) most = n, e.largest_body = static_cast<int>(b);
  }
  const bool three_phase = c.phases == Phases::solid_liquid_gas;
  const bool main_cycle = three_phase && c.solver.cycle == Cycle::implicit_pressure;
  const double per_point = main_cycle    ? point_bytes_main
                           : three_phase ? point_bytes_three_phase
                                         : point_bytes_solid;
  const double per_node = (three_phase ? node_bytes_three_phase : node_bytes_solid) +
                          std::max(0, n_threads - 1) * (three_phase ? thread_node_bytes_three_phase
                                                                    : thread_node_bytes_solid);
  e.bytes = base_bytes + per_point * e.points + per_node * e.nodes +
            (main_cycle ? flow_bytes(c.dimension, cells) : 0.0);
  return e;
}

double default_memory_limit() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || page <= 0) return 8.0 * (1u << 30);
  return 0.8 * static_cast<double>(pages) * static_cast<double>(page);
}

std::string format_bytes(double bytes) {
  if (bytes >= 1e12) return fmt::format("{:.3g} TB", bytes / 1e12);
  if (bytes >= 1e9) return fmt::format("{:.3g} GB", bytes / 1e9);
  return fmt::format("{:.3g} MB", bytes / 1e6);
}

std::string describe_resources(const ResourceEstimate& e) {
  return fmt::format("about {} of memory ({:.0f} grid nodes, {}{:.0f} material points)",
                     format_bytes(e.bytes), e.nodes, e.points_exact ? "" : "at most ", e.points);
}

void require_resources(const Case& c, const InputNode& root, int n_threads, double limit_bytes) {
  const ResourceEstimate e = estimate_resources(c, n_threads);
  const auto bodies = root.find("bodies");
  const auto body_items =
      bodies && bodies->is_sequence() ? bodies->items() : std::vector<InputNode>{};
  for (std::size_t b = 0; b < c.bodies.size(); ++b) {
    if (e.body_points[b] > 0.0) continue;
    const std::string why = fmt::format(
        "body '{}' holds no material point: none of its sample points ({} per cell and direction, "
        "at the cell fractions (i + 1/2)/{}) lies inside it; enlarge it or refine the grid",
        c.bodies[b].name, c.bodies[b].points_per_cell, c.bodies[b].points_per_cell);
    if (b < body_items.size()) body_items[b].fail(why);
    throw InputError(c.file + ": bodies[" + std::to_string(b) + "]: " + why);
  }
  if (e.bytes <= limit_bytes) return;
  const std::string why = fmt::format(
      "the case needs {}; the limit is {} (by default 80 % of this machine's memory; "
      "--max-memory sets it, docs/input.md)",
      describe_resources(e), format_bytes(limit_bytes));
  Case nodes_only = c;
  nodes_only.bodies.clear();
  const bool grid_alone = estimate_resources(nodes_only, n_threads).bytes > limit_bytes;
  const auto grid = root.find("grid");
  if (grid_alone || c.bodies.empty()) {
    if (grid)
      if (const auto cells = grid->find("cells")) cells->fail(why);
    throw InputError(c.file + ": grid.cells: " + why);
  }
  if (e.largest_body < static_cast<int>(body_items.size()))
    if (const auto ppc = body_items[e.largest_body].find("points_per_cell")) ppc->fail(why);
  throw InputError(c.file + ": bodies: " + why);
}

}  // namespace unsatmpm

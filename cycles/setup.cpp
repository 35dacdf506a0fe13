#include "cycles/setup.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "cycles/initial_stress.hpp"
#include "input/input_node.hpp"
#include "numerics/geometry.hpp"

namespace unsatmpm {

using numerics::Grid;
using numerics::Vec;

template <int D>
Grid<D> make_grid(const Case& c) {
  Vec<D> origin, spacing;
  std::array<int, D> cells;
  for (int d = 0; d < D; ++d) {
    origin[d] = c.grid.origin[d];
    cells[d] = c.grid.cells[d];
    spacing[d] = c.grid.size[d] / c.grid.cells[d];
  }
  return Grid<D>(origin, spacing, cells);
}

namespace {

template <int D>
bool inside(const Geometry& g, const Vec<D>& x) {
  if (const auto* box = std::get_if<BoxGeometry>(&g)) {
    for (int d = 0; d < D; ++d)
      if (x[d] < box->min[d] || x[d] > box->max[d]) return false;
    return true;
  }
  const auto& poly = std::get<PolygonGeometry>(g);
  if constexpr (D == 3) {
    if (x[2] < (*poly.extrude_z)[0] || x[2] > (*poly.extrude_z)[1]) return false;
  }
  if constexpr (D >= 2) return numerics::inside_polygon(poly.vertices, x[0], x[1]);
  return false;  // the parser forbids polygons in 1D
}

template <int D>
Vec<D> initial_velocity(const InitialVelocity& iv, const Vec<D>& x) {
  Vec<D> v;
  if (const auto* constant = std::get_if<std::vector<double>>(&iv)) {
    for (int d = 0; d < D; ++d) v[d] = constant->empty() ? 0.0 : (*constant)[d];
    return v;
  }
  const auto& s = std::get<SineVelocity>(iv);
  const double f = std::sin(s.wavenumber * (x[s.axis] - s.origin));
  for (int d = 0; d < D; ++d) v[d] = s.amplitude[d] * f;
  return v;
}

/// Visits the k^D sample positions of every grid cell.
template <int D, class F>
void for_each_sample(const Grid<D>& grid, int k, F&& f) {
  const std::int64_t n_cells = grid.n_cells_total();
  const std::int64_t per_cell = static_cast<std::int64_t>(std::pow(k, D) + 0.5);
  for (std::int64_t cell = 0; cell < n_cells; ++cell) {
    std::array<int, D> ijk;
    std::int64_t rest = cell;
    for (int d = 0; d < D; ++d)
      ijk[d] = static_cast<int>(rest % grid.n_cells[d]), rest /= grid.n_cells[d];
    for (std::int64_t s = 0; s < per_cell; ++s) {
      Vec<D> x;
      std::int64_t r = s;
      for (int d = 0; d < D; ++d) {
        const int sub = static_cast<int>(r % k);
        r /= k;
        x[d] = grid.origin[d] + grid.spacing[d] * (ijk[d] + (sub + 0.5) / k);
      }
      f(x);
    }
  }
}

}  // namespace

template <int D>
PointSet<D> fill_bodies(const Case& c, const Grid<D>& grid) {
  numerics::MaterialPoints<D> raw;
  std::vector<int> raw_body;
  double cell_volume = 1.0;
  for (int d = 0; d < D; ++d) cell_volume *= grid.spacing[d];
  for (std::size_t b = 0; b < c.bodies.size(); ++b) {
    const BodySpec& body = c.bodies[b];
    const int k = body.points_per_cell;
    const double vol = cell_volume / std::pow(k, D);
    const double rho = c.materials[body.material].density;
    const Vec<D> half = grid.spacing / (2.0 * k);
    for_each_sample<D>(grid, k, [&](const Vec<D>& x) {
      if (!inside<D>(body.geometry, x)) return;
      for (std::size_t earlier = 0; earlier < b; ++earlier)
        if (inside<D>(c.bodies[earlier].geometry, x)) return;
      raw.push_back(body.material, x, half, rho * vol, vol);
      raw.velocity.back() = initial_velocity<D>(body.initial_velocity, x);
      raw_body.push_back(static_cast<int>(b));
    });
  }
  // Order by material (stable: keeps the generation order within a material).
  std::vector<std::int64_t> order(raw.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](auto a, auto b) { return raw.material[a] < raw.material[b]; });
  PointSet<D> out;
  out.points.reserve(raw.size());
  for (const auto p : order) {
    out.points.push_back(raw.material[p], raw.position[p], raw.half_size[p], raw.mass[p],
                         raw.volume[p]);
    out.points.velocity.back() = raw.velocity[p];
    out.body.push_back(raw_body[p]);
  }
  const int n_mat = static_cast<int>(c.materials.size());
  out.ranges.assign(n_mat + 1, 0);
  for (const int m : out.points.material) ++out.ranges[m + 1];
  std::partial_sum(out.ranges.begin(), out.ranges.end(), out.ranges.begin());
  // A body thinner than the sample spacing is refused before (require_resources, with its line);
  // here a body all of whose points lie in earlier-listed bodies.
  for (std::size_t b = 0; b < c.bodies.size(); ++b)
    if (std::find(out.body.begin(), out.body.end(), static_cast<int>(b)) == out.body.end())
      throw InputError(c.file + ": bodies[" + std::to_string(b) + "]: body '" + c.bodies[b].name +
                       "' holds no material point: its sample points all lie in bodies listed "
                       "before it");
  apply_k0_stresses<D>(c, out);
  return out;
}

template <int D>
void mark_boundaries(const Case& c, const Grid<D>& grid, std::vector<std::uint8_t>& fixed) {
  for (const BoundarySpec& bc : c.boundaries) {
    if (!bc.mechanical || *bc.mechanical == MechanicalCondition::rigid_plate) continue;
    const int axis = bc.region.axis;
    const double h = grid.spacing[axis];
    const std::uint8_t bits = *bc.mechanical == MechanicalCondition::fixed
                                  ? std::uint8_t((1u << D) - 1)
                                  : std::uint8_t(1u << axis);
    for (std::int64_t i = 0; i < grid.n_nodes(); ++i)
      if (std::abs(grid.node_position(i)[axis] - bc.region.coordinate) < 1e-9 * h) fixed[i] |= bits;
  }
}

template <int D>
std::vector<numerics::RigidPlate> make_rigid_plates(const Case& c, const Grid<D>& grid) {
  std::vector<numerics::RigidPlate> plates;
  for (const BoundarySpec& bc : c.boundaries) {
    if (bc.mechanical != MechanicalCondition::rigid_plate) continue;
    const int axis = bc.region.axis;
    const double h = grid.spacing[axis];
    numerics::RigidPlate plate{axis, {}};
    for (std::int64_t i = 0; i < grid.n_nodes(); ++i)
      if (std::abs(grid.node_position(i)[axis] - bc.region.coordinate) < 1e-9 * h)
        plate.nodes.push_back(i);
    plates.push_back(std::move(plate));
  }
  return plates;
}

#define UNSATMPM_INSTANTIATE(D)                                                                 \
  template Grid<D> make_grid<D>(const Case&);                                                   \
  template std::vector<numerics::RigidPlate> make_rigid_plates<D>(const Case&, const Grid<D>&); \
  template PointSet<D> fill_bodies<D>(const Case&, const Grid<D>&);                             \
  template void mark_boundaries<D>(const Case&, const Grid<D>&, std::vector<std::uint8_t>&);
UNSATMPM_INSTANTIATE(1)
UNSATMPM_INSTANTIATE(2)
UNSATMPM_INSTANTIATE(3)
#undef UNSATMPM_INSTANTIATE

}  // namespace unsatmpm

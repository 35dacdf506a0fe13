#include "cycles/tractions.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "input/input_node.hpp"

namespace unsatmpm {

namespace {

/// "x = 1.5": the plane as the messages name it.
std::string plane_text(const PlaneRegion& plane) {
  static const char* names[] = {"x", "y", "z"};
  return std::string(names[plane.axis]) + " = " + format_number(plane.coordinate);
}

/// The points within one cell of the plane, on each side: (below, above) counts.
template <int D>
std::array<std::int64_t, 2> sides(const PlaneRegion& plane, const numerics::Grid<D>& grid,
                                  const numerics::MaterialPoints<D>& mp) {
  const double h = grid.spacing[plane.axis];
  std::array<std::int64_t, 2> n{0, 0};
  for (std::size_t p = 0; p < mp.size(); ++p) {
    const double d = mp.position[p][plane.axis] - plane.coordinate;
    if (std::abs(d) <= h) ++n[d > 0.0 ? 1 : 0];
  }
  return n;
}

}  // namespace

template <int D>
BoundaryTractions<D>::BoundaryTractions(const Case& c, const numerics::Grid<D>& grid,
                                        const numerics::MaterialPoints<D>& mp)
    : grid_(grid) {
  for (const BoundarySpec& b : c.boundaries) {
    if (!b.traction) continue;
    const PlaneRegion& plane = b.region;
    const int axis = plane.axis;
    const auto n = sides<D>(plane, grid, mp);
    if (n[0] > 0 && n[1] > 0)
      throw InputError(b.traction->where + ": boundary '" + b.name +
                       "': material lies on both sides of plane " + plane_text(plane) +
                       " (within one cell); a traction acts on a body's surface");
    if (n[0] + n[1] == 0)
      throw InputError(b.traction->where + ": boundary '" + b.name +
                       "': no material point lies within one cell of plane " + plane_text(plane) +
                       ", so the traction would load nothing");
    const int plane_index =
        static_cast<int>(std::lround((plane.coordinate - grid.origin[axis]) / grid.spacing[axis]));
    Load load{&b, n[1] > 0 ? 1.0 : -1.0, plane_index, {}, {}, {}};

    // The in-plane directions and the raster of sub-cells over the plane.
    std::array<int, D> dims{}, count{};
    int m = 0;
    std::int64_t n_sub = 1;
    for (int e = 0; e < D; ++e)
      if (e != axis) {
        dims[m] = e;
        count[m] = grid.n_cells[e] * raster;
        n_sub *= count[m];
        ++m;
      }
    std::vector<char> covered(static_cast<std::size_t>(n_sub), m == 0 ? 1 : 0);
    for (std::size_t p = 0; p < mp.size() && m > 0; ++p) {
      if (std::abs(mp.position[p][axis] - plane.coordinate) > grid.spacing[axis]) continue;
      // Sub-cells whose centres the point's footprint covers, direction by direction.
      std::array<int, D> lo{}, hi{};
      bool any = true;
      for (int k = 0; k < m; ++k) {
        const int e = dims[k];
        const double s = grid.spacing[e] / raster;
        const double a = (mp.position[p][e] - mp.half_size[p][e] - grid.origin[e]) / s - 0.5;
        const double z = (mp.position[p][e] + mp.half_size[p][e] - grid.origin[e]) / s - 0.5;
        lo[k] = std::max(0, static_cast<int>(std::ceil(a)));
        hi[k] = std::min(count[k] - 1, static_cast<int>(std::floor(z)));
        any = any && lo[k] <= hi[k];
      }
      if (!any) continue;
      if (m == 1) {
        for (int i = lo[0]; i <= hi[0]; ++i) covered[i] = 1;
      } else {
        for (int j = lo[1]; j <= hi[1]; ++j)
          for (int i = lo[0]; i <= hi[0]; ++i) covered[i + std::int64_t(count[0]) * j] = 1;
      }
    }

    // A_i: each covered sub-cell's area shared among its cell's nodes on the plane by N_i.
    std::vector<double> area(grid.n_nodes(), 0.0);
    for (std::int64_t k = 0; k < n_sub; ++k) {
      if (!covered[k]) continue;
      std::array<int, D> sub{}, cell{};
      std::array<double, D> frac{};
      double a_sub = 1.0;
      std::int64_t rest = k;
      for (int q = 0; q < m; ++q) {
        sub[q] = static_cast<int>(rest % count[q]);
        rest /= count[q];
        cell[q] = sub[q] / raster;
        frac[q] = (sub[q] % raster + 0.5) / raster;  // position of the centre within its cell
        a_sub *= grid.spacing[dims[q]] / raster;
      }
      for (int corner = 0; corner < (1 << m); ++corner) {
        std::int64_t node = plane_index * grid.stride[axis];
        double w = a_sub;
        for (int q = 0; q < m; ++q) {
          const int up = (corner >> q) & 1;
          node += (cell[q] + up) * grid.stride[dims[q]];
          w *= up ? frac[q] : 1.0 - frac[q];
        }
        area[node] += w;
      }
    }
    std::int64_t n_plane = 1;
    for (int e = 0; e < D; ++e)
      if (e != axis) n_plane *= grid.n_cells[e] + 1;
    load.column_of.assign(static_cast<std::size_t>(n_plane), -1);
    for (std::int64_t i = 0; i < grid.n_nodes(); ++i)
      if (area[i] > 0.0) {
        load.column_of[plane_slot(axis, grid.node_ijk(i))] = static_cast<int>(load.nodes.size());
        load.nodes.push_back(i), load.area.push_back(area[i]);
      }
    loads_.push_back(std::move(load));
  }
}

template <int D>
std::int64_t BoundaryTractions<D>::plane_slot(int axis, const std::array<int, D>& j) const {
  std::int64_t slot = 0, stride = 1;
  for (int e = 0; e < D; ++e)
    if (e != axis) slot += j[e] * stride, stride *= grid_.n_cells[e] + 1;
  return slot;
}

template <int D>
template <class F>
void BoundaryTractions<D>::columns_seeing(const Load& load, const numerics::Vec<D>& y,
                                          F&& f) const {
  const int axis = load.spec->region.axis;
  // The in-plane nodes within one cell of y, direction by direction (at most two each).
  std::array<int, D> lo{}, hi{};
  for (int e = 0; e < D; ++e) {
    if (e == axis) continue;
    const double u = (y[e] - grid_.origin[e]) / grid_.spacing[e];
    lo[e] = std::max(0, static_cast<int>(std::floor(u)));
    hi[e] = std::min(grid_.n_cells[e], static_cast<int>(std::ceil(u)));
  }
  std::array<int, D> j = lo;
  while (true) {
    double w = 1.0;
    for (int e = 0; e < D; ++e)
      if (e != axis)
        w *= std::max(0.0, 1.0 - std::abs(y[e] - grid_.origin[e] - j[e] * grid_.spacing[e]) /
                                     grid_.spacing[e]);
    const int k = load.column_of[plane_slot(axis, j)];
    if (w > 0.0 && k >= 0) f(k, w);
    int e = 0;  // the next in-plane node index, odometer-wise
    for (; e < D; ++e) {
      if (e == axis) continue;
      if (j[e] < hi[e]) {
        ++j[e];
        break;
      }
      j[e] = lo[e];
    }
    if (e == D) return;
  }
}

template <int D>
void BoundaryTractions<D>::find_faces(const Load& load, const numerics::MaterialPoints<D>& mp) {
  const int axis = load.spec->region.axis;
  const double h = grid_.spacing[axis], plane = load.spec->region.coordinate;
  const std::size_t n = load.nodes.size();
  outer_.assign(n, unseen);
  filled_.assign(n, 0.0);
  // The cell of a point's centre, counted inward from the plane (one beyond it counts in the
  // plane's cell); -1: farther beyond the plane than a cell, not this face's material.
  const auto cell = [&](std::size_t p) {
    const double u = -load.inward * (mp.position[p][axis] - plane) / h;  // outward, in cells
    return u > 1.0 ? -1 : std::max(0, static_cast<int>(std::floor(-u)));
  };
  for (std::size_t p = 0; p < mp.size(); ++p)
    if (const int c = cell(p); c >= 0)
      columns_seeing(load, mp.position[p],
                     [&](int k, double) { outer_[k] = std::min(outer_[k], c); });
  for (std::size_t p = 0; p < mp.size(); ++p)
    if (const int c = cell(p); c >= 0)
      columns_seeing(load, mp.position[p], [&](int k, double w) {
        if (c == outer_[k]) filled_[k] += w * mp.volume[p];
      });
  for (std::size_t k = 0; k < n; ++k) filled_[k] = std::min(1.0, filled_[k] / (h * load.area[k]));
}

template <int D>
void BoundaryTractions<D>::forces(double t, const numerics::MaterialPoints<D>& mp,
                                  std::vector<numerics::NodalForce<D>>& out) {
  out.clear();
  unseen_.clear();
  for (const Load& load : loads_) {
    const TractionSpec& tr = *load.spec->traction;
    const int axis = load.spec->region.axis;
    const double normal = tr.normal(t) * load.inward;
    const double shear = tr.shear_axis >= 0 ? tr.shear(t) : 0.0;
    find_faces(load, mp);
    for (std::size_t k = 0; k < load.nodes.size(); ++k) {
      numerics::Vec<D> f = numerics::Vec<D>::Zero();
      f[axis] = normal * load.area[k];
      if (tr.shear_axis >= 0) f[tr.shear_axis] = shear * load.area[k];
      if (outer_[k] == unseen) {  // no point in sight: the plane's node keeps it
        out.push_back({load.nodes[k], f});
        unseen_.emplace_back(load.nodes[k], &load.spec->name);
        continue;
      }
      // The outer cell's nodes, m and m + 1 cells inward of the plane (within the grid).
      const auto node_at = [&](int cells_in) {
        const int j = load.plane_index + static_cast<int>(load.inward) * cells_in;
        return j < 0 || j > grid_.n_cells[axis]
                   ? std::int64_t{-1}
                   : load.nodes[k] + (j - load.plane_index) * grid_.stride[axis];
      };
      const std::int64_t outer = node_at(outer_[k]), inner = node_at(outer_[k] + 1);
      const double phi = inner < 0 ? 1.0 : filled_[k];
      if (outer >= 0 && phi > 0.0) out.push_back({outer, phi * f});
      if (inner >= 0 && phi < 1.0) out.push_back({inner, (1.0 - phi) * f});
    }
  }
}

template class BoundaryTractions<1>;
template class BoundaryTractions<2>;
template class BoundaryTractions<3>;

}  // namespace unsatmpm

// Structured background grid in 1, 2 or 3 dimensions (one code path templated on D).
//
// Nodes are numbered lexicographically, x fastest: index = i + nx (j + ny k), where nx, ny, nz
// are node counts. Cells are axis-aligned boxes of size `spacing` [m]. The grid is fixed in space
// (MPM): material points move through it.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>

namespace unsatmpm::numerics {

template <int D>
using Vec = Eigen::Matrix<double, D, 1>;

template <int D>
struct Grid {
  static_assert(D >= 1 && D <= 3);

  Vec<D> origin;                // lower corner [m]
  Vec<D> spacing;               // cell size per direction [m]
  std::array<int, D> n_cells;   // cells per direction
  std::array<int, D> n_nodes_;  // nodes per direction (n_cells + 1)
  std::array<std::int64_t, D> stride;

  Grid(const Vec<D>& origin_, const Vec<D>& spacing_, const std::array<int, D>& n_cells_)
      : origin(origin_), spacing(spacing_), n_cells(n_cells_) {
    std::int64_t s = 1;
    for (int d = 0; d < D; ++d) {
      if (n_cells[d] < 1) throw std::invalid_argument("grid needs at least one cell per direction");
      if (!(spacing[d] > 0.0) || !std::isfinite(spacing[d]))
        throw std::invalid_argument("grid spacing must be positive and finite");
      n_nodes_[d] = n_cells[d] + 1;
      stride[d] = s;
      s *= n_nodes_[d];
    }
  }

  std::int64_t n_nodes() const {
    std::int64_t n = 1;
    for (int d = 0; d < D; ++d) n *= n_nodes_[d];
    return n;
  }
  std::int64_t n_cells_total() const {
    std::int64_t n = 1;
    for (int d = 0; d < D; ++d) n *= n_cells[d];
    return n;
  }
  Vec<D> upper() const {
    Vec<D> u;
    for (int d = 0; d < D; ++d) u[d] = origin[d] + spacing[d] * n_cells[d];
    return u;
  }
  double min_spacing() const { return spacing.minCoeff(); }

  /// Integer node coordinates of a node index.
  std::array<int, D> node_ijk(std::int64_t index) const {
    std::array<int, D> ijk;
    for (int d = 0; d < D; ++d) {
      ijk[d] = static_cast<int>(index % n_nodes_[d]);
      index /= n_nodes_[d];
    }
    return ijk;
  }
  Vec<D> node_position(std::int64_t index) const {
    const auto ijk = node_ijk(index);
    Vec<D> x;
    for (int d = 0; d < D; ++d) x[d] = origin[d] + spacing[d] * ijk[d];
    return x;
  }
  /// True when x lies in the closed grid box.
  bool contains(const Vec<D>& x) const {
    for (int d = 0; d < D; ++d) {
      const double lo = origin[d], hi = origin[d] + spacing[d] * n_cells[d];
      if (!(x[d] >= lo && x[d] <= hi)) return false;  // also false for NaN
    }
    return true;
  }
};

}  // namespace unsatmpm::numerics

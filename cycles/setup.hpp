// From a parsed Case to the objects of a run: grid, material points, boundary masks.
//
// Points fill each body's cells with k^D points at the cell fractions (i + 1/2)/k; a point inside
// two bodies belongs to the first body listed. Points are then ordered by material so that every
// material owns one contiguous range (the hot loops are templated on the material's model).
#pragma once

#include <cstdint>
#include <vector>

#include "input/case.hpp"
#include "numerics/grid.hpp"
#include "numerics/material_points.hpp"
#include "numerics/nodal_state.hpp"
#include "numerics/rigid_plates.hpp"

namespace unsatmpm {

template <int D>
numerics::Grid<D> make_grid(const Case& c);

/// The case's gravity [m/s^2] as a vector of the grid's dimension.
template <int D>
numerics::Vec<D> gravity_vector(const Case& c) {
  numerics::Vec<D> g;
  for (int d = 0; d < D; ++d) g[d] = c.gravity[d];
  return g;
}

/// Material points of every body, ordered by material; `ranges[m]..ranges[m+1]` are material m's.
template <int D>
struct PointSet {
  numerics::MaterialPoints<D> points;
  std::vector<std::int64_t> ranges;  // size n_materials + 1
  std::vector<int> body;             // the body each point was generated in
};

template <int D>
PointSet<D> fill_bodies(const Case& c, const numerics::Grid<D>& grid);

/// Sets the per-node masks (bit d: velocity component d held) of fixed and roller conditions.
template <int D>
void mark_boundaries(const Case& c, const numerics::Grid<D>& grid,
                     std::vector<std::uint8_t>& fixed);

/// The rigid plates of the boundaries (`mechanical: rigid_plate`) with the nodes of their planes.
template <int D>
std::vector<numerics::RigidPlate> make_rigid_plates(const Case& c, const numerics::Grid<D>& grid);

}  // namespace unsatmpm
